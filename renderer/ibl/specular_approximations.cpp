#include "ibl/specular_approximations.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "ibl/equirect.hpp"
#include "ibl/parallel_rows.hpp"
#include "ibl/table_sampling.hpp"

namespace iblab {

namespace {

#include "ibl/specular_lobe_fit.inc"

glm::dvec3 reflectView(glm::dvec3 n, glm::dvec3 v)
{
    return 2.0 * glm::dot(n, v) * n - v;
}

} // namespace

// ---- LobeFitTable ----------------------------------------------------------------------

glm::dvec4 LobeFitTable::sample(double NdotV, double roughness, int plane) const
{
    if (cells.empty()) throw std::logic_error("LobeFitTable::sample on an empty table");
    return sampleTableBilinear(NdotV, roughness, nvSize, roughnessSize, [&](int col, int row) { return glm::dvec4(at(col, row, plane)); });
}

const LobeFitTable& fittedLobeTable()
{
    static const LobeFitTable table = [] {
        LobeFitTable t;
        t.taps = kLobeFitTaps;
        t.nvSize = kLobeFitNvSize;
        t.roughnessSize = kLobeFitRoughnessSize;
        t.minFittedRoughness = kLobeFitMinRoughness;
        const std::size_t n = std::size_t(t.nvSize) * std::size_t(t.roughnessSize) * std::size_t(t.planes());
        if (sizeof(kLobeFitCells) / sizeof(float) != 4 * n) throw std::logic_error("specular_lobe_fit.inc: the cell count does not match its layout");
        for (std::size_t i = 0; i < n; ++i)
            t.cells.emplace_back(kLobeFitCells[4 * i], kLobeFitCells[4 * i + 1], kLobeFitCells[4 * i + 2], kLobeFitCells[4 * i + 3]);
        return t;
    }();
    return table;
}

// ---- The methods -----------------------------------------------------------------------

std::string_view specularMethodName(SpecularMethod method)
{
    switch (method) {
    case SpecularMethod::SplitSum: return "split-sum";
    case SpecularMethod::FrostbiteDominant: return "frostbite-dd";
    case SpecularMethod::FrostbitePerceptual: return "frostbite-dd-perceptual";
    case SpecularMethod::FilamentDominant: return "filament-dd";
    case SpecularMethod::FittedLobe: return "fitted-lobe";
    }
    return "?";
}

std::vector<LobeTap> fittedLobeTaps(const LobeFitTable& fit, glm::dvec3 n, glm::dvec3 v, double roughness)
{
    const double NdotV = std::max(glm::dot(n, v), 1e-4);
    const glm::vec4 p(fit.sample(NdotV, roughness));
    const glm::vec3 N(n), R(reflectView(n, v));
    std::vector<LobeTap> taps;
    const int reads = fit.taps == 1 ? 1 : 2;
    for (int k = 0; k < reads; ++k) {
        LobeTap tap;
        tap.direction = glm::dvec3(shared::lobeTapDirection(N, R, shared::lobeTapTowardsNormal(p, fit.taps, k)));
        tap.roughness = shared::lobeTapRoughness(p, fit.taps, k);
        tap.weight = shared::lobeTapWeight(p, fit.taps, k);
        tap.multipliesB = fit.taps >= 3 && k == 1;
        taps.push_back(tap);
    }
    if (fit.taps == 4) {
        const glm::vec4 q(fit.sample(NdotV, roughness, 1));
        const double w = shared::lobeSecondAWeight(q);
        taps[0].weight = 1.0 - w;
        taps.push_back({glm::dvec3(shared::lobeTapDirection(N, R, shared::lobeSecondATowardsNormal(q))), shared::lobeSecondARoughness(q), w, false});
    }
    return taps;
}

glm::dvec3 shadeSpecularApproximation(SpecularMethod method, const SpecularShadingInputs& in, const PrefilteredLookup& prefiltered,
                                      const LobeFitTable* fit)
{
    const glm::dvec3 albedo = in.F0 * in.lut.x + in.lut.y;
    const glm::dvec3 R = reflectView(in.n, in.v);
    const double alpha = in.roughness * in.roughness;
    switch (method) {
    case SpecularMethod::SplitSum:
        return prefiltered(R, in.roughness) * albedo;
    case SpecularMethod::FrostbiteDominant:
        return prefiltered(glm::mix(in.n, R, double(shared::frostbiteDominantLerp(float(alpha)))), in.roughness) * albedo;
    case SpecularMethod::FrostbitePerceptual:
        return prefiltered(glm::mix(in.n, R, double(shared::frostbiteDominantLerp(float(in.roughness)))), in.roughness) * albedo;
    case SpecularMethod::FilamentDominant:
        return prefiltered(glm::mix(R, in.n, double(shared::filamentDominantTowardsNormal(float(alpha)))), in.roughness) * albedo;
    case SpecularMethod::FittedLobe: {
        const LobeFitTable& table = fit ? *fit : fittedLobeTable();
        const std::vector<LobeTap> taps = fittedLobeTaps(table, in.n, in.v, in.roughness);
        if (table.taps >= 3) {
            glm::dvec3 a(0.0), b(0.0);
            for (const LobeTap& tap : taps)
                if (tap.weight != 0.0) (tap.multipliesB ? b : a) += tap.weight * prefiltered(tap.direction, tap.roughness);
            return in.F0 * in.lut.x * a + in.lut.y * b;
        }
        glm::dvec3 sum(0.0);
        for (const LobeTap& tap : taps)
            if (tap.weight != 0.0) sum += tap.weight * prefiltered(tap.direction, tap.roughness);
        return sum * albedo;
    }
    }
    return glm::dvec3(0.0);
}

// ---- Prefiltered chain emulation ---------------------------------------------------------

ImageRGB32F prefilterEquirect(const ImageRGB32F& env, double roughness, int width)
{
    if (env.empty() || width < 2 || width % 2 != 0) throw std::invalid_argument("prefilterEquirect: need an environment and an even width");
    struct Texel {
        glm::dvec3 direction;
        glm::dvec3 radiance;
        double solidAngle;
    };
    std::vector<Texel> texels;
    texels.reserve(env.texelCount());
    for (int y = 0; y < env.height; ++y) {
        const double dOmega = equirectTexelSolidAngle(y, env.width, env.height);
        for (int x = 0; x < env.width; ++x) texels.push_back({equirectTexelDirection(x, y, env.width, env.height), glm::dvec3(env.at(x, y)), dOmega});
    }
    const int height = width / 2;
    ImageRGB32F out(width, height);
    const double alpha = roughness * roughness;
    parallelRows(height, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < width; ++x) {
                const glm::dvec3 n = equirectTexelDirection(x, y, width, height);
                if (roughness <= 0.0) {
                    out.set(x, y, sampleEquirectBilinear(env, n));
                    continue;
                }
                // With v = n the half vector's cosine needs no normalisation:
                // (n.h)^2 = (1 + n.l) / 2, and ggxD only needs (n.h)^2 (its denominator is
                // a2 (n.h)^2 + 1 - (n.h)^2), so the weight D(h) (n.l) costs one division.
                const double a2 = alpha * alpha;
                glm::dvec3 sum(0.0);
                double weight = 0.0;
                for (const Texel& t : texels) {
                    const double NdotL = glm::dot(n, t.direction);
                    if (NdotL <= 0.0) continue;
                    const double c = 0.5 * (1.0 + NdotL);
                    const double d = a2 * c + (1.0 - c);
                    const double w = NdotL * t.solidAngle / (d * d); // a2 / pi cancels in the ratio
                    sum += t.radiance * w;
                    weight += w;
                }
                out.set(x, y, weight > 0.0 ? glm::vec3(sum / weight) : sampleEquirectBilinear(env, n));
            }
    });
    return out;
}

