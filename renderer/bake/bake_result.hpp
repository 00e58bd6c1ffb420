#pragma once
// What a bake produces: the GL textures, the SH9 coefficients and how long each phase took.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "bake/bake_settings.hpp"
#include "bake/baked_texture.hpp"
#include "ibl/sh.hpp"

namespace iblab::bake {

struct ShResult {
    SH9Color radiance;           // L_lm
    SH9Color irradiance;         // E_lm = A-hat_l L_lm
    SH9Color irradianceWindowed; // E_lm scaled by the window (band 0 unchanged)
    ShWindow window = ShWindow::None;
    double windowWidth = 0.0;    // the width used (resolved when the settings asked for automatic)
};

struct PhaseTiming {
    std::string phase;         // "shaders", "upload", "environment_cube", "sh9", ...
    double milliseconds = 0.0; // steady clock around the phase's steps, each ending in glFinish
};

struct BakeResult {
    BakeSettings settings;
    std::string source;             // the environment's spec
    std::uint64_t contentHash = 0;  // Environment::contentHash of the input pixels
    int sourceWidth = 0;
    int sourceHeight = 0;

    BakedTexture environmentCube;      // radiance, full mip chain (box-filtered per face)
    BakedTexture irradianceCube; // E, 1 level, baked by settings.irradiance; empty for IrradianceMethod::None
    BakedTexture prefiltered;          // mip m = roughness prefilterRoughnessFromMip(m, levels)
    std::array<BakedTexture, 2> brdfLut; // [int(GeometryTerm)], RGBA16F: A, B, A + B, 1
    ShResult sh;

    std::vector<PhaseTiming> timings; // in the order the phases ran
    double totalMilliseconds = 0.0;
    bool fromCache = false;                 // environment-dependent results loaded from disk
    std::array<bool, 2> lutFromCache{};     // per geometry term
    std::vector<std::string> notes;         // one line each: cache problems found and fixed

    const BakedTexture& lut(GeometryTerm term) const { return brdfLut[std::size_t(term)]; }
    // GPU memory of the result's textures (all levels and faces), from formats and sizes.
    std::size_t gpuBytes() const;
    double phaseMilliseconds(std::string_view phase) const; // 0 if the phase did not run
};

} // namespace iblab::bake
