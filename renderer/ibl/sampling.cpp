#include "ibl/sampling.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "ibl/brdf.hpp"
#include "ibl/conventions.hpp"

namespace iblab {

namespace {

// phi in [0, 2 pi) -> u in [0, 1). atan2 returns (-pi, pi]; fold the negative half up.
double azimuthToU(double x, double y)
{
    double phi = std::atan2(y, x);
    if (phi < 0.0)
        phi += 2.0 * kPi;
    const double u = phi / (2.0 * kPi);
    return u >= 1.0 ? 0.0 : u;
}

glm::dvec3 fromSphericalCos(double cosTheta, double u)
{
    const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
    const double phi = 2.0 * kPi * u;
    return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}

} // namespace

double radicalInverseVdC(std::uint32_t bits)
{
    // Swap halves, then pairs of bytes, nibbles, bit pairs and bits: a 32-bit reversal.
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return double(bits) * 0x1p-32;
}

glm::dvec2 hammersley(std::uint32_t i, std::uint32_t n)
{
    return {double(i) / double(n), radicalInverseVdC(i)};
}

glm::dvec3 sampleGgxHalfVector(glm::dvec2 u, double alpha)
{
    const double a2 = alpha * alpha;
    const double cos2 = (1.0 - u.y) / (1.0 + (a2 - 1.0) * u.y);
    return fromSphericalCos(std::sqrt(std::clamp(cos2, 0.0, 1.0)), u.x);
}

double pdfGgxHalfVector(glm::dvec3 h, double alpha)
{
    if (h.z <= 0.0)
        return 0.0;
    return ggxD(h.z, alpha) * h.z;
}

glm::dvec2 invertGgxHalfVector(glm::dvec3 h, double alpha)
{
    const double a2 = alpha * alpha;
    const double cos2 = h.z * h.z;
    // sin^2 from the tangent components rather than 1 - cos^2: no cancellation near the pole.
    const double sin2 = h.x * h.x + h.y * h.y;
    const double uy = sin2 / (1.0 + cos2 * (a2 - 1.0));
    return {azimuthToU(h.x, h.y), std::clamp(uy, 0.0, 1.0)};
}

double pdfGgxReflected(double pdfHalfVector, double VdotH)
{
    const double a = std::abs(VdotH);
    return a > 0.0 ? pdfHalfVector / (4.0 * a) : 0.0;
}

glm::dvec3 sampleCosineHemisphere(glm::dvec2 u)
{
    return fromSphericalCos(std::sqrt(std::max(0.0, 1.0 - u.y)), u.x);
}

double pdfCosineHemisphere(glm::dvec3 w)
{
    return w.z > 0.0 ? w.z / kPi : 0.0;
}

glm::dvec2 invertCosineHemisphere(glm::dvec3 w)
{
    return {azimuthToU(w.x, w.y), std::clamp(w.x * w.x + w.y * w.y, 0.0, 1.0)};
}

glm::dvec3 sampleUniformSphere(glm::dvec2 u)
{
    return fromSphericalCos(1.0 - 2.0 * u.y, u.x);
}

double pdfUniformSphere()
{
    return 1.0 / (4.0 * kPi);
}

glm::dvec2 invertUniformSphere(glm::dvec3 w)
{
    return {azimuthToU(w.x, w.y), std::clamp(0.5 * (1.0 - w.z), 0.0, 1.0)};
}

glm::dvec3 Frame::toLocal(glm::dvec3 world) const
{
    return {glm::dot(world, t), glm::dot(world, b), glm::dot(world, n)};
}

Frame tangentFrame(glm::dvec3 n)
{
    const double sign = std::copysign(1.0, n.z);
    const double a = -1.0 / (sign + n.z);
    const double b = n.x * n.y * a;
    return Frame{
        glm::dvec3(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        glm::dvec3(b, sign + n.y * n.y * a, -n.y),
        n,
    };
}

} // namespace iblab
