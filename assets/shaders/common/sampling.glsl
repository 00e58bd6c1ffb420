// Samplers, GLSL side of renderer/ibl/sampling.hpp: the same maps from the unit square to
// directions in a local frame whose +z is the normal, and their densities (tested against
// the C++ core in tests/gl/bake_shared_glsl_gltest.cpp). u.x drives the azimuth
// phi = 2 pi u.x, u.y the polar angle, so a Hammersley point stratifies phi regularly and
// theta by the van der Corput sequence.
#include "common/conventions.glsl"
#include "common/brdf.glsl"

// Van der Corput radical inverse in base 2: the 32 bits mirrored about the binary point.
// (float() keeps the top 24 bits; that is the resolution the sample positions need.)
float radicalInverseVdC(uint bits)
{
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return float(bits) * 2.3283064365386963e-10; // 2^-32
}

// The i-th of n Hammersley points.
vec2 hammersley(uint i, uint n)
{
    return vec2(float(i) / float(n), radicalInverseVdC(i));
}

vec3 sphericalToLocal(float cosTheta, float u)
{
    float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
    float phi = 2.0 * IBL_PI * u;
    return vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);
}

// GGX half vector distributed as D(h) (n.h): inverting its CDF gives
// cos^2(theta_h) = (1 - u.y) / (1 + (alpha^2 - 1) u.y) (Walter et al. 2007, Karis 2013).
vec3 sampleGgxHalfVector(vec2 u, float alpha)
{
    float a2 = alpha * alpha;
    float cos2 = (1.0 - u.y) / (1.0 + (a2 - 1.0) * u.y);
    return sphericalToLocal(sqrt(clamp(cos2, 0.0, 1.0)), u.x);
}

// Density of that half vector w.r.t. solid angle: D(h) (n.h).
float pdfGgxHalfVector(float NdotH, float alpha)
{
    return NdotH > 0.0 ? ggxD(NdotH, alpha) * NdotH : 0.0;
}

// Density of l = reflect(-v, h) w.r.t. solid angle around l: the reflection's Jacobian is
// 1 / (4 |v.h|) (Walter et al. 2007, eq. 14).
float pdfGgxReflected(float pdfHalfVector, float VdotH)
{
    return VdotH != 0.0 ? pdfHalfVector / (4.0 * abs(VdotH)) : 0.0;
}

// Cosine-weighted hemisphere: sin^2(theta) = u.y, density cos(theta) / pi.
vec3 sampleCosineHemisphere(vec2 u)
{
    return sphericalToLocal(sqrt(max(0.0, 1.0 - u.y)), u.x);
}

float pdfCosineHemisphere(float cosTheta)
{
    return cosTheta > 0.0 ? cosTheta * (1.0 / IBL_PI) : 0.0;
}

// Right-handed orthonormal basis around a unit normal: columns (t, b, n), so that
// tangentFrame(n) * local takes a local direction (+z = n) to the world. Duff et al. 2017,
// "Building an Orthonormal Basis, Revisited", listing 3 (the same as the C++ core).
mat3 tangentFrame(vec3 n)
{
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float b = n.x * n.y * a;
    return mat3(vec3(1.0 + s * n.x * n.x * a, s * b, -s * n.x), vec3(b, s + n.y * n.y * a, -n.y), n);
}
