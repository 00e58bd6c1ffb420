#pragma once
// The prefilter's split of the environment into a bounded base and its brightest texels
// (docs/bake.md, "The prefilter's estimator"). A small, very bright source (a sun) is what a
// sample table shared by every texel cannot integrate: each output texel sees it through
// the same few samples, and the result carries the table's pattern. So every source texel
// whose luminance exceeds a threshold T keeps only T (its chroma unchanged), and its excess
// is summed exactly, as a point of light with the excess times the texel's solid angle as
// its flux, by every output texel with the GGX weight itself. The base, whose largest value
// is T, is importance-sampled as before.
//
// The bright texels are the float equirect's (the map as loaded), not the environment
// cube's: a half-float cube stores a sun of 1e6 as at most 65504 and loses its flux. The
// base is the cube's level 0 with every texel clamped to T, from the level nearest the
// finest its samples read (splitBaseTopLevel); near the bright texels it is the map clamped
// and resampled as the cube was (near_lights.hpp), so that nothing the lights hold stays in it.
//
// The cost of the exact sum is (output texels) x (lights), and mip 1 has four times the texels
// of mip 2, so each mip gets its own list: texels closer together than half of alpha radians
// (a quarter of the lobe's width in l) are merged into one light at their flux-weighted
// centre (which keeps the sum's first moment; the error is second order, about 2% at the
// lobe's peak), and those lights are grouped again in the cells of a 32^2-per-face cube: an output
// texel sums a cell further than 6 cells from it as one light (the far field of the lobe's
// heavy tail), and a nearer cell light by light (bright_texels_block.hpp). brightTexelCap
// bounds the far cells of each mip (mip 1: PrefilterSettings::brightTexels, mip 2 8 times as
// many, each further mip 4 times the one before) and its lights to 8 times that. T is set
// per group of mips (mip 1; mips 2 and up) to the lowest value, at least brightThreshold x
// the mean luminance, at which the caps (and the tiles' caps) hold; a group with its own T
// has its own base.
//
// Mips 1 and 2 also list lights per tile of output texels (tile_lights.hpp): mip 1 a band
// below its block's T, down to a lower threshold at which its base is clamped; mip 2 all of
// its lights, in place of a block. Lamps and thin lines that a cap on a block every texel sums
// would leave to the samples are summed there.
//
// Mip 1's cap leaves most of a large bright area (a softbox, a row of lamps) in its base,
// where its 8 samples, each reading a mip that the area's edge cuts, alias the edge (mip 2's
// 24 likewise, less). A texel of mips 1 and 2 (kLastRefinedMip) whose samples' luminances
// spread by more than refineSpread x the base's RMS luminance is sampled again with
// refineFactor times as many (prefilter_ggx.comp); the
// RMS, not T, sets the scale, because the error that matters is against the level's own
// magnitude (the per-mip relative RMSE), and T sits at the floor on maps without large areas.
// The RMS is of the base as the samples see it, averaged in blocks as wide as their median
// footprint (block_luminance.hpp): thin bright lines, diluted in every sample, otherwise
// spread too little against it to be refined.
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "bake/baked_texture.hpp"
#include "bake/block_luminance.hpp"
#include "bake/tile_lights.hpp"
#include "bake/bake_settings.hpp"
#include "gl/handles.hpp"
#include "ibl/image.hpp"

