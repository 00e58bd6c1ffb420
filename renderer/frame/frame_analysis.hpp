#pragma once
// What read-back frames say, as free functions over their pixels (no GL): the error of a
// frame against the reference, the furnace view's sphere readings, and the debug views'
// texel readout under the cursor.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "frame/debug_layout.hpp"
#include "frame/readback.hpp"
#include "frame/settings.hpp"
#include "ibl/error_metrics.hpp"

namespace iblab {

// The error of a frame against the reference, over surface pixels. With the split view,
// `left` covers the pixels left of the divider (settings A) and `right` the others
// (settings B); without it, `left` covers the whole frame.
struct ErrorReport {
    bool valid = false; // false until a complete reference of the frame's settings and size exists
    ErrorMetrics left;
    std::optional<ErrorMetrics> right;
};

// Compares frame with reference (same size) in ViewSettings::errorSpace: linear HDR, or
// display values after settings.toneMap. Measures the pixels that the reference covers at
// their centre (referenceNormals' alpha, ReferenceLayer::Normal) and the frame's surfaces
// cover entirely (isMeasuredPixel): an MSAA edge pixel mixes in the sky, which the
// single-sampled reference does not, so it is left out like the background.
ErrorReport frameErrorReport(FrameReadback frame, FrameReadback reference, const FrameReadback& referenceNormals, const FrameSettings& settings);

// The mean radiance over the central disc of one sphere of a procedural scene.
struct SphereReading {
    glm::vec2 pixel{0.0f}; // projected centre, y up
    glm::vec3 radiance{0.0f};
    float metallic = 0.0f;  // the draw's own factors (the grid's), else the sliders'
    float roughness = 0.0f;
};

// A unit sphere of the scene, placed by model, with the material it was drawn with.
struct SphereInstance {
    glm::mat4 model{1.0f};
    float metallic = 0.0f;
    float roughness = 0.0f;
};

// A reading per sphere with any pixel inside the frame: the inner half of its disc, where
// n.v > 0.87, the near-normal reflectance (what the furnace view prints).
std::vector<SphereReading> sphereReadings(const FrameReadback& frame, const CameraSettings& camera, std::span<const SphereInstance> spheres);

// What the texel under the cursor of a debug view holds.
struct TexelProbe {
    bool valid = false;
    std::string text; // "mip 2 (roughness 0.50), face +Z, texel (12, 30): 0.412 0.380 0.301"
};

// A point (x, y) (y up) in tile coordinates: 0..1 across the tile, y up.
glm::vec2 tileLocal(const DebugTile& tile, float x, float y);

// The texel of a prefiltered mip of faceSize texels per edge under a tile-local point of
// its cube cross (debug_views.frag's layout); none in the cross's empty cells.
struct CubeTexel {
    int face = 0; // GL order: +X -X +Y -Y +Z -Z
    int column = 0;
    int row = 0;  // t = 0 at the top of the cell
};
std::optional<CubeTexel> cubeCrossTexel(glm::vec2 local, int faceSize);
// The texel of a size x size LUT under a tile-local point.
glm::ivec2 lutTexel(glm::vec2 local, int size);

std::string prefilterTexelText(const std::string& tileLabel, const CubeTexel& texel, int faceSize, glm::vec4 value);
std::string lutTexelText(glm::ivec2 texel, int size, glm::vec4 value);

} // namespace iblab
