#pragma once
// The microfacet specular BRDF terms iblab uses, in float (to mirror the shaders) and double
// (for references). Roughness conventions: `roughness` is the perceptual roughness the UI
// shows; `alpha` = roughness^2 is the GGX width (Burley 2012, Karis 2013). Every function
// here takes alpha unless its parameter is called roughness.
//
//   f_spec(v, l) = D(h) * G(v, l) * F(v.h) / (4 (n.l) (n.v)) = D(h) * Vis(v, l) * F(v.h)
//
// G is the masking-shadowing term, Vis = G / (4 n.l n.v) the "visibility" form that folds
// the denominator in. Two G/Vis choices are offered (GeometryTerm):
//  - SchlickGGX: Schlick's approximation of Smith G1 applied separably,
//    G1(x) = x / (x (1 - k) + k) and G = G1(n.v) G1(n.l), with k = alpha / 2 — the IBL choice
//    in Karis 2013 and LearnOpenGL (their k = a^2 / 2 with a = roughness). Not the
//    direct-lighting k = (roughness + 1)^2 / 8.
//  - HeightCorrelatedSmith: the exact Smith GGX masking-shadowing with height correlation
//    (Heitz 2014, eq. 99), already in Vis form, as used by Filament and the glTF spec:
//    Vis = 0.5 / (n.l sqrt(n.v^2 (1 - a2) + a2) + n.v sqrt(n.l^2 (1 - a2) + a2)), a2 = alpha^2.
#include <algorithm>
#include <cmath>
#include <string_view>

#include <glm/vec3.hpp>

#include "ibl/conventions.hpp"
#include "ibl/enum_names.hpp"