namespace iblab::bake {

class BakePasses;

// A source texel above the floor threshold (brightThreshold x mean).
struct BrightTexel {
    glm::dvec3 direction;
    glm::dvec3 radiance;
    double solidAngle = 0.0;
    float luminance = 0.0f; // Rec. 709 weights
    std::uint32_t sourceIndex = 0; // row-major in the equirect it came from
};

struct BrightCandidates {
    std::vector<BrightTexel> texels; // brightest first (ties in texel order: deterministic)
    float floorThreshold = 0.0f;     // brightThreshold x meanLuminance
    float meanLuminance = 0.0f;      // over the sphere, by solid angle
    // The integral of luminance^2 over the texels not in `texels` (all at most the floor).
    double squaredLuminanceOutsideList = 0.0;
    // More texels were above brightThreshold x meanLuminance than the cap kept: the floor is
    // the first one left out.
    bool truncated = false;
    // Per refined mip, the equirect's luminance in blocks as wide as its samples' footprint
    // (block_luminance.hpp); none where the candidates came from a cube.
    std::vector<BlockLuminance> refinedMipBlocks;
    int sourceWidth = 0; // of the equirect the texels came from (0: a cube)
    int sourceHeight = 0;
};

// The root mean square over the sphere of the luminance clamped at threshold (>= the floor):
// the scale of the base a level with that threshold samples. With mip > 0 and its blocks
// among the candidates', of the base averaged over those blocks (as the mip's samples see it).
double clampedLuminanceRms(const BrightCandidates& candidates, float threshold, int mip = 0);

// Whether the map clamped at threshold is spiky at a refined mip's scale: its RMS luminance at
// full resolution above spikyBaseRatio times its RMS over that mip's samples' footprint
// (clampedLuminanceRms with and without mip). Over blocks w texels wide, isolated one-texel
// lights far brighter than their neighbourhood read about w, since a block dilutes them
// w^2-fold; one-texel lines read sqrt(w), diluted w-fold; skies and large bright areas read
// about 1 (1.0-1.25 on the bundled maps). false where the mip has no blocks.
// exponent: the ratio is spikyBaseRatio(scale, exponent).
// coarser: over blocks 2^coarser times as wide as the mip's (and their ratio).
bool spikyBase(const BrightCandidates& candidates, float threshold, int mip, double exponent = 0.25, int coarser = 0);
// The ratio above which a base is spiky over blocks w = 2^scale texels wide: w^exponent. The
// caps take w^(1/4), the geometric middle of a smooth base's 1 and a one-texel line's sqrt(w),
// so that lines as thin as a texel count as well as points (2 at mip 2's blocks of 16 on a
// 1024 x 512 map, 1.41 at mip 1's of 4, where a one-texel line reads 2.0 and the bundled maps
// at most 1.10). The refined sets take w^(1/8), the middle of 1 and that: lines a few texels
// wide (4 texels on a 2048-wide map read 1.41 over mip 1's blocks of 8) are refined more, with
// no list to take them; the bundled maps read at most 1.10 and 1.25 against 1.19 and 1.41.
// Mip 1's refined set is tested over blocks twice as wide as well (coarser = 1): a line a
// texels wide reads sqrt(w / a), at most sqrt(2) once it is half a footprint wide or more, but
// sqrt(2 w / a), up to 2, over those, above their gate up to about 0.85 w; the bundled maps
// read at most 1.23 there (studio) against 1.30, the pmndrs maps 1.12.
inline constexpr double kRefineSpikyExponent = 0.125;
double spikyBaseRatio(int scale, double exponent = 0.25);
// Mips 1 and 2 list this many times the cap, the rough mips' blocks allow this many times
// their far cells, and mips 1 and 2 refine this many times the samples, where the base the
// cap leaves is spiky (planBrightSplit).
inline constexpr int kSpikyBaseCapFactor = 4;

// Every texel of the equirect (exact row solid angles) or of a cube level above
// thresholdOverMean x the mean luminance, at most maxCandidates of them (the brightest;
// the floor threshold then rises to the first one left out).
// With blocks, also the map's luminance in blocks of 2^blocks->scale texels, from the same scan.
// keepMore: where the cap left texels out and keepMore says so of the candidates kept, keeps
// kSpikyCandidatesFactor times as many instead, from the same scan.
BrightCandidates brightCandidates(const ImageRGB32F& equirect, float thresholdOverMean, int maxCandidates,
                                  BlockLuminance* blocks = nullptr,
                                  const std::function<bool(const BrightCandidates&)>& keepMore = {});
BrightCandidates brightCandidates(const CubeImage& level0, float thresholdOverMean, int maxCandidates);

// The lights of the candidates strictly above threshold: their excess over it, merged in the
// texels of a cellFaceSize cube (two vec4 each: (direction, 0), (flux rgb, 0)), cells in order.
std::vector<glm::vec4> mergedBrightLights(const BrightCandidates& candidates, float threshold, int cellFaceSize);

// The texel of a cellFaceSize cube that direction falls in, (face, row, column) row-major:
// the cell that merges the lights there.
std::uint64_t brightCellOf(const glm::dvec3& direction, int cellFaceSize);

// The face size of the cube whose texels merge lights for a lobe of this roughness
// (half of alpha radians across, a power of two from 16 to 1024).
int brightCellFaceSize(double roughness);

// The lowest threshold (at least the floor) at which each roughness's far cells fit under its
// cap, its lights under 8 times the cap, and its block in kMaxBrightLights lights.
float brightThresholdFor(const BrightCandidates& candidates, const std::vector<double>& roughness, const std::vector<int>& caps);

// The split on the GPU, for BakePasses::prefilter. Per prefiltered mip (index = level; level
// 0, the mirror, has none): the base it samples, its lights, their count and the uniform
// block's size.
struct PrefilterBrightTexels {
    std::vector<BakedTexture> bases; // one per distinct threshold
    struct Level {
        int base = -1; // into bases; -1: no split at this level
        gl::Buffer texels; // bright_texels_block.hpp's layout
        int count = 0;     // far cells
        int capacity = 0; // entries (prefilter_ggx.comp's BRIGHT_CAPACITY)
        float threshold = 0.0f;
        // Mips 1 and 2 (kLastRefinedMip): the luminance spread among a sampled texel's samples
        // above which it takes PrefilterSettings::refineFactor times as many (refineSpread x
        // the base's RMS); < 0: never. Or the standard error of their mean above refineError
        // (PrefilterSettings::refineError x the same RMS).
        float refineSpread = -1.0f;
        float refineError = 0.0f;
        // The refined set's multiple of the first: PrefilterSettings::refineFactor, or at mip 2
        // kSpikyBaseCapFactor times it where its base is spiky (planBrightSplit).
        int refineFactor = 1;
        // Mips 1 and 2: their lights per tile (tile_lights.hpp's buffer); 0 tiles: none.
        gl::Buffer tileLights;
        int tileLightsPerEdge = 0;
        // The base's mip this level sums exactly (exactSumSourceLevel), two entries per
        // texel: (direction, 0), (radiance x solid angle, solid angle); 0 texels: sampled.
        gl::Buffer exactTexels;
        int exactCount = 0;
        // Or per-tile cuts of it (tiledExactSumSourceLevel; exact_tiles.hpp's lists, in one
        // buffer): tile t's list starts at vec4 exactTileFirst[t] and has exactTileCount[t]
        // entries; 0 tiles per edge: none.
        gl::Buffer exactTiles;
        std::vector<int> exactTileFirst;
        std::vector<int> exactTileCount;
        int exactTilesPerEdge = 0;
    };
    std::vector<Level> levels;
    float meanLuminance = 0.0f;
};

// The most candidates the split keeps (the brightest; brightCandidates' maxCandidates), and
// where that many leave a spiky base behind (a field of tens of thousands of one-texel stars
// on a 3000- or 4096-wide map, a grid of one-texel lines, thousands of lamps a few texels
// wide), kSpikyCandidatesFactor times as many (splitCandidates): 262144, a sixteenth of a
// 4096-wide map's texels. A grid of lines of 130000 texels read 0.039 at mip 1 with four
// times the cap, 0.010 so; 2000 squares 8 texels wide on a 4096-wide map 0.040 and 0.004.
inline constexpr int kMaxBrightCandidates = 1 << 14;
inline constexpr int kSpikyCandidatesFactor = 16;

// The split's host work, which needs no GL: the thresholds and, per prefiltered mip (index =
// level), its block of lights and its refinement spread. A bake runs it on a worker thread
// beside the environment's GPU passes where the GPU is hardware (bake_job.cpp).
struct BrightSplitPlan {
    struct Level {
        bool split = false; // false: the mirror level, which has no lobe to weight lights by
        float threshold = 0.0f;
        std::vector<glm::vec4> block; // bright_texels_block.hpp's layout, unpadded
        int farCells = 0;
        float refineSpread = -1.0f; // Level::refineSpread where the level samples its base
        float refineError = 0.0f;   // Level::refineError likewise
        int refineFactor = 1;       // Level::refineFactor likewise
        // Mips 1 and 2: their lights per tile (tile_lights.hpp); mip 2's instead of a block.
        TileLights tiles;
    };
    // Mip 1's base threshold (its band's, tile_lights.hpp, where it has one) and its block's.
    float mip1Threshold = 0.0f;
    float mip1LightsThreshold = 0.0f;
    float roughThreshold = 0.0f;
    float meanLuminance = 0.0f;
    std::vector<Level> levels;
    // The equirect's bright texels at the edge of a bright area (row-major indices,
    // near_lights.hpp's brightEdgeTexels), near which the bases are resampled from the map
    // clamped (NearLights in bake_passes.hpp); empty where the candidates came from a cube.
    std::vector<std::uint32_t> edgeTexels;
    int sourceWidth = 0;
    int sourceHeight = 0;
    // Where the plan knew the environment cube's face size: near_lights.hpp's marks on its
    // level 0, made with the plan (on a worker thread, beside the GPU's passes) instead of in
    // the split's GL step.
    std::vector<std::uint8_t> nearLightsMarks;
    int nearLightsFaceSize = 0;
};
// The candidates of the split from the float map (the equirect as loaded).
BrightCandidates splitCandidates(const ImageRGB32F& equirect, const PrefilterSettings& settings);
BrightSplitPlan planBrightSplit(BrightCandidates candidates, const PrefilterSettings& settings);

// Builds the split from its plan: the bases on the GPU from the cube's level 0
// (BakePasses::clampedBases), the lights' blocks and the exact sums' tables. With
// equirectTexture (the map the environment cube was resampled from, as uploaded), the bases
// near the bright texels are resampled from the map clamped, so that nothing the lights hold
// stays in them.
// Throws iblab::Error where the driver's uniform blocks cannot hold the lights.
PrefilterBrightTexels splitBrightTexels(BakePasses& passes, const BakedTexture& environment, const BrightSplitPlan& plan,
                                        const PrefilterSettings& settings, GLuint equirectTexture = 0);
// Plans and builds it in one: the candidates from the equirect when the job still holds it
// (else from the cube's level 0).
PrefilterBrightTexels splitBrightTexels(BakePasses& passes, const BakedTexture& environment, const ImageRGB32F& equirect,
                                        const PrefilterSettings& settings, GLuint equirectTexture = 0);

// The mip of a base (face baseSize, baseLevels mips) that level `roughness` sums exactly
// instead of sampling (PrefilterSettings::exactSumTexels): the smallest whose texels are at
// most alpha / 2 across at a face centre and whose face is at least 8 (the finest where
// none is), or -1 where it has more than exactSumTexels texels.
int exactSumSourceLevel(const PrefilterSettings& settings, int baseSize, int baseLevels, double roughness);
// The mip that level `roughness` sums over per-tile cuts (exact_tiles.hpp) instead of
// sampling: exactSumSourceLevel's choice where that has more than exactSumTexels texels and at
// most exactSumTiledTexels; else -1.
int tiledExactSumSourceLevel(const PrefilterSettings& settings, int baseSize, int baseLevels, double roughness);

// The environment level that the split's bases start at: the one nearest the finest any
// split mip reads (the smallest lod its samples' pdfs pick, at the largest texel; the level
// an exact sum reads), so that a base holds no level nothing samples. readSource's lod,
// relative to the base's own face, then names the same level as it does in the environment.
// Over mips firstMip..lastMip (-1: the last), for a base that only those mips read.
int splitBaseTopLevel(const PrefilterSettings& settings, int environmentSize, int environmentLevels, int firstMip = 1,
                      int lastMip = -1);

// The most entries pairs of a level's block (far cells and lights together): GL guarantees
// 16 KB uniform blocks, llvmpipe allows 64 KB (4096 entries); a driver with less is told so.
inline constexpr int kMaxBrightLights = 2048;
// The last mip whose sampled texels are refined where their samples disagree
// (PrefilterSettings::refineFactor): mips 1 and 2, whose caps leave large bright areas and
// thin bright lines to their 8 and 24 samples.
inline constexpr int kLastRefinedMip = 2;
// The most far cells mip `level` (>= 1) sums for every texel (bright_texels_block.hpp).
int brightTexelCap(const PrefilterSettings& settings, int level);

} // namespace iblab::bake