PrefilteredChain::PrefilteredChain(const ImageRGB32F& env, int levels, int layout) : layout_(layout)
{
    if (levels < 1) throw std::invalid_argument("PrefilteredChain: levels >= 1");
    mips_.push_back(env);
    for (int m = 1; m < levels; ++m) {
        const double roughness = shared::prefilterRoughnessFromMip(float(m), float(levels), layout);
        const int width = std::max(32, std::min(env.width, 256 >> (m - 1)));
        mips_.push_back(prefilterEquirect(env, roughness, width));
    }
}

PrefilteredChain PrefilteredChain::fromMips(std::vector<ImageRGB32F> mips, int layout)
{
    if (mips.empty()) throw std::invalid_argument("PrefilteredChain::fromMips: no mips");
    PrefilteredChain c;
    c.mips_ = std::move(mips);
    c.layout_ = layout;
    return c;
}

glm::dvec3 PrefilteredChain::lookupLod(glm::dvec3 direction, double lod) const
{
    const double l = std::clamp(lod, 0.0, double(mips_.size() - 1));
    const int m0 = int(std::floor(l));
    const int m1 = std::min(m0 + 1, int(mips_.size()) - 1);
    const double t = l - m0;
    const glm::dvec3 a(sampleEquirectBilinear(mips_[std::size_t(m0)], direction));
    if (t <= 0.0 || m1 == m0) return a;
    const glm::dvec3 b(sampleEquirectBilinear(mips_[std::size_t(m1)], direction));
    return a * (1.0 - t) + b * t;
}

