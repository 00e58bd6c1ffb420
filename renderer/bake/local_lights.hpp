#pragma once
// Mip 1's local lights (docs/bake.md, "Mip 1's local lights"). Mip 1's lobe (alpha 0.011) is
// about a degree wide, so a lamp or a line that its far-cell cap (brightTexelCap) leaves in
// the base is narrower than its samples' footprints, and they alias it. But at mip 1 a light
// matters only near it: 99.5% of the lobe's weight lies within localLightRadius (18 degrees).
// So, below the global threshold T (whose lights every texel sums, tails and all), a second
// band of the bright texels, (T_local, T], is summed as lights by the texels near them only:
// per tile of 8 x 8 output texels (one work group), the lights within localLightRadius of any
// of its texels. A texel then pays for the lights near it, not for every light on the sphere,
// and the cap is on each tile's list. What it leaves out is the band's tails beyond that
// radius: at most kLocalTailWeight of each light's weight, and the band is at most T.
//
// T_local is the lowest threshold (at least the candidates' floor) at which no tile's list
// exceeds the cap. Mip 1's base is then the map clamped at T_local.
#include <vector>

#include <glm/vec4.hpp>

namespace iblab::bake {

struct BrightCandidates;

// Texels per tile edge: cube_texel.glsl's work group, so that every lane of a group reads
// the same list (the host cuts the rows of a step at multiples of 8, bake_job.cpp).
inline constexpr int kLocalLightTile = 8;

// The share of a light's GGX weight (D(h) n.l over l) that its tile lists may leave out.
inline constexpr double kLocalTailWeight = 0.005;

// The angle around a light within which an output texel sums it: the lobe (alpha =
// roughness^2) holds all but kLocalTailWeight of its weight within it.
double localLightRadius(double roughness);

// A tile per kLocalLightTile^2 texels of each face of mip 1 (one for a face smaller than
// that). buffer: first the tile table, one entry per tile in (face, tile row, tile column)
// order, (index of its first light's entry, light count, 0, 0); then the lights, two entries
// each, (direction, 0), (band flux rgb, 0), each tile's contiguous.
struct LocalLights {
    float threshold = 0.0f; // T_local; equal to the global threshold where there is no band
    int tilesPerEdge = 0;   // 0: none
    int lights = 0;         // distinct lights before they are listed per tile
    int longestList = 0;
    std::vector<glm::vec4> buffer;
};

// The band (threshold, upperThreshold] of the candidates as local lights of a level with this
// roughness and face size, merged as that level's global lights are (brightCellFaceSize),
// at most capPerTile per tile. capPerTile 0: none.
LocalLights planLocalLights(const BrightCandidates& candidates, float upperThreshold, double roughness, int faceSize, int capPerTile);

} // namespace iblab::bake
