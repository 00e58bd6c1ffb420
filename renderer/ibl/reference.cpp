#include "ibl/reference.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <glm/geometric.hpp>

#include "ibl/equirect.hpp"

namespace iblab {

namespace {

struct Sums {
    glm::dvec3 weighted{0.0}; // sum L(w) * weight(w) * dOmega
    double weight = 0.0;      // sum weight(w) * dOmega
};

// Sums weightFn(direction) * {L, 1} * dOmega over all texels with weightFn(...) != 0.
// weightFn returns a per-channel weight (dvec3) so that Fresnel can differ by channel; the
// scalar `weight` sum uses its first channel.
template <typename WeightFn>
Sums sumOverTexels(const ImageRGB32F& env, const WeightFn& weightFn)
{
    auto sumRows = [&](int y0, int y1) {
        Sums s;
        for (int y = y0; y < y1; ++y) {
            const double dOmega = equirectTexelSolidAngle(y, env.width, env.height);
            Sums row;
            for (int x = 0; x < env.width; ++x) {
                const glm::dvec3 w = weightFn(equirectTexelDirection(x, y, env.width, env.height));
                if (w.x == 0.0 && w.y == 0.0 && w.z == 0.0)
                    continue;
                row.weighted += glm::dvec3(env.at(x, y)) * w;
                row.weight += w.x;
            }
            s.weighted += row.weighted * dOmega;
            s.weight += row.weight * dOmega;
        }
        return s;
    };

    // Threads pay off only above a few tens of thousands of texels (thread start ~ 20 us).
    constexpr std::size_t kTexelsPerThread = 1u << 15;
    const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
    const int threads = int(std::min<std::size_t>({std::size_t(hw), std::size_t(env.height),
                                                   env.texelCount() / kTexelsPerThread}));
    if (threads <= 1)
        return sumRows(0, env.height);

    std::vector<Sums> partial(static_cast<std::size_t>(threads));
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t) {
        const int y0 = env.height * t / threads;
        const int y1 = env.height * (t + 1) / threads;
        pool.emplace_back([&, t, y0, y1] { partial[std::size_t(t)] = sumRows(y0, y1); });
    }
    Sums total;
    for (int t = 0; t < threads; ++t) {
        pool[std::size_t(t)].join();
        total.weighted += partial[std::size_t(t)].weighted;
        total.weight += partial[std::size_t(t)].weight;
    }
    return total;
}

void requireEnvironment(const ImageRGB32F& env, const char* who)
{
    if (env.empty() || env.texels.size() != env.texelCount() * 3)
        throw std::invalid_argument(std::string(who) + ": empty or inconsistent environment (" +
                                    std::to_string(env.width) + "x" + std::to_string(env.height) + ")");
}

} // namespace

glm::dvec3 referenceIrradiance(const ImageRGB32F& env, glm::dvec3 n)
{
    requireEnvironment(env, "referenceIrradiance");
    return sumOverTexels(env, [&](glm::dvec3 w) { return glm::dvec3(std::max(0.0, glm::dot(n, w))); }).weighted;
}

// Why this is what the LearnOpenGL prefilter computes. Its loop draws half vectors h from
// D(h) (n.h) (sampling.hpp), reflects v = n about h to get l, and accumulates
//   sum_i L(l_i) (n.l_i)  /  sum_i (n.l_i)       over samples with n.l_i > 0.
// Each l_i has the solid-angle density p(l) = D(h) (n.h) / (4 (v.h)) (the reflection
// Jacobian), and with v = n we have n.h = v.h, so p(l) = D(h) / 4. By the law of large
// numbers numerator and denominator, each divided by the sample count, converge to
//   integral L(l) (n.l) D(h)/4 dOmega_l    and    integral (n.l) D(h)/4 dOmega_l,
// the 1/4 cancels, and h = normalize(n + l) is the half vector between v = n and l. Note the
// weight is D(h) (n.l), not the BRDF: the split-sum's first factor is this normalised
// D-weighted average by construction (Karis 2013, "we found weighting by cos(theta_l) achieves
// better results").
glm::dvec3 referencePrefilteredRadiance(const ImageRGB32F& env, glm::dvec3 n, double roughness)
{
    requireEnvironment(env, "referencePrefilteredRadiance");
    if (roughness <= 0.0)
        return glm::dvec3(sampleEquirectBilinear(env, n));
    const double alpha = roughness * roughness;
    const Sums s = sumOverTexels(env, [&](glm::dvec3 w) {
        const double NdotL = glm::dot(n, w);
        if (NdotL <= 0.0)
            return glm::dvec3(0.0);
        const glm::dvec3 h = glm::normalize(n + w);
        return glm::dvec3(ggxD(glm::dot(n, h), alpha) * NdotL);
    });
    // The lobe can fall between texel centres when it is much narrower than a texel; then
    // no texel carries weight and the bilinear lookup is the limit the sum would approach.
    if (!(s.weight > 0.0))
        return glm::dvec3(sampleEquirectBilinear(env, n));
    return s.weighted / s.weight;
}

glm::dvec3 referenceSpecular(const ImageRGB32F& env, glm::dvec3 n, glm::dvec3 v, double roughness, glm::dvec3 F0,
                             GeometryTerm term)
{
    requireEnvironment(env, "referenceSpecular");
    const double NdotV = glm::dot(n, v);
    if (NdotV <= 0.0)
        return glm::dvec3(0.0);
    const double alpha = roughness * roughness;
    return sumOverTexels(env, [&](glm::dvec3 w) {
               const double NdotL = glm::dot(n, w);
               if (NdotL <= 0.0)
                   return glm::dvec3(0.0);
               const glm::dvec3 h = glm::normalize(v + w);
               const double NdotH = std::max(0.0, glm::dot(n, h));
               const double VdotH = std::max(0.0, glm::dot(v, h));
               const double DV = ggxSpecularBrdf(term, NdotH, NdotV, NdotL, alpha);
               return fresnelSchlick(VdotH, F0) * (DV * NdotL);
           })
        .weighted;
}

ImageRGB32F downsampleEquirect2x(const ImageRGB32F& env)
{
    if (env.empty() || env.width % 2 != 0 || env.height % 2 != 0)
        throw std::invalid_argument("downsampleEquirect2x: dimensions must be even and non-zero, got " +
                                    std::to_string(env.width) + "x" + std::to_string(env.height));
    ImageRGB32F out(env.width / 2, env.height / 2);
    for (int y = 0; y < out.height; ++y) {
        const double w0 = equirectTexelSolidAngle(2 * y, env.width, env.height);
        const double w1 = equirectTexelSolidAngle(2 * y + 1, env.width, env.height);
        for (int x = 0; x < out.width; ++x) {
            const glm::dvec3 top = glm::dvec3(env.at(2 * x, 2 * y)) + glm::dvec3(env.at(2 * x + 1, 2 * y));
            const glm::dvec3 bottom =
                glm::dvec3(env.at(2 * x, 2 * y + 1)) + glm::dvec3(env.at(2 * x + 1, 2 * y + 1));
            out.set(x, y, glm::vec3((top * w0 + bottom * w1) / (2.0 * (w0 + w1))));
        }
    }
    return out;
}

ImageRGB32F downsampleEquirectToWidth(const ImageRGB32F& env, int maxWidth)
{
    ImageRGB32F out = env;
    while (out.width > maxWidth && out.width % 2 == 0 && out.height % 2 == 0) out = downsampleEquirect2x(out);
    return out;
}

double referenceMinResolvedRoughness(int width)
{
    return std::sqrt(1.5 * 2.0 * kPi / double(std::max(width, 1)));
}

} // namespace iblab