glm::dvec3 PrefilteredChain::lookup(glm::dvec3 direction, double roughness) const
{
    return lookupLod(direction, shared::prefilterMipFromRoughness(float(roughness), float(mips_.size()), layout_));
}

// ---- Full integral -----------------------------------------------------------------------

ReferenceSums::ReferenceSums(const ImageRGB32F& env) : width_(env.width)
{
    if (env.empty()) throw std::invalid_argument("ReferenceSums: empty environment");
    texels_.reserve(env.texelCount());
    for (int y = 0; y < env.height; ++y) {
        const double dOmega = equirectTexelSolidAngle(y, env.width, env.height);
        for (int x = 0; x < env.width; ++x)
            // A black texel adds nothing; skipping it makes a sparse map (lights alone) cheap.
            if (env.at(x, y) != glm::vec3(0.0f)) texels_.push_back({equirectTexelDirection(x, y, env.width, env.height), glm::dvec3(env.at(x, y)) * dOmega});
    }
}

ReferenceSums::ReferenceSums(const std::vector<ShadingLight>& lights)
{
    for (const ShadingLight& light : lights) texels_.push_back({glm::dvec3(light.direction), glm::dvec3(light.flux)});
}

FullIntegral ReferenceSums::evaluate(glm::dvec3 n, glm::dvec3 v, double roughness, GeometryTerm term, bool withIrradiance) const
{
    FullIntegral r;
    const double NdotVRaw = glm::dot(n, v);
    const double NdotV = std::max(NdotVRaw, 1e-4);
    const double alpha = std::max(roughness * roughness, 1e-3);
    // h = (v + l) / |v + l| with |v + l| = sqrt(2 + 2 v.l): n.h and v.h without forming h.
    for (const Texel& t : texels_) {
        const double NdotL = glm::dot(n, t.direction);
        if (NdotL <= 0.0) continue;
        if (withIrradiance) r.irradiance += t.radianceTimesSolidAngle * NdotL;
        const double VdotL = glm::dot(v, t.direction);
        const double len2 = 2.0 + 2.0 * VdotL;
        if (!(len2 > 0.0)) continue; // l = -v: h undefined, and n.l > 0 with n.v > 0 cannot hold
        const double inv = 1.0 / std::sqrt(len2);
        const double NdotH = std::max(0.0, (NdotVRaw + NdotL) * inv);
        const double VdotH = std::max(0.0, (1.0 + VdotL) * inv);
        const double w = ggxSpecularBrdf(term, NdotH, NdotV, NdotL, alpha) * NdotL;
        const double Fc = schlickWeight(VdotH);
        r.Ia += t.radianceTimesSolidAngle * (w * (1.0 - Fc));
        r.Ib += t.radianceTimesSolidAngle * (w * Fc);
    }
    return r;
}

} // namespace iblab
