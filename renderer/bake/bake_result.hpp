#pragma once
// What a bake produces: the GL textures, the SH9 coefficients and how long each phase took.
#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "bake/bake_settings.hpp"
#include "bake/baked_texture.hpp"
#include "ibl/sh.hpp"
#include "ibl/shading_lights.hpp"

namespace iblab::bake {

struct ShResult {
    SH9Color radiance;           // L_lm
    SH9Color irradiance;         // E_lm = A-hat_l L_lm
    SH9Color irradianceWindowed; // E_lm scaled by the window (band 0 unchanged)
    ShWindow window = ShWindow::None;
    double windowWidth = 0.0;    // the width used (resolved when the settings asked for automatic)
};

// The bake's phases, in the order they run; their names are the keys of the timings in
// reports and the cache's metadata.
enum class BakePhase {
    Shaders,
    CacheLookup,
    Upload,
    EnvironmentCube,
    Sh9,
    IrradianceRiemann,
    IrradianceImportance,
    IrradianceMoments,
    Prefilter,
    BrdfLut,
    CacheStore
};

constexpr BakePhase irradiancePhase(IrradianceMethod method)
{
    switch (method) {
    case IrradianceMethod::Riemann: return BakePhase::IrradianceRiemann;
    case IrradianceMethod::Importance: return BakePhase::IrradianceImportance;
    case IrradianceMethod::Moments: return BakePhase::IrradianceMoments;
    case IrradianceMethod::None: break;
    }
    throw std::logic_error("irradiancePhase: IrradianceMethod::None bakes no cube");
}

struct PhaseTiming {
    BakePhase phase = BakePhase::Shaders;
    // Steady clock from each step's submission to its fence signalling (the job waits for one
    // step's fence before it issues the next), summed over the phase.
    double milliseconds = 0.0;
};

// The same clock for the steps of one part of a phase, named "phase.part": the prefilter's
// shading lights, its bright-texel split and each of its mips.
struct PartTiming {
    std::string name;
    double milliseconds = 0.0;
};

struct BakeResult {
    BakeSettings settings;
    std::string source;             // the environment's spec
    std::uint64_t contentHash = 0;  // Environment::contentHash of the input pixels
    std::uint64_t shaderFingerprint = 0; // bakeShaderFingerprint of the shaders it is (or was to be) baked with
    int sourceWidth = 0;
    int sourceHeight = 0;
    // The map was baked from its bilinear upsample by this factor (bakeSourceUpsampleFactor;
    // 1: from its own texels, as every imported bake).
    int sourceUpsample = 1;

    BakedTexture environmentCube;      // radiance, full mip chain (box-filtered per face)
    BakedTexture irradianceCube; // E, 1 level, baked by settings.irradiance; empty for IrradianceMethod::None
    BakedTexture prefiltered;          // mip m = roughness prefilterRoughnessFromMip(m, levels)
    std::array<BakedTexture, 2> brdfLut; // [int(GeometryTerm)], RGBA16F: A, B, A + B, 1
    ShResult sh;
    // The fitted lobe's lights (settings.prefilter.shadingLights; none for an imported bake):
    // shading subtracts them from `prefiltered` (ibl/shading_lights.hpp) and sums them exactly.
    ShadingLights shadingLights;

    std::vector<PhaseTiming> timings; // in the order the phases ran
    double totalMilliseconds = 0.0;
    std::vector<PartTiming> partTimings; // in the order the parts ran
    // The step that took longest, the same clock: in the GUI, where a slice of steps runs per
    // frame, the longest a frame can wait on the bake. Named as partTimings (its phase alone
    // where it has no part).
    PartTiming longestStep;
    bool fromCache = false;                 // environment-dependent results loaded from disk
    std::array<bool, 2> lutFromCache{};     // per geometry term
    std::vector<std::string> notes;         // one line each: cache problems found and fixed

    const BakedTexture& lut(GeometryTerm term) const { return brdfLut[std::size_t(term)]; }
    // GPU memory of the result's textures (all levels and faces), from formats and sizes.
    std::size_t gpuBytes() const;
    double phaseMilliseconds(BakePhase phase) const; // 0 if the phase did not run
};

} // namespace iblab::bake

namespace iblab {
template <>
struct EnumNames<bake::BakePhase> {
    static constexpr std::array<EnumName<bake::BakePhase>, 11> entries{{{bake::BakePhase::Shaders, "shaders"},
                                                                        {bake::BakePhase::CacheLookup, "cache_lookup"},
                                                                        {bake::BakePhase::Upload, "upload"},
                                                                        {bake::BakePhase::EnvironmentCube, "environment_cube"},
                                                                        {bake::BakePhase::Sh9, "sh9"},
                                                                        {bake::BakePhase::IrradianceRiemann, "irradiance_riemann"},
                                                                        {bake::BakePhase::IrradianceImportance, "irradiance_importance"},
                                                                        {bake::BakePhase::IrradianceMoments, "irradiance_moments"},
                                                                        {bake::BakePhase::Prefilter, "prefilter"},
                                                                        {bake::BakePhase::BrdfLut, "brdf_lut"},
                                                                        {bake::BakePhase::CacheStore, "cache_store"}}};
};
} // namespace iblab
