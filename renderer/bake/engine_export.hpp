#pragma once
// A bake written as an engine loads it, without conversion (docs/engine-export.md has each
// format's conventions and the engine sources they come from):
//   filament  DIR/NAME_ibl.ktx, DIR/NAME_skybox.ktx (KTX 1.1, RGBA16F), DIR/sh.txt: the
//             layout of `cmgen --format=ktx --deploy=DIR` (NAME = DIR's name), texels
//             mirrored as cmgen mirrors by default, quadratic roughness-to-lod over mips
//             down to 16^2, the shader-ready SH9 in the KTX key "sh" and sh.txt;
//   khronos   DIR/ggx/specular.ktx2, DIR/lambertian/diffuse.ktx2, DIR/lut_ggx.ktx2 (KTX 2.0,
//             RGBA16F): the glTF-IBL-Sampler's outputs in its orientation, lod = roughness x
//             (levels - 1) down to 2^2, the diffuse cube holding E / pi;
//   bevy      DIR/NAME_specular.ktx2, DIR/NAME_diffuse.ktx2: what EnvironmentMapLight reads,
//             in its orientation (its shader negates z), the same layouts as khronos.
// When the bake's prefiltered cube does not have the engine's layout (levels, roughness per
// mip, face size), the environment is prefiltered again with iblab's own bake passes.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>

#include "bake/bake_result.hpp"
#include "bake/bake_settings.hpp"
#include "gl/shader_library.hpp"
#include "ibl/enum_names.hpp"
#include "io/environment.hpp"
#include "io/ktx_texture.hpp"

namespace iblab::bake {

enum class EngineFormat { Filament, Khronos, Bevy };

// What an engine expects of its files.
struct EngineLayout {
    int faceSize = 256;    // the prefiltered cube's level 0
    int levels = 5;        // prefiltered mips
    RoughnessLayout roughness = RoughnessLayout::Quadratic;
    // The engine's cube direction d holds iblab's radiance from direction engineToIblab d.
    glm::dmat3 engineToIblab{1.0};
    double diffuseScale = 1.0; // the diffuse cube holds diffuseScale x E (no cube: 0)
};

// For a bake whose prefiltered cube has faces of prefilterFaceSize texels.
EngineLayout engineLayout(EngineFormat format, int prefilterFaceSize);
// The settings that bake in the engine's layout (the given ones where the engine has no say).
BakeSettings engineBakeSettings(EngineFormat format, const BakeSettings& settings);

// A cube level in the engine's orientation: texel (face, x, row) of the result is the texel of
// `level` whose centre direction is engineToIblab times its own (a signed permutation of the
// axes maps texel centres onto texel centres, so this is a copy).
CubeImage reorientCube(const CubeImage& level, const glm::dmat3& engineToIblab);
// Levels [0, levels) of a cube texture, reoriented and scaled, as a KTX texture.
ktx::KtxTexture cubeToKtx(const BakedTexture& cube, int levels, const glm::dmat3& engineToIblab, float scale = 1.0f);

struct ExportReport {
    std::vector<std::filesystem::path> files; // in the order written
    bool reprefiltered = false;                // the bake's layout was not the engine's
    // A file clipped texels above a half float's 65504 (a float bake of a map brighter than
    // that: the engines' layouts are half floats).
    bool clippedToHalf = false;
    double milliseconds = 0.0;
};

// Needs a current GL context. environment: the pixels the bake was made from (only read when
// the engine's layout needs a new prefilter). Throws iblab::Error naming the file or problem.
ExportReport exportForEngine(gl::ShaderLibrary& shaders, const Environment& environment, const BakeResult& bake, EngineFormat format,
                             const std::filesystem::path& directory);

} // namespace iblab::bake

namespace iblab {
template <>
struct EnumNames<bake::EngineFormat> {
    static constexpr std::array<EnumName<bake::EngineFormat>, 3> entries{
        {{bake::EngineFormat::Filament, "filament"}, {bake::EngineFormat::Khronos, "khronos"}, {bake::EngineFormat::Bevy, "bevy"}}};
};
} // namespace iblab
