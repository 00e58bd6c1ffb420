#pragma once
// Lights listed per tile of output texels (docs/bake.md, "Lights per tile"), for mips 1 and 2,
// whose many texels made a block of lights that every texel sums (bright_texels_block.hpp)
// the split's cost: there a cap on the block left lamps and lines to the samples.
//
// Per tile of 8 x 8 output texels (one work group), a list of the lights that reach one of its
// texels, each merged with its neighbours where they are far from the tile: the lights sit in a
// quadtree of cube cells, from alpha / 2 (brightCellFaceSize) up to an 8 face, and a tile sums
// a cell as one light at its flux centre where the cell is at most a quarter of its distance
// across, and opens it otherwise. A texel then pays for the lights near it and a few merged
// ones far from it, not for every light on the sphere, and the cap is on each tile's list.
//
// Mip 1 (alpha 0.011): its lobe holds all but kBandTailWeight of its weight within bandReach
// (18 degrees), so its lists hold only the lights within that reach: a band of the bright
// texels, (T_band, T], below the threshold T of the block every texel sums (the tails of the
// brightest sources, a sun's, reach much further and stay there). What the band leaves out is
// its lights' tails beyond that reach, at most kBandTailWeight of their weight, and they are at
// most T bright. Mip 2 (alpha 0.051) lists every light above its threshold within the
// hemisphere (the weight is 0 beyond it), and has no block.
//
// The threshold is the lowest (at least the candidates' floor) at which no tile's list
// exceeds the cap; the level's base is the map clamped at it. Where planBrightSplit asks
// (coarsenOverfull, a spiky base), a tile that cannot list every light first merges its far
// lights coarser, so that a few tiles near a pole do not raise the threshold of all of them.
#include <vector>

#include <glm/vec4.hpp>

namespace iblab::bake {

struct BrightCandidates;

// Texels per tile edge: cube_texel.glsl's work group, so that every lane of a group reads
// the same list (the host cuts the rows of a step at multiples of 8, bake_job.cpp).
inline constexpr int kTileLightsTile = 8;

// The share of a light's GGX weight (D(h) n.l over l) that mip 1's band may leave out.
inline constexpr double kBandTailWeight = 0.005;

// The angle around a light within which the lobe (alpha = roughness^2) holds all but
// kBandTailWeight of its weight.
double bandReach(double roughness);

// A tile per kTileLightsTile^2 texels of each face (one for a face smaller than that).
// buffer: first the tile table, one entry per tile in (face, tile row, tile column) order,
// (index of its first light's entry, light count, 0, 0); then the lights, two entries each,
// (direction, 0), (flux rgb, 0), each tile's contiguous.
struct TileLights {
    float threshold = 0.0f; // equal to the upper threshold where there are none
    int tilesPerEdge = 0;   // 0: none
    int lights = 0;         // distinct lights at the finest cells, before they are merged
    int longestList = 0;
    std::vector<glm::vec4> buffer;
};

// The candidates between the threshold found and upperThreshold (their excess over the one,
// up to the other) as the lights of a level with this roughness and face size, within `reach`
// radians of a tile's texels, at most capPerTile per tile, with a threshold no lower than
// lowestThreshold. capPerTile 0: none. coarsenOverfull: a tile whose list would exceed the cap
// with every candidate lit merges its far lights coarser before the threshold is raised for it.
TileLights planTileLights(const BrightCandidates& candidates, float upperThreshold, double roughness, int faceSize, int capPerTile,
                          double reach, float lowestThreshold = 0.0f, bool coarsenOverfull = false);

} // namespace iblab::bake
