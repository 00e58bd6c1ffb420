// Image-based lighting of one surface point: the split-sum approximation and runtime GGX
// importance sampling with N samples, over the baked textures. Directions are in world
// space; the environment's yaw is applied here, once, for every lookup.
#include "common/environment_lookup.glsl"
#include "common/brdf.glsl"
#include "common/sampling.glsl"
#include "common/prefilter_lod.glsl"
#include "common/sh9.glsl"
#include "common/specular_lobe.glsl"

uniform samplerCube uEnvironmentCube; // radiance with a box-filtered mip chain (PDF mip filtering source)
uniform samplerCube uPrefiltered;     // mip m = roughness prefilterRoughnessFromMip(m, levels, layout)
uniform samplerCube uIrradianceCube;  // E (white environment -> pi)
uniform sampler2D uBrdfLut;           // x = n.v, y = roughness; R = A, G = B, B = A + B
uniform vec3 uShIrradiance[9];        // E_lm as the Diffuse setting picks: windowed (sh9) or plain (sh9-plain)
uniform float uPrefilteredLevels;
uniform int uPrefilteredLayout;  // PREFILTER_LAYOUT_* of prefilter_lod.glsl, as the bake used
uniform float uEnvironmentFaceSize;
uniform float uEnvironmentLevels;
uniform int uGeometry;       // GEOMETRY_* of brdf.glsl
// Code paths that settings choose are compile-time constants, and each pass specialises its
// program with them (lighting.hpp's diffuseSourceOf, mesh_pass.cpp): llvmpipe evaluates
// both sides of a branch on a uniform, texture reads included. The fitted lobe's unused
// reads were a third of a split-sum mesh pass, and the sky's unused modes two thirds of
// the sky pass (1280 x 720); a GPU resolves such branches at compile time either way.
#ifndef DIFFUSE_SOURCE
#define DIFFUSE_SOURCE 0 // 0: SH9, 1: the irradiance cube
#endif
#ifndef FITTED_LOBE
#define FITTED_LOBE 0 // 1: shadeSplitSum reads where the fitted table says (ShadingMethod::FittedLobe)
#endif
#ifndef LOBE_FIT_LAYOUT
#define LOBE_FIT_LAYOUT 4 // the fitted table's taps (LobeFitTable::taps), compiled in by the mesh pass
#endif
#ifndef SHADING_LIGHTS_GEOMETRY
#define SHADING_LIGHTS_GEOMETRY 1 // the frame's GEOMETRY_* (uGeometry), compiled in for the lights' loop
#endif
uniform bool uMultiscatter;
uniform int uMultiscatterModel; // MULTISCATTER_* below, the values of iblab::MultiscatterModel
const int MULTISCATTER_FILAMENT = 0;
const int MULTISCATTER_FDEZ_AGUERA = 1;
uniform bool uRoughFresnelOnLut; // LearnOpenGL's F_roughness * A + B (SamplingSettings::roughFresnelOnLut)
uniform int uSpecularDirection;  // SPECULAR_DIRECTION_* of specular_lobe.glsl: where the split sum reads the cube
// ShadingMethod::FittedLobe: the cube read per the fitted table (specular_approximations.hpp's
// LobeFitTable, uploaded once from the CPU core's fittedLobeTable()): x = n.v, y = perceptual
// roughness, texel centres (i + 0.5) / size, bilinear, clamp to edge; LOBE_FIT_LAYOUT its taps.
uniform sampler2D uLobeFit;
// The map's brightest texels, shaded exactly (renderer/ibl/shading_lights.hpp): with them the
// fitted lobe reads uPrefiltered made from the rest of the map (its residual), and each light
// adds its flux times the BRDF at its direction. Environment space, flux = radiance x solid
// angle. uShadingLightCount 0: the plain cube, no lights.
const int SHADING_LIGHTS_MAX = 16;
uniform int uShadingLightCount;
uniform vec3 uShadingLightDirection[SHADING_LIGHTS_MAX];
uniform vec3 uShadingLightFlux[SHADING_LIGHTS_MAX];
uniform float uShadingLightMinAlpha; // a light is a texel across, not a point: alpha at least its size
uniform float uForcedMip;    // < 0: automatic
uniform bool uPdfMipFiltering;
uniform float uMipBias;

