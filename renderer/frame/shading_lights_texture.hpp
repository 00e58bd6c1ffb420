#pragma once
// The fitted lobe's inputs with the bake's shading lights split off (ibl/shading_lights.hpp):
// the prefiltered cube less the lights, made once per bake from a read-back on the CPU (the
// same code the accuracy study measures), and the lights the mesh pass sums exactly.
#include <memory>
#include <vector>

#include "bake/baked_texture.hpp"
#include "ibl/shading_lights.hpp"

namespace iblab {

namespace bake {
struct BakeResult;
}

struct ShadingLightsTexture {
    std::vector<ShadingLight> lights;
    float minAlpha = 0.0f;
    bake::BakedTexture residual; // the bake's prefiltered cube less the lights, same format and levels
    double milliseconds = 0.0;   // what making it cost (read-back, residual, upload)
};

// Null when the bake has no lights: the fitted lobe then reads the bake's own cube.
std::unique_ptr<ShadingLightsTexture> makeShadingLightsTexture(const bake::BakeResult& bake);

} // namespace iblab
