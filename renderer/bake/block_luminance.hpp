#pragma once
// The scale a refined mip's samples see the base at (bright_texels.hpp: a texel of mips 1
// and 2 whose samples' luminances spread by more than refineSpread x the base's RMS luminance
// is sampled again). Each sample reads a source mip whose texels are about as wide as its
// share of the lobe, so a bright line narrower than that reaches it diluted: the samples
// spread by the line's diluted luminance, not its full one. Compared with the RMS of the
// full-resolution base, a field of thin lines (slits, fluorescent tubes, rings) then looked
// smooth and was left to aliased samples. The RMS is therefore taken over the base averaged
// in blocks of the equirect about as wide as the samples' median footprint: where the bright
// areas are larger than that block (a softbox, a window, the sky) it is the full RMS, and
// where they are thinner it falls with their dilution (docs/bake.md, "The refinement's scale").
#include <cstdint>
#include <span>
#include <vector>

#include "bake/bake_settings.hpp"
#include "ibl/image.hpp"

namespace iblab::bake {

// The luminance (negative values as 0) of an equirect, per block of 2^scale x 2^scale texels
// (the last row and column of blocks hold what is left): its integral and solid angle.
struct BlockLuminance {
    int mip = 0;   // the prefiltered mip whose samples it scales
    int scale = 0; // log2 of the block's width in texels
    int sourceWidth = 0;
    int blocksPerRow = 0;
    int blockRows = 0;
    std::vector<double> luminanceTimesSolidAngle; // per block, row-major
    std::vector<double> solidAngle;

    // Takes a texel's excess over a threshold (luminance excess x its solid angle) out of
    // its block: the base clamps every texel above the threshold to it.
    void removeExcess(std::uint32_t sourceIndex, double excessTimesSolidAngle);
    // The root mean square over the sphere of the blocks' mean luminance.
    double rms() const;
};

// The blocks of a width-wide equirect from its rows: rowBlockSums[y * blocks per row + b] is
// the luminance summed over row y's texels in block column b, rowSolidAngle[y] the solid
// angle of each texel of row y (brightCandidates fills them in its scan of the map).
BlockLuminance blockLuminanceFromRows(std::span<const double> rowBlockSums, std::span<const double> rowSolidAngle, int width, int scale);
// The same sums over blocks 2^(scale - fine.scale) times as wide (scale >= fine.scale), for mip.
BlockLuminance coarsenedBlocks(const BlockLuminance& fine, int scale, int mip);

// The block scale for mip `level`'s first samples on a width x height equirect: the source
// lod its median sample's pdf picks (prefilter_lod.glsl) relative to a texel at the
// equator, rounded, at least 0 and at most the image's log2(height).
int refinedSampleScale(const PrefilterSettings& settings, int level, int width, int height);

} // namespace iblab::bake