struct SurfacePoint {
    vec3 N;
    vec3 V;
    vec3 baseColor;
    float metallic;
    float roughness; // perceptual
    float occlusion;
    vec3 F0;
};

vec3 diffuseIrradiance(vec3 N)
{
#if DIFFUSE_SOURCE == 0
    return max(sh9Evaluate(uShIrradiance, toEnvironment(N)), vec3(0.0)) * uEnvironmentIntensity;
#else
    return textureLod(uIrradianceCube, toEnvironment(N), 0.0).rgb * uEnvironmentIntensity;
#endif
}

// Multiple-scattering energy compensation: single scattering misses the energy of rays that
// bounce between microfacets; a factor on the single-scattering specular restores it, from
// the single-scattering albedo E_ss = A + B (the LUT's third channel; the reference's own
// sum). Both forms reflect exactly 1 for a white metal (F0 = 1) and differ for coloured F0:
//   Filament (getEnergyCompensationPixelParams): 1 + F0 (1 / E_ss - 1);
//   Fdez-Aguera 2019 as the glTF Sample Viewer's getIBLGGXFresnel and Bevy's
//   compute_multiscatter write it: (FssEss + FmsEms) / FssEss = 1 / (1 - F_avg E_ms), with
//   E_ms = 1 - E_ss and F_avg = F0 + (1 - F0) / 21.
vec3 energyCompensation(vec3 F0, float singleScatterAlbedo)
{
    if (!uMultiscatter) return vec3(1.0);
    if (uMultiscatterModel == MULTISCATTER_FDEZ_AGUERA) {
        vec3 averageFresnel = F0 + (vec3(1.0) - F0) * (1.0 / 21.0);
        return vec3(1.0) / (vec3(1.0) - averageFresnel * (1.0 - singleScatterAlbedo));
    }
    return vec3(1.0) + F0 * (1.0 / max(singleScatterAlbedo, 1e-4) - 1.0);
}

// The shading model every estimator shares (split sum, sampled, and the reference): a
// Lambertian layer under the specular one. The roughness-aware Fresnel at n.v leaves
// kD = (1 - F)(1 - metallic) of the light to the diffuse layer (metals have none).
// irradianceOverPi is E / pi and specular the reflected radiance, both with the
// environment's intensity applied.
vec3 combineLobes(SurfacePoint s, float NdotV, vec3 irradianceOverPi, vec3 specular)
{
    vec3 F = fresnelSchlickRoughness(NdotV, s.F0, s.roughness);
    vec3 kD = (vec3(1.0) - F) * (1.0 - s.metallic);
    return (kD * s.baseColor * irradianceOverPi + specular) * s.occlusion;
}

// The prefiltered cube around `direction` (any length) for a lobe of perceptual `roughness`,
// at the lod the bake's layout gives it (or the forced mip).
vec3 prefilteredRadiance(vec3 direction, float roughness)
{
    float lod = uForcedMip >= 0.0 ? uForcedMip : prefilterMipFromRoughness(roughness, uPrefilteredLevels, uPrefilteredLayout);
    return textureLod(uPrefiltered, toEnvironment(direction), lod).rgb * uEnvironmentIntensity;
}

// The fitted lobe (docs/accuracy-study.md): the table texel at (n.v, roughness) gives each
// read its direction between R and N and its roughness (specular_lobe.glsl decodes it). The
// Fresnel split (layout 3) reads once for F0 A and once for B; the other layouts mix their
// reads with weights that sum to 1. scaledA is A times F0 (or LearnOpenGL's F_roughness).
vec4 lobeFitTexel(float NdotV, float roughness, int plane)
{
    int planes = lobeFitPlanes(LOBE_FIT_LAYOUT);
    float rows = float(textureSize(uLobeFit, 0).y / planes);
    return texture(uLobeFit, vec2(NdotV, lobeFitPlaneY(roughness, plane, planes, rows)));
}

