#pragma once
// The layout of a prefiltered level's bright-texel block (bright_texels.cpp writes it,
// prefilter_ggx.comp reads it): its far cells first, two vec4 entries each,
// (direction, index of its first light), (flux, light count), then the lights, two entries
// each, grouped by cell. An output texel sums a far cell as one point of light at its flux
// centre where the cell is further than brightNearCos from it, and light by light where nearer.
#include "bake/bake_settings.hpp"

namespace iblab::bake {

// Entries of the block every split level binds (prefilter_ggx.comp's BRIGHT_CAPACITY): one
// size for every mip, so that one program variant serves them all; 0 without a split.
int brightBlockCapacity(const PrefilterSettings& settings);

// Cosine of the angle within which a far cell of a level whose lights are merged in the
// texels of a cellFaceSize cube is summed light by light (2: never, where the far cells are
// the lights themselves).
float brightNearCos(int cellFaceSize);

} // namespace iblab::bake
