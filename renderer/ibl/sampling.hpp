#pragma once
// Samplers as pbrt-style triplets: sample (unit square -> direction), pdf (density of that
// direction w.r.t. solid angle) and invert (direction -> the unit-square point that maps to
// it). The triplet makes the round trip testable and lets a caller weight a sample it did
// not draw itself (MIS, or checking a GPU sample against the CPU).
//
// All directions are in a local frame whose +z is the normal (tangentFrame maps it to the
// world). All maps use u.x for the azimuth phi = 2 pi u.x (measured from +x towards +y) and
// u.y for the polar angle, so a Hammersley point (i/n, radicalInverse(i)) stratifies phi
// regularly and theta by the van der Corput sequence, exactly like LearnOpenGL's
// ImportanceSampleGGX.
#include <cstdint>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace iblab {

// Van der Corput radical inverse in base 2: mirror the 32 bits about the binary point.
// Exact in double (bits / 2^32).
double radicalInverseVdC(std::uint32_t bits);

// The i-th of n Hammersley points: (i / n, radicalInverseVdC(i)).
glm::dvec2 hammersley(std::uint32_t i, std::uint32_t n);

// --- GGX half-vector, density D(h) (n.h) (all microfacet normals, not only visible ones) --
// Inverting the CDF of D(h) cos(theta_h) gives (Walter et al. 2007, Karis 2013)
//   cos^2(theta_h) = (1 - u.y) / (1 + (alpha^2 - 1) u.y),   phi = 2 pi u.x.
// alpha = roughness^2 > 0.
glm::dvec3 sampleGgxHalfVector(glm::dvec2 u, double alpha);
// pdf of h w.r.t. solid angle around h: D(h) cos(theta_h). 0 below the horizon.
double pdfGgxHalfVector(glm::dvec3 h, double alpha);
// The inverse of sampleGgxHalfVector: u.y = sin^2 / (1 + cos^2 (alpha^2 - 1)). h.z > 0.
glm::dvec2 invertGgxHalfVector(glm::dvec3 h, double alpha);
// pdf of the reflected direction l = reflect(-v, h) w.r.t. solid angle around l: the
// Jacobian of the reflection is |dOmega_h / dOmega_l| = 1 / (4 |v.h|) (Walter 2007, eq. 14).
double pdfGgxReflected(double pdfHalfVector, double VdotH);

// --- cosine-weighted hemisphere ---------------------------------------------------------
// Polar map: sin^2(theta) = u.y (so cos(theta) = sqrt(1 - u.y)), phi = 2 pi u.x. The
// Jacobian is |d(u.x, u.y) / dOmega| = cos(theta) / pi. (pbrt's concentric-disk version
// stratifies slightly better; this one has a one-line inverse.)
glm::dvec3 sampleCosineHemisphere(glm::dvec2 u);
double pdfCosineHemisphere(glm::dvec3 w); // cos(theta) / pi, 0 below the horizon
glm::dvec2 invertCosineHemisphere(glm::dvec3 w);

// --- uniform sphere ---------------------------------------------------------------------
// z = 1 - 2 u.y (Archimedes: area is uniform in z), phi = 2 pi u.x; pdf = 1 / (4 pi).
glm::dvec3 sampleUniformSphere(glm::dvec2 u);
double pdfUniformSphere();
glm::dvec2 invertUniformSphere(glm::dvec3 w);

// --- frames -----------------------------------------------------------------------------
// Right-handed orthonormal basis (t, b, n) with t x b = n.
struct Frame {
    glm::dvec3 t;
    glm::dvec3 b;
    glm::dvec3 n;

    glm::dvec3 toWorld(glm::dvec3 local) const { return t * local.x + b * local.y + n * local.z; }
    glm::dvec3 toLocal(glm::dvec3 world) const;
};

// Branchless basis around a unit normal (Duff et al. 2017, "Building an Orthonormal Basis,
// Revisited", listing 3): continuous everywhere except across the z = 0 plane's sign flip,
// and free of the n = -z singularity of Frisvad's original.
Frame tangentFrame(glm::dvec3 n);

} // namespace iblab