vec3 fittedLobeRadiance(SurfacePoint s, float NdotV, vec3 R, vec3 scaledA, float B)
{
    vec4 p = lobeFitTexel(NdotV, s.roughness, 0);
    vec3 read0 = prefilteredRadiance(lobeTapDirection(s.N, R, lobeTapTowardsNormal(p, LOBE_FIT_LAYOUT, 0)), lobeTapRoughness(p, LOBE_FIT_LAYOUT, 0));
    if (LOBE_FIT_LAYOUT == 1) return read0 * (scaledA + B);
    vec3 read1 = prefilteredRadiance(lobeTapDirection(s.N, R, lobeTapTowardsNormal(p, LOBE_FIT_LAYOUT, 1)), lobeTapRoughness(p, LOBE_FIT_LAYOUT, 1));
    if (LOBE_FIT_LAYOUT == 4) {
        vec4 q = lobeFitTexel(NdotV, s.roughness, 1);
        vec3 read2 = prefilteredRadiance(lobeTapDirection(s.N, R, lobeSecondATowardsNormal(q)), lobeSecondARoughness(q));
        read0 = mix(read0, read2, lobeSecondAWeight(q));
    }
    if (LOBE_FIT_LAYOUT >= 3) return scaledA * read0 + B * read1;
    return (lobeTapWeight(p, LOBE_FIT_LAYOUT, 0) * read0 + lobeTapWeight(p, LOBE_FIT_LAYOUT, 1) * read1) * (scaledA + B);
}

// The lights' exact specular, F D Vis (n.l) flux each, without the energy compensation (the
// caller applies it to the whole specular, as to the cube's reads), and their irradiance,
// flux (n.l) each: with them the irradiance cube and SH9 are the map less them
// (shading_lights_texture.cpp), and a sun's terminator is as sharp as the sun, not a texel of
// the cube wide. One loop for both: a second one cost llvmpipe a quarter of a fitted-lobe grid
// frame. Dot products are the same in either space, so N and V are turned into the
// environment's rather than every light out.
vec3 shadingLightsSpecular(SurfacePoint s, float NdotV, out vec3 irradiance)
{
    vec3 N = toEnvironment(s.N), V = toEnvironment(s.V);
    float alpha = max(s.roughness * s.roughness, uShadingLightMinAlpha);
    vec3 sum = vec3(0.0);
    irradiance = vec3(0.0);
    for (int i = 0; i < uShadingLightCount; ++i) {
        vec3 L = uShadingLightDirection[i];
        float NdotL = dot(N, L);
        if (NdotL <= 0.0) continue;
        irradiance += uShadingLightFlux[i] * NdotL;
        vec3 H = normalize(V + L);
        float VdotH = max(dot(V, H), 0.0);
        sum += uShadingLightFlux[i] * fresnelSchlick(VdotH, s.F0)
               * (ggxD(max(dot(N, H), 0.0), alpha) * geometryVisibility(SHADING_LIGHTS_GEOMETRY, NdotV, NdotL, alpha) * NdotL);
    }
    irradiance *= uEnvironmentIntensity;
    return sum * uEnvironmentIntensity;
}

// Split sum (Karis 2013): the specular integral as (prefiltered radiance at R) times
// (F0 A + B), with A and B from the LUT. LearnOpenGL multiplies the LUT by the
// roughness-aware Fresnel instead of F0; that counts Fresnel twice (it is already inside A
// and B), so by default F_roughness only sets the diffuse weight kD = (1 - F)(1 - metallic),
// and uRoughFresnelOnLut reproduces the tutorial for the convention presets.
// uSpecularDirection moves the read from R towards N (a dominant direction); FITTED_LOBE
// reads where the fitted table says instead.
vec3 shadeSplitSum(SurfacePoint s)
{
    float NdotV = max(dot(s.N, s.V), 1e-4);
    vec3 R = reflect(-s.V, s.N);
    vec3 lut = texture(uBrdfLut, vec2(NdotV, s.roughness)).rgb;
    vec3 scaleFresnel = uRoughFresnelOnLut ? fresnelSchlickRoughness(NdotV, s.F0, s.roughness) : s.F0;
    vec3 irradiance = diffuseIrradiance(s.N);
#if FITTED_LOBE
    vec3 lightsIrradiance;
    vec3 reflected = fittedLobeRadiance(s, NdotV, R, scaleFresnel * lut.r, lut.g) + shadingLightsSpecular(s, NdotV, lightsIrradiance);
    irradiance += lightsIrradiance;
#else
    if (uSpecularDirection != SPECULAR_DIRECTION_REFLECTION)
        R = lobeTapDirection(s.N, R, specularDirectionTowardsNormal(uSpecularDirection, s.roughness * s.roughness));
    vec3 reflected = prefilteredRadiance(R, s.roughness) * (scaleFresnel * lut.r + lut.g);
#endif
    vec3 specular = reflected * energyCompensation(s.F0, lut.b);
    return combineLobes(s, NdotV, irradiance * (1.0 / IBL_PI), specular);
}

