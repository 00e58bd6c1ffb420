#pragma once
// The generated textured test model, assets/models/material_spheres.glb: no CC0
// metallic-roughness model with textures is available through apt or npm, so iblab
// makes its own. Regenerate it with
//   iblab_make_test_model assets/models/material_spheres.glb
// (the tool target lives in renderer/scene/CMakeLists.txt; the output is deterministic).
//
// Content: three UV spheres (radius 1, 64 x 32 segments, one shared set of accessors,
// 16-bit indices) in a row at x = -2.5, 0, +2.5, each its own mesh and node:
//   materials[0] "textured": baseColor, metallicRoughness, normal and occlusion textures;
//   materials[1] "gold":     factors only (base colour (1, 0.766, 0.336), metallic 1, roughness 0.3);
//   materials[2] "emissive": dark dielectric with an emissive texture x emissiveFactor (1, 0.5, 0.1).
// The textures are 64 x 64 PNGs laid out as 8 x 4 tiles (8 across u, 4 down v):
//   baseColor (sRGB): a hue per tile column, lighter and darker tile rows, dark tile borders;
//   metallicRoughness (linear): G = roughness = (column + 0.5) / 8, B = metallic = 0 on even
//     tile rows and 1 on odd ones, so every tile is a distinct (metallic, roughness) pair;
//   normal (linear): one raised dome per tile, +Y = image up (glTF convention);
//   occlusion (linear, R): 1 inside a tile, darkening to 0.35 at its borders;
//   emissive (sRGB): warm horizontal stripes, 4 texels high, on black.
#include <string>
#include <vector>

#include "scene/material.hpp"

namespace iblab {

// The five textures in the order above (baseColor, metallicRoughness, normal,
// occlusion, emissive), exactly as they are stored (PNG is lossless).
std::vector<TextureImage> materialSpheresTextures();

// Writes the model (atomically). Throws iblab::Error on failure.
void writeMaterialSpheresGlb(const std::string& path);

} // namespace iblab
