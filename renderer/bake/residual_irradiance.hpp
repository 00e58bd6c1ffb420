#pragma once
// The diffuse the fitted lobe shades where the bake found shading lights
// (ibl/shading_lights.hpp, docs/accuracy-study.md "Compact sources"): the irradiance cube less
// each light's flux max(0, n.l) at its texel centres, read as shading reads it, plus each
// light's term summed per pixel. The renderer binds the residual cube
// (frame/shading_lights_texture.hpp); the bake's error report measures the diffuse the same
// way (bake_accuracy.hpp, irradiance_shaded), so that its figure is the shading's, not the cube's
// alone, which spreads a sun's terminator over a texel of the cube.
#include <vector>

#include "bake/baked_texture.hpp"
#include "ibl/shading_lights.hpp"

namespace iblab::bake {

// The RGB of a read-back level, in the same texel order (ibl's cube levels carry no alpha).
CubeLevelRgb cubeLevelRgb(const CubeImage& image);

// The one-level irradiance cube less the lights' irradiance at its texel centres, clamped at
// 0 (ibl's subtractShadingLightsIrradiance), in the cube's format: a read-back and an upload
// of its 6 size^2 texels.
BakedTexture residualIrradianceCube(const BakedTexture& irradiance, const std::vector<ShadingLight>& lights);

} // namespace iblab::bake
