// The narrowest read a lobe-table cell may make (--read-floor; read_floor.hpp).
#include "read_floor.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "ibl/brdf.hpp"
#include "ibl/conventions.hpp"
#include "ibl/prefilter_lod.hpp"

namespace iblab::accuracy {

namespace {

// Integrals over l of a lobe weighted by D(h), taken over h on a midpoint grid of the GGX
// half-vector sampling's (u, phi): with cos^2(theta_h) = (1 - u) / (1 + (alpha^2 - 1) u) the
// grid has density D(h) (n.h) in solid angle, so a sum of g(h) / (D(h) (n.h)) over it,
// divided by its size, is the integral of g over the hemisphere of h; and
// dOmega_l = 4 (v.h) dOmega_h. The grid follows the lobe however narrow it is.
constexpr int kGrid = 192;

template <typename Fn>
void forEachHalfVector(double alpha, const Fn& fn)
{
    const double a2 = alpha * alpha;
    for (int i = 0; i < kGrid; ++i) {
        const double u = (i + 0.5) / kGrid;
        const double cos2 = (1.0 - u) / (1.0 + (a2 - 1.0) * u);
        const double cosTheta = std::sqrt(cos2), sinTheta = std::sqrt(std::max(0.0, 1.0 - cos2));
        for (int j = 0; j < kGrid; ++j) {
            const double phi = 2.0 * kPi * (j + 0.5) / kGrid;
            fn(glm::dvec3(sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta));
        }
    }
}

constexpr double kGridPoints = double(kGrid) * double(kGrid);

// The prefilter's lobe around d (N = V = d) at a roughness, as a function of the angle theta
// between d and l: D(h) (d.l), h halfway, so n.h = cos(theta / 2); isotropic about d.
// Integrals of products of such lobes are 1-D: 2 pi integral f(theta) sin(theta) dtheta over
// theta in [0, pi / 2], on theta = (pi / 2) u^2 so that the narrowest lobe (roughness 0.1,
// about 0.02 radians) still spans hundreds of points.
constexpr int kAngles = 8192;

double prefilterLobeValue(double alpha, double theta)
{
    const double dl = std::cos(theta);
    return dl > 0.0 ? ggxD(std::cos(0.5 * theta), alpha) * dl : 0.0;
}

template <typename Fn>
double overAngles(const Fn& fn)
{
    double sum = 0.0;
    for (int i = 0; i < kAngles; ++i) {
        const double u = (i + 0.5) / kAngles;
        const double theta = 0.5 * kPi * u * u, dTheta = kPi * u / kAngles;
        sum += fn(theta) * std::sin(theta) * dTheta;
    }
    return 2.0 * kPi * sum;
}

// One mip's lobe, normalised to 1; mip 0 (the mirror) is a texel of the face, a box of
// solid angle `mirrorTexel` at d.
struct MipLobe {
    double alpha = 0.0; // 0: the mirror
    double norm = 1.0;
    double at(double theta) const { return prefilterLobeValue(alpha, theta) / norm; }
};

MipLobe mipLobe(const ReadChain& chain, int mip)
{
    MipLobe lobe;
    const double roughness = prefilterRoughnessFromMip(float(mip), float(chain.levels), chain.layout);
    if (mip == 0 || roughness <= 0.0) return lobe;
    lobe.alpha = roughness * roughness;
    lobe.norm = overAngles([&](double theta) { return prefilterLobeValue(lobe.alpha, theta); });
    return lobe;
}

// integral a b dOmega for two mips' lobes about the same direction.
double lobeProduct(const MipLobe& a, const MipLobe& b, double mirrorTexel)
{
    if (a.alpha == 0.0 && b.alpha == 0.0) return 1.0 / mirrorTexel;
    if (a.alpha == 0.0) return b.at(0.0);
    if (b.alpha == 0.0) return a.at(0.0);
    return overAngles([&](double theta) { return a.at(theta) * b.at(theta); });
}

} // namespace

double prefilterReadSolidAngle(double roughness, const ReadChain& chain)
{
    const double lod = prefilterMipFromRoughness(float(roughness), float(chain.levels), chain.layout);
    const int lo = std::clamp(int(std::floor(lod)), 0, chain.levels - 1), hi = std::min(lo + 1, chain.levels - 1);
    const double f = std::clamp(lod - lo, 0.0, 1.0);
    const double mirrorTexel = 4.0 * kPi / (6.0 * double(chain.faceSize) * double(chain.faceSize));
    const MipLobe a = mipLobe(chain, lo), b = mipLobe(chain, hi);
    const double squared = (1.0 - f) * (1.0 - f) * lobeProduct(a, a, mirrorTexel) + f * f * lobeProduct(b, b, mirrorTexel) +
                           2.0 * f * (1.0 - f) * lobeProduct(a, b, mirrorTexel);
    return 1.0 / squared;
}

SpecularLobeSolidAngles specularLobeSolidAngles(double NdotV, double roughness, GeometryTerm term)
{
    const double alpha = roughness * roughness;
    const glm::dvec3 v(std::sqrt(std::max(0.0, 1.0 - NdotV * NdotV)), 0.0, NdotV);
    double weightA = 0.0, weightB = 0.0, squaredA = 0.0, squaredB = 0.0;
    forEachHalfVector(alpha, [&](const glm::dvec3& h) {
        const double vh = glm::dot(v, h);
        if (vh <= 0.0) return;
        const glm::dvec3 l = 2.0 * vh * h - v;
        if (l.z <= 0.0) return;
        // The LUT's two terms as lobes over l: f (n.l) = D Vis (n.l) F, F = F0 (1 - s) + s.
        const double s = schlickWeight(vh);
        const double lobe = ggxD(h.z, alpha) * visibility(term, NdotV, l.z, alpha) * l.z; // f (n.l) without F
        const double jacobian = 4.0 * vh / (ggxD(h.z, alpha) * h.z);                      // dOmega_l over the grid's density
        weightA += lobe * (1.0 - s) * jacobian;
        weightB += lobe * s * jacobian;
        squaredA += lobe * lobe * (1.0 - s) * (1.0 - s) * jacobian;
        squaredB += lobe * lobe * s * s * jacobian;
    });
    // Each sum / kGridPoints; the ratio needs it once.
    return {weightA * weightA / (squaredA * kGridPoints), squaredB > 0.0 ? weightB * weightB / (squaredB * kGridPoints) : 0.0};
}

ReadRoughnessFloor readRoughnessFloor(double NdotV, double roughness, GeometryTerm term, const ReadChain& chain)
{
    // A read's solid angle grows with its roughness (between two mips the blend's square
    // shrinks as the weight moves to the wider one): bisect for the one that matches.
    auto roughnessFor = [&](double solidAngle) {
        double lo = 0.0, hi = roughness;
        if (solidAngle <= 0.0 || prefilterReadSolidAngle(hi, chain) <= solidAngle) return hi;
        for (int k = 0; k < 24; ++k) {
            const double mid = 0.5 * (lo + hi);
            (prefilterReadSolidAngle(mid, chain) < solidAngle ? lo : hi) = mid;
        }
        return hi;
    };
    const SpecularLobeSolidAngles exact = specularLobeSolidAngles(NdotV, roughness, term);
    return {roughnessFor(exact.a), roughnessFor(exact.b)};
}

} // namespace iblab::accuracy