namespace iblab {

enum class GeometryTerm { SchlickGGX, HeightCorrelatedSmith };

// "schlick" and "correlated" were the frame settings' spellings until both settings used one.
template <>
struct EnumNames<GeometryTerm> {
    static constexpr std::array<EnumName<GeometryTerm>, 4> entries{{{GeometryTerm::SchlickGGX, "schlick-ggx"},
                                                                   {GeometryTerm::HeightCorrelatedSmith, "height-correlated-smith"},
                                                                   {GeometryTerm::SchlickGGX, "schlick"},
                                                                   {GeometryTerm::HeightCorrelatedSmith, "correlated"}}};
};

// GGX / Trowbridge-Reitz normal distribution, D(h) = a2 / (pi ((n.h)^2 (a2 - 1) + 1)^2).
// Normalised so that the projected microfacet area is the macro area:
// integral D(h) (n.h) dOmega_h = 1 over the hemisphere (tested).
// The denominator is written a2 (n.h)^2 + (1 - n.h)(1 + n.h): near n.h = 1 with small alpha
// the textbook 1 + (n.h)^2 (a2 - 1) cancels catastrophically in float, while 1 - n.h is
// exact (Sterbenz) — the same concern Filament's D_GGX addresses with a cross product.
// alpha must be > 0 (alpha = 0 is a Dirac delta).
template <typename T>
T ggxD(T NdotH, T alpha)
{
    const T a2 = alpha * alpha;
    const T d = a2 * NdotH * NdotH + (T(1) - NdotH) * (T(1) + NdotH);
    return a2 / (T(kPi) * d * d);
}

// The prefilter's kernel (N = V = R), D(h) max(0, n.l) without the constant alpha^2 / pi, for
// c = n.l: D = alpha^2 / (pi t^2) with t = (n.h)^2 (alpha^2 - 1) + 1 and (n.h)^2 = (1 + c) / 2,
// written t = alpha^2 + (1 - c)(1 - alpha^2) / 2 with 1 - c passed apart, so that a caller
// that has it more exactly than 1 - c (|n - l|^2 / 2 near the lobe's peak) keeps t's digits.
// The bake's bright texels, its exact sums and the shading lights' residual all weigh with it.
template <typename T>
T ggxPrefilterWeight(T c, T oneMinusC, T alpha2)
{
    const T t = alpha2 + T(0.5) * oneMinusC * (T(1) - alpha2);
    return std::max(c, T(0)) / (t * t);
}

// Schlick's G1 with the IBL remapping k = alpha / 2 (Karis 2013).
template <typename T>
T schlickGgxK(T alpha)
{
    return alpha / T(2);
}

template <typename T>
T schlickGgxG1(T NdotX, T k)
{
    return NdotX / (NdotX * (T(1) - k) + k);
}

// Separable Schlick-GGX masking-shadowing G = G1(n.v) G1(n.l), k = alpha / 2.
template <typename T>
T schlickGgxG(T NdotV, T NdotL, T alpha)
{
    const T k = schlickGgxK(alpha);
    return schlickGgxG1(NdotV, k) * schlickGgxG1(NdotL, k);
}

// The same term in visibility form: G / (4 n.l n.v) = 1 / (4 (n.v (1-k) + k)(n.l (1-k) + k)).
// The n.v and n.l of the G1 numerators cancel the denominator, so this stays finite at
// grazing angles where G / (4 n.l n.v) would be 0/0.
template <typename T>
T schlickGgxVisibility(T NdotV, T NdotL, T alpha)
{
    const T k = schlickGgxK(alpha);
    return T(0.25) / ((NdotV * (T(1) - k) + k) * (NdotL * (T(1) - k) + k));
}

// Height-correlated Smith GGX visibility, Vis = G2 / (4 n.l n.v) (Heitz 2014; Filament's
// V_SmithGGXCorrelated; glTF 2.0 spec appendix B). Returns 0 when both cosines are 0.
template <typename T>
T smithGgxCorrelatedVisibility(T NdotV, T NdotL, T alpha)
{
    const T a2 = alpha * alpha;
    const T lambdaV = NdotL * std::sqrt(NdotV * NdotV * (T(1) - a2) + a2);
    const T lambdaL = NdotV * std::sqrt(NdotL * NdotL * (T(1) - a2) + a2);
    const T denom = lambdaV + lambdaL;
    return denom > T(0) ? T(0.5) / denom : T(0);
}

// The masking-shadowing G itself (Vis * 4 n.l n.v for the correlated form).
template <typename T>
T geometryG(GeometryTerm term, T NdotV, T NdotL, T alpha)
{
    if (term == GeometryTerm::SchlickGGX)
        return schlickGgxG(NdotV, NdotL, alpha);
    return smithGgxCorrelatedVisibility(NdotV, NdotL, alpha) * T(4) * NdotL * NdotV;
}

template <typename T>
T visibility(GeometryTerm term, T NdotV, T NdotL, T alpha)
{
    if (term == GeometryTerm::SchlickGGX)
        return schlickGgxVisibility(NdotV, NdotL, alpha);
    return smithGgxCorrelatedVisibility(NdotV, NdotL, alpha);
}

// The specular BRDF without its Fresnel factor: D * G / (4 n.l n.v) = D * Vis. Multiply by
// F(v.h) for the full f_spec. Cosines must be clamped to [0, 1] by the caller.
template <typename T>
T ggxSpecularBrdf(GeometryTerm term, T NdotH, T NdotV, T NdotL, T alpha)
{
    return ggxD(NdotH, alpha) * visibility(term, NdotV, NdotL, alpha);
}

// Fresnel-Schlick, F = F0 + (1 - F0)(1 - cos)^5, cos clamped to [0, 1].
template <typename T>
T schlickWeight(T cosTheta)
{
    const T m = std::clamp(T(1) - cosTheta, T(0), T(1));
    const T m2 = m * m;
    return m2 * m2 * m;
}

template <typename T>
T fresnelSchlick(T cosTheta, T F0)
{
    return F0 + (T(1) - F0) * schlickWeight(cosTheta);
}

template <typename T>
glm::vec<3, T> fresnelSchlick(T cosTheta, glm::vec<3, T> F0)
{
    return F0 + (glm::vec<3, T>(T(1)) - F0) * schlickWeight(cosTheta);
}

// LearnOpenGL's roughness-aware Fresnel for the ambient term (after Sébastien Lagarde):
// the grazing value is limited to max(1 - roughness, F0) so rough surfaces do not get a
// bright rim from an environment the split-sum has already blurred.
template <typename T>
glm::vec<3, T> fresnelSchlickRoughness(T cosTheta, glm::vec<3, T> F0, T roughness)
{
    const glm::vec<3, T> F90(std::max(T(1) - roughness, F0.x), std::max(T(1) - roughness, F0.y),
                             std::max(T(1) - roughness, F0.z));
    return F0 + (F90 - F0) * schlickWeight(cosTheta);
}

// What shading knows of a surface point besides its geometry (ibl_lighting.glsl's
// SurfacePoint without N and V).
struct SurfaceMaterial {
    glm::dvec3 baseColor{1.0};
    double metallic = 0.0;
    double roughness = 0.5; // perceptual
    glm::dvec3 F0{0.04};
    double occlusion = 1.0;
};

// The shading model every estimator shares (ibl_lighting.glsl's combineLobes, where the
// split sum, the sampled method and the reference renderer all end): a Lambertian layer under
// the specular one. The roughness-aware Fresnel at n.v leaves kD = (1 - F)(1 - metallic) of
// the light to the diffuse layer (metals have none), which reflects E / pi of the irradiance
// E. `specular` is the reflected radiance, energy compensation included.
inline glm::dvec3 combineLobes(const SurfaceMaterial& s, double NdotV, glm::dvec3 irradiance, glm::dvec3 specular)
{
    const glm::dvec3 kD = (glm::dvec3(1.0) - fresnelSchlickRoughness(NdotV, s.F0, s.roughness)) * (1.0 - s.metallic);
    return (kD * s.baseColor / kPi * irradiance + specular) * s.occlusion;
}

} // namespace iblab
