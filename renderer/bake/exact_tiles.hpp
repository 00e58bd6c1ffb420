#pragma once
// Per-tile cuts of a base mip, for an exact sum too large to run over every texel of it for
// every output texel (PrefilterSettings::exactSumTiledTexels: mip 3 of the
// default layout, roughness 0.37, whose exact source is a 32 face of 6144 texels). Each tile of
// kExactTileTexels^2 output texels (one dispatch) sums a list of its own: the source's texels
// near the tile one by one, and further out groups of them, merged at their flux centre, each
// no wider than a fixed share (the spread) of its distance from the tile. GGX's weight is smooth away from its peak, so a
// group far from every texel of the tile is weighted as one point with an error of second order
// in width / distance; near the peak the source's own texels (at most alpha / 2 across,
// exactSumSourceLevel) are summed as the full sum sums them. A group wholly below the horizon
// of every texel of the tile, whose weight is 0 there, is left out.
//
// The lists have exactSumTexels' entries, (direction, 0), (radiance x solid angle, solid
// angle), and the shader's exactBaseSum sums and normalises them unchanged (a constant map stays
// exact): each tile's list is bound as the exact table's uniform block for that tile's
// dispatch alone (BakePasses::dispatchExactTiles), so that every lane reads the same entry at
// once: from a storage buffer llvmpipe reads an entry lane by lane, at several times the cost.
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "bake/baked_texture.hpp"

namespace iblab::bake {

// 2 x 2 of cube_texel.glsl's work groups, one dispatch: 24 for mip 3 of the default layout, at
// 1822 entries a tile. 8 x 8 tiles take 96 at 1377 (the bake 2.77 billion instructions against
// 2.85), and llvmpipe runs each dispatch's few work groups across its threads and waits; in
// wall clock the runs could not tell the two apart (docs/bake.md, "Mip 3 summed per tile").
inline constexpr int kExactTileTexels = 16;
// A group is summed as one point where its angular width is at most this share of its
// angular distance from the tile. At 0.35 the cut agrees with the full sum within 0.0005 of
// the RMS on texel noise and 0.002 beside a bright texel, at 1 within 0.003 and 0.01
// (exact_tiles_test); mip 3 of the default layout lists 1822 entries a tile, under a 64 KB
// uniform block's 2048. A tile whose list would not fit is cut coarser (exactSumTiles).
inline constexpr double kExactTileSpread = 0.35;

struct ExactTiles {
    int tilesPerEdge = 0;          // of the output face
    std::vector<glm::vec4> buffer; // every tile's list, each starting at a multiple of the alignment
    std::vector<int> first;        // per tile, (face * tilesPerEdge + row) * tilesPerEdge + column: its first vec4
    std::vector<int> count;        // its entries (pairs of vec4)
    int largest = 0;               // entries of the longest list
};

// One texel of a base mip as the shader's exact sums enter it: its centre, its solid angle as
// the shader's cubeTexelSolidAngle, and radiance x solid angle. The full sum's table and the
// tiles' single texels both come from here, so that a tile's near texels sum what the full
// sum sums.
struct ExactSumEntry {
    glm::vec3 direction;
    glm::vec3 flux;
    float solidAngle;
};
ExactSumEntry exactSumEntry(const CubeImage& level, int face, int x, int row);

// The cuts of `source` (one base mip, as read back) for an output face of outputFaceSize
// texels: at most maxEntries entries a tile, each list starting at a multiple of alignmentVec4
// vec4 (GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT / 16), the buffer padded by padVec4 at its end so
// that a uniform block of that many vec4 bound at any tile's start stays inside it.
ExactTiles exactSumTiles(const CubeImage& source, int outputFaceSize, int maxEntries, int alignmentVec4, int padVec4,
                         double spread = kExactTileSpread);

} // namespace iblab::bake
