#pragma once
// Where the debug views put their tiles, computed once on the CPU so that the shader, the
// UI's labels and the texel readout under the cursor agree.
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "frame/settings.hpp"

namespace iblab {

struct DebugTile {
    glm::vec4 rect{0.0f}; // (x0, y0, x1, y1) in pixels, y up (GL window coordinates)
    std::string label;      // "mip 2: roughness 0.50", "Schlick-GGX, k = alpha/2 (x: n.v, y: roughness)"
    std::string shortLabel; // for a tile narrower than label: "mip 2 r 0.50", "Schlick-GGX"
    int index = 0;        // the mip, or the LUT variant (GeometryTerm)
};

// Tiles for ViewMode::PrefilterMips (one 4:3 cube cross per mip; mipRoughness holds each
// mip's roughness, as the bake's layout put it) and ViewMode::Lut (two squares); empty for
// the other views.
std::vector<DebugTile> debugTiles(ViewMode mode, const std::vector<float>& mipRoughness, int width, int height);

// The tile under pixel (x, y) (y up), or -1.
int debugTileAt(const std::vector<DebugTile>& tiles, float x, float y);

} // namespace iblab
