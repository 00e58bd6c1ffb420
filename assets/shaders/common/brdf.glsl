// The microfacet specular terms, GLSL side of renderer/ibl/brdf.hpp (same formulas, same
// names; tests/gl/bake_shared_glsl_gltest.cpp compares the two). `alpha` is the GGX width
// = perceptual roughness^2 everywhere; cosines are clamped to [0, 1] by the caller.
#include "common/conventions.glsl"

// Geometry terms, as the GEOMETRY_* values that select one at run time (the integer
// values are those of iblab::GeometryTerm).
const int GEOMETRY_SCHLICK_GGX = 0;
const int GEOMETRY_HEIGHT_CORRELATED_SMITH = 1;

// GGX / Trowbridge-Reitz D(h) = a2 / (pi ((n.h)^2 (a2 - 1) + 1)^2). The denominator is
// written a2 (n.h)^2 + (1 - n.h)(1 + n.h): for n.h near 1 and small alpha the textbook
// 1 + (n.h)^2 (a2 - 1) cancels catastrophically in float, 1 - n.h does not.
float ggxD(float NdotH, float alpha)
{
    float a2 = alpha * alpha;
    float d = a2 * NdotH * NdotH + (1.0 - NdotH) * (1.0 + NdotH);
    return a2 / (IBL_PI * d * d);
}

// The prefilter's kernel D(h) max(0, n.l) without alpha^2 / pi, c = n.l, 1 - c passed apart
// (brdf.hpp says why).
float ggxPrefilterWeight(float c, float oneMinusC, float alpha2)
{
    float t = alpha2 + 0.5 * oneMinusC * (1.0 - alpha2);
    return max(c, 0.0) / (t * t);
}

// Schlick's G1 with the IBL remapping k = alpha / 2 (Karis 2013), applied separably.
float schlickGgxG(float NdotV, float NdotL, float alpha)
{
    float k = 0.5 * alpha;
    return NdotV / (NdotV * (1.0 - k) + k) * (NdotL / (NdotL * (1.0 - k) + k));
}

// The same in visibility form G / (4 n.l n.v): the G1 numerators cancel the denominator,
// so it stays finite at grazing angles.
float schlickGgxVisibility(float NdotV, float NdotL, float alpha)
{
    float k = 0.5 * alpha;
    return 0.25 / ((NdotV * (1.0 - k) + k) * (NdotL * (1.0 - k) + k));
}

// Height-correlated Smith GGX visibility (Heitz 2014 eq. 99; Filament, glTF): already
// G2 / (4 n.l n.v). 0 when both cosines are 0.
float smithGgxCorrelatedVisibility(float NdotV, float NdotL, float alpha)
{
    float a2 = alpha * alpha;
    float lambdaV = NdotL * sqrt(NdotV * NdotV * (1.0 - a2) + a2);
    float lambdaL = NdotV * sqrt(NdotL * NdotL * (1.0 - a2) + a2);
    float denom = lambdaV + lambdaL;
    return denom > 0.0 ? 0.5 / denom : 0.0;
}

float geometryVisibility(int geometry, float NdotV, float NdotL, float alpha)
{
    return geometry == GEOMETRY_SCHLICK_GGX ? schlickGgxVisibility(NdotV, NdotL, alpha)
                                            : smithGgxCorrelatedVisibility(NdotV, NdotL, alpha);
}

float geometryG(int geometry, float NdotV, float NdotL, float alpha)
{
    return geometry == GEOMETRY_SCHLICK_GGX ? schlickGgxG(NdotV, NdotL, alpha)
                                            : smithGgxCorrelatedVisibility(NdotV, NdotL, alpha) * 4.0 * NdotL * NdotV;
}

// (1 - cos)^5, the Schlick Fresnel weight.
float schlickWeight(float cosTheta)
{
    float m = clamp(1.0 - cosTheta, 0.0, 1.0);
    float m2 = m * m;
    return m2 * m2 * m;
}

vec3 fresnelSchlick(float cosTheta, vec3 F0)
{
    return F0 + (vec3(1.0) - F0) * schlickWeight(cosTheta);
}

// LearnOpenGL's roughness-aware Fresnel for the ambient term (after Lagarde): the grazing
// value is limited to max(1 - roughness, F0).
vec3 fresnelSchlickRoughness(float cosTheta, vec3 F0, float roughness)
{
    return F0 + (max(vec3(1.0 - roughness), F0) - F0) * schlickWeight(cosTheta);
}
