#pragma once
// The fitted lobe's inputs with the bake's shading lights split off (ibl/shading_lights.hpp):
// the prefiltered cube less the lights, made once per bake on the GPU (the accuracy study
// makes it on the CPU, shadingLightResidual; shading_lights_gltest compares the two), the
// irradiance cube and SH9 less them, and the lights the mesh pass sums exactly, specular and
// diffuse.
#include <memory>
#include <vector>

#include "bake/baked_texture.hpp"
#include "ibl/shading_lights.hpp"

namespace iblab {

namespace bake {
struct BakeResult;
}
namespace gl {
class ShaderLibrary;
}

struct ShadingLightsTexture {
    std::vector<ShadingLight> lights;
    float minAlpha = 0.0f;
    bake::BakedTexture residual; // the bake's prefiltered cube less the lights, same format and levels
    // The diffuse sources less the lights, which the fitted lobe adds per pixel: the bake's
    // irradiance cube (none where the bake has none) and its SH9 irradiance, plain and windowed.
    bake::BakedTexture residualIrradiance;
    SH9Color shResidual, shResidualWindowed;
    double milliseconds = 0.0;   // what making it cost, waited for
};

// Null when the bake has no lights: the fitted lobe then reads the bake's own cube.
std::unique_ptr<ShadingLightsTexture> makeShadingLightsTexture(gl::ShaderLibrary& shaders, const bake::BakeResult& bake);

} // namespace iblab
