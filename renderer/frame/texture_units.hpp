#pragma once
// Every sampler uniform of every program the renderer compiles has its own fixed unit, so
// that a cube and a 2D sampler never share one (a draw-time GL error) and binding never
// depends on the program. The shader library's program initializer assigns them by name.
#include <utility>

#include <epoxy/gl.h>

namespace iblab {

enum TextureUnit : GLuint {
    kUnitEquirect,
    kUnitEnvironmentCube,
    kUnitPrefiltered,
    kUnitIrradianceCube,
    kUnitBrdfLut,
    kUnitBaseColor,
    kUnitMetallicRoughness,
    kUnitNormal,
    kUnitOcclusion,
    kUnitEmissive,
    kUnitHdrFrame,
    kUnitLutSchlick,
    kUnitLutCorrelated,
    // The reference renderer's G-buffer (in ReferenceLayer order: the resolve binds them
    // by offset), environment, sums and result.
    kUnitGNormal,
    kUnitGView,
    kUnitGSpecular,
    kUnitGBaseColor,
    kUnitGEmissive,
    kUnitReferenceEnvironment,
    kUnitSpecularSum,
    kUnitIrradianceSum,
    kUnitReferenceFrame,
    kUnitLobeFit, // the fitted lobe's table (MeshPass)
};

inline constexpr std::pair<const char*, TextureUnit> kSamplerUnits[] = {
    {"uEquirect", kUnitEquirect},
    {"uEnvironmentCube", kUnitEnvironmentCube},
    {"uPrefiltered", kUnitPrefiltered},
    {"uIrradianceCube", kUnitIrradianceCube},
    {"uBrdfLut", kUnitBrdfLut},
    {"uBaseColorTexture", kUnitBaseColor},
    {"uMetallicRoughnessTexture", kUnitMetallicRoughness},
    {"uNormalTexture", kUnitNormal},
    {"uOcclusionTexture", kUnitOcclusion},
    {"uEmissiveTexture", kUnitEmissive},
    {"uHdrFrame", kUnitHdrFrame},
    {"uLutSchlick", kUnitLutSchlick},
    {"uLutCorrelated", kUnitLutCorrelated},
    {"uGNormal", kUnitGNormal},
    {"uGView", kUnitGView},
    {"uGSpecular", kUnitGSpecular},
    {"uGBaseColor", kUnitGBaseColor},
    {"uGEmissive", kUnitGEmissive},
    {"uReferenceEnvironment", kUnitReferenceEnvironment},
    {"uSpecularSum", kUnitSpecularSum},
    {"uIrradianceSum", kUnitIrradianceSum},
    {"uReferenceFrame", kUnitReferenceFrame},
    {"uLobeFit", kUnitLobeFit},
};

} // namespace iblab