// The first 1024 Hammersley points for the current N, two per vec4, uploaded once per N.
layout(std140, binding = 0) uniform HammersleyPoints { vec4 uHammersley[512]; };
uniform int uSampleCount;
uniform vec2 uSampleRotation; // Cranley-Patterson rotation: 0 for the plain set, per-frame for accumulation
uniform bool uNormalizeByAccepted;
uniform bool uCosineSampledDiffuse;

vec2 samplePoint(int i)
{
    vec4 pair = uHammersley[i >> 1];
    return fract(((i & 1) == 0 ? pair.xy : pair.zw) + uSampleRotation);
}

float sampleLod(float pdf)
{
    if (uForcedMip >= 0.0) return uForcedMip;
    if (!uPdfMipFiltering) return 0.0;
    return clamp(sourceLodFromPdf(pdf, float(uSampleCount), uEnvironmentFaceSize, uMipBias), 0.0, uEnvironmentLevels - 1.0);
}

// Monte Carlo estimate of the specular integral with N GGX half-vector samples: each term
// is L(l) f(v, l) (n.l) / pdf(l), with pdf(l) = D (n.h) / (4 v.h), so D cancels:
//   f (n.l) / pdf = F V 4 (v.h) (n.l) / (n.h), V the visibility G / (4 n.l n.v).
// Samples below the horizon are valid draws that contribute 0: dividing by N keeps the
// estimator unbiased. uNormalizeByAccepted divides by the accepted count instead, as the
// prefilter of LearnOpenGL does (slightly bright at grazing angles).
vec3 shadeSampled(SurfacePoint s)
{
    float NdotV = max(dot(s.N, s.V), 1e-4);
    float alpha = max(s.roughness * s.roughness, 1e-3);
    mat3 frame = tangentFrame(s.N);
    vec3 specular = vec3(0.0);
    vec3 diffuseSum = vec3(0.0);
    int accepted = 0;
    for (int i = 0; i < uSampleCount; ++i) {
        vec2 u = samplePoint(i);
        vec3 H = frame * sampleGgxHalfVector(u, alpha);
        vec3 L = reflect(-s.V, H);
        float NdotL = dot(s.N, L);
        if (NdotL > 0.0) {
            float NdotH = max(dot(s.N, H), 1e-4);
            float VdotH = max(dot(s.V, H), 1e-4);
            float pdf = pdfGgxReflected(pdfGgxHalfVector(NdotH, alpha), VdotH);
            vec3 radiance = textureLod(uEnvironmentCube, toEnvironment(L), sampleLod(pdf)).rgb;
            vec3 F = fresnelSchlick(VdotH, s.F0);
            float V = geometryVisibility(uGeometry, NdotV, NdotL, alpha);
            specular += radiance * F * (V * 4.0 * VdotH * NdotL / NdotH);
            ++accepted;
        }
        if (uCosineSampledDiffuse) {
            // Lambert: f cos / pdf = (albedo / pi) cos / (cos / pi) = albedo, so the
            // estimate of E / pi is the mean radiance of cosine-distributed directions.
            vec3 Ld = frame * sampleCosineHemisphere(u);
            float pdfD = pdfCosineHemisphere(max(dot(s.N, Ld), 1e-4));
            diffuseSum += textureLod(uEnvironmentCube, toEnvironment(Ld), sampleLod(pdfD)).rgb;
        }
    }
    float denominator = uNormalizeByAccepted ? float(max(accepted, 1)) : float(uSampleCount);
    vec3 lut = texture(uBrdfLut, vec2(NdotV, s.roughness)).rgb;
    specular *= energyCompensation(s.F0, lut.b) * uEnvironmentIntensity / denominator;
    vec3 irradianceOverPi = uCosineSampledDiffuse ? diffuseSum * uEnvironmentIntensity / float(uSampleCount)
                                                  : diffuseIrradiance(s.N) * (1.0 / IBL_PI);
    return combineLobes(s, NdotV, irradianceOverPi, specular);
}
