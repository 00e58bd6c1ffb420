#pragma once
// Where the split's bases must be resampled from the map clamped rather than clamped in the
// cube (clamp_near_lights.comp, NearLights in bake_passes.hpp): the environment's level-0 texels
// within reach of a map texel that the lights hold. The environment pass spreads each map
// texel over the cube texels whose footprints read it; clamped in the cube, the spread parts
// that fall under the threshold stay in the base, though the lights hold them already.
#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

#include "bake/bright_texels.hpp"

namespace iblab::bake {

// Map texels the environment pass reads together with a bright texel: the footprint of a
// cube texel about as wide as a map texel, and the bilinear read's one texel either side.
inline constexpr int kEdgeReach = 2;

// The candidates above the lower threshold that have, within kEdgeReach map texels, one
// under a threshold they exceed: where the spread that the clamp in the cube misses can be.
// Inside a bright area every texel a footprint reads is clamped to the threshold either way.
std::vector<std::uint32_t> brightEdgeTexels(const BrightCandidates& candidates, float firstThreshold, float secondThreshold);

// Cube texels (at a face centre) from a bright map texel's centre to the farthest cube texel
// whose footprint can read it: half a cube texel of footprint, and one and a half map texels
// (the bright texel's half and the bilinear read's reach), at least 1 and at most 8.
int nearLightsRadius(const BrightSplitPlan& plan, int faceSize);

// Per texel of a faceSize cube (faces in GL order, row t = 0 first, 6 faceSize^2): 1 within
// nearLightsRadius of one of plan.edgeTexels. Empty where the plan has none or came from a cube.
std::vector<std::uint8_t> nearLightsMarks(const BrightSplitPlan& plan, int faceSize);

// The texels (x, y, face, 0) of a base whose texels each cover step x step texels of the
// faceSize cube, under at least one mark: the ones clamp_near_lights.comp rewrites.
std::vector<glm::ivec4> nearLightsBaseTexels(const std::vector<std::uint8_t>& marks, int faceSize, int step);

} // namespace iblab::bake
