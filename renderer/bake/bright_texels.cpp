#include "bake/bright_texels.hpp"
#include "bake/bright_texels_block.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <future>
#include <limits>
#include <map>
#include <string>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "bake/bake_passes.hpp"
#include "bake/exact_tiles.hpp"
#include "bake/near_lights.hpp"
#include "ibl/prefilter_lod.hpp"
#include "ibl/conventions.hpp"
#include "ibl/luminance.hpp"
#include "ibl/parallel_rows.hpp"
#include "io/error.hpp"

namespace iblab::bake {
namespace {

// Candidates strictly above threshold: a prefix, since they are sorted brightest first.
std::size_t countAbove(const BrightCandidates& c, float threshold)
{
    return std::size_t(std::partition_point(c.texels.begin(), c.texels.end(),
                                            [&](const BrightTexel& t) { return t.luminance > threshold; }) -
                       c.texels.begin());
}

// The distinct cells of a cellFaceSize cube among the first p candidates, for every p
// (index p): what a threshold that keeps those p merges them into, counted once for all.
std::vector<std::uint32_t> distinctCellsByPrefix(const BrightCandidates& c, int cellFaceSize)
{
    std::vector<std::uint32_t> counts(c.texels.size() + 1, 0);
    // One bit per cell (under a megabyte at a 1024 face): with a hash set of the cells the
    // threshold search took about twice as long, and this runs for every cell size of it.
    std::vector<bool> seen(6 * std::size_t(cellFaceSize) * std::size_t(cellFaceSize), false);
    for (std::size_t i = 0; i < c.texels.size(); ++i) {
        const std::uint64_t cell = brightCellOf(c.texels[i].direction, cellFaceSize);
        counts[i + 1] = counts[i] + (seen[cell] ? 0 : 1);
        seen[cell] = true;
    }
    return counts;
}

// The far field: lights further than kNearCells cells of a kFarFace cube from an output
// texel are summed as their cell's merged light (a point at its flux centre; the error of
// that is second order, (cell / distance)^2 of the cell's contribution, about 3% at 6 cells),
// nearer ones light by light. The mip-1 lobe's heavy tails reach tens of degrees, so a
// large lamp or softbox must be summed everywhere, but exactly only near it.
constexpr int kFarFace = 32;
constexpr double kNearCells = 6.0;
// The lights of a level, at most this many times its cap on far cells: an output texel near
// a cell sums each of its lights, and near a large area (a softbox) that is most of them.
constexpr std::size_t kLightsPerFarCell = 8;

int farFaceSize(int cellFaceSize) { return std::min(kFarFace, cellFaceSize); }

} // namespace

std::uint64_t brightCellOf(const glm::dvec3& direction, int faceSize)
{
    const glm::vec3 fuv = directionToCubeFaceUv(glm::vec3(direction));
    const int x = std::clamp(int(fuv.y * float(faceSize)), 0, faceSize - 1);
    const int row = std::clamp(int(fuv.z * float(faceSize)), 0, faceSize - 1);
    return (std::uint64_t(fuv.x) * std::uint64_t(faceSize) + std::uint64_t(row)) * std::uint64_t(faceSize) + std::uint64_t(x);
}

int brightCellFaceSize(double roughness)
{
    // A cell of a size-S face spans about 2 / S radians; alpha / 2 of it needs S >= 4 / alpha.
    // The lobe in l is about 2 alpha wide (theta_l = 2 theta_h), so a full cell at the lobe's
    // peak is summed about 2% low, and cells side by side sum an area as a midpoint rule at a
    // quarter of the lobe's width. Finer cells only raise the count, and with it the
    // threshold, leaving more of a large bright area to the samples. Never coarser than a 16
    // face: mips 4 and 5 sum their base over a 16 face's texels (exactSumTexels), and the
    // lights are kept no coarser than those.
    const double alpha = std::max(roughness * roughness, 1e-6);
    int size = 16;
    while (size < 1024 && size < 4.0 / alpha)
        size *= 2;
    return size;
}

namespace {

// The RMS over blocks of the map clamped at threshold. Texels outside the list are at most the
// floor, and the threshold is at least the floor: the list holds every texel the clamp changes.
double clampedBlocksRms(const BrightCandidates& candidates, float threshold, BlockLuminance blocks)
{
    for (const BrightTexel& t : candidates.texels)
        if (t.luminance > threshold)
            blocks.removeExcess(t.sourceIndex, (double(t.luminance) - double(threshold)) * t.solidAngle);
    return blocks.rms();
}

} // namespace

double clampedLuminanceRms(const BrightCandidates& candidates, float threshold, int mip)
{
    for (const BlockLuminance& blocks : candidates.refinedMipBlocks)
        if (blocks.mip == mip)
            return clampedBlocksRms(candidates, threshold, blocks);
    double squared = candidates.squaredLuminanceOutsideList;
    for (const BrightTexel& t : candidates.texels) {
        const double clamped = std::min(double(t.luminance), double(threshold));
        squared += clamped * clamped * t.solidAngle;
    }
    return std::sqrt(squared / (4.0 * kPi));
}

std::vector<glm::vec4> mergedBrightLights(const BrightCandidates& candidates, float threshold, int cellFaceSize)
{
    struct Cell {
        glm::dvec3 weightedDirection{0.0};
        glm::dvec3 flux{0.0};
    };
    std::map<std::uint64_t, Cell> cells;
    const std::size_t count = countAbove(candidates, threshold);
    for (std::size_t i = 0; i < count; ++i) {
        const BrightTexel& t = candidates.texels[i];
        const glm::dvec3 excess = t.radiance * (1.0 - double(threshold) / double(t.luminance)) * t.solidAngle;
        Cell& cell = cells[brightCellOf(t.direction, cellFaceSize)];
        cell.flux += excess;
        cell.weightedDirection += t.direction * double(luminance(glm::vec3(excess)));
    }
    std::vector<glm::vec4> lights;
    lights.reserve(2 * cells.size());
    for (const auto& [key, cell] : cells) {
        lights.emplace_back(glm::vec3(glm::normalize(cell.weightedDirection)), 0.0f);
        lights.emplace_back(glm::vec3(cell.flux), 0.0f);
    }
    return lights;
}

namespace {

// A level's block (prefilter_ggx.comp): the far cells first, two entries each,
// (direction, index of its first light), (flux, its light count), then its lights, two
// entries each, (direction, 0), (flux, 0), grouped by cell. Where the far cells are the
// lights themselves (the lobe is wide enough), the lights alone, and nearCos 2 (never near).
std::vector<glm::vec4> hierarchicalLights(const BrightCandidates& candidates, float threshold, int cellFaceSize, int& farCells)
{
    const std::vector<glm::vec4> lights = mergedBrightLights(candidates, threshold, cellFaceSize);
    const int farFace = farFaceSize(cellFaceSize);
    if (farFace == cellFaceSize) {
        farCells = int(lights.size() / 2);
        return lights;
    }
    struct Cell {
        glm::dvec3 weightedDirection{0.0};
        glm::dvec3 flux{0.0};
        std::vector<std::size_t> lights;
    };
    std::map<std::uint64_t, Cell> cells;
    for (std::size_t i = 0; i < lights.size(); i += 2) {
        const glm::dvec3 direction(lights[i]), flux(lights[i + 1]);
        Cell& cell = cells[brightCellOf(direction, farFace)];
        cell.flux += flux;
        cell.weightedDirection += direction * double(luminance(glm::vec3(flux)));
        cell.lights.push_back(i);
    }
    farCells = int(cells.size());
    std::vector<glm::vec4> block;
    block.reserve(2 * cells.size() + lights.size());
    std::vector<glm::vec4> grouped;
    grouped.reserve(lights.size());
    for (const auto& [key, cell] : cells) {
        block.emplace_back(glm::vec3(glm::normalize(cell.weightedDirection)), float(cells.size() + grouped.size() / 2));
        block.emplace_back(glm::vec3(cell.flux), float(cell.lights.size()));
        for (std::size_t i : cell.lights) {
            grouped.push_back(lights[i]);
            grouped.push_back(lights[i + 1]);
        }
    }
    block.insert(block.end(), grouped.begin(), grouped.end());
    return block;
}

} // namespace

// Cosine of the angle within which a far cell of a level is summed light by light (2: never).
float brightNearCos(int cellFaceSize)
{
    if (farFaceSize(cellFaceSize) == cellFaceSize)
        return 2.0f;
    return float(std::cos(kNearCells * 2.0 / farFaceSize(cellFaceSize)));
}

float brightThresholdFor(const BrightCandidates& candidates, const std::vector<double>& roughness, const std::vector<int>& caps)
{
    const std::size_t n = candidates.texels.size();
    auto thresholdAt = [&](std::size_t p) { return p < n ? candidates.texels[p].luminance : candidates.floorThreshold; };
    std::map<int, std::vector<std::uint32_t>> distinct; // by cell face size
    for (double r : roughness)
        for (int face : {brightCellFaceSize(r), farFaceSize(brightCellFaceSize(r))})
            distinct.try_emplace(face);
    // One face size per thread: each finds the cell of every candidate.
    std::vector<std::pair<const int, std::vector<std::uint32_t>>*> faces;
    for (auto& entry : distinct)
        faces.push_back(&entry);
    parallelRows(int(faces.size()), [&](int first, int end) {
        for (int i = first; i < end; ++i)
            faces[std::size_t(i)]->second = distinctCellsByPrefix(candidates, faces[std::size_t(i)]->first);
    });
    auto fits = [&](std::size_t p) {
        const std::size_t count = countAbove(candidates, thresholdAt(p));
        for (std::size_t i = 0; i < roughness.size(); ++i) {
            // The cap is on the far cells (every output texel sums each of them), the block
            // on everything the level uploads: 2 entries per far cell, 2 per light.
            const int cell = brightCellFaceSize(roughness[i]);
            const auto cap = std::size_t(std::max(0, caps[i]));
            const std::size_t lights = distinct.at(cell)[count];
            const std::size_t far = distinct.at(farFaceSize(cell))[count];
            const std::size_t entries = 2 * (lights + (farFaceSize(cell) == cell ? 0 : far));
            if (far > cap || lights > kLightsPerFarCell * cap || entries > std::size_t(2 * kMaxBrightLights))
                return false;
        }
        return true;
    };
    // The merged count grows with p: the largest p that fits, by bisection (p = 0 always fits).
    std::size_t lo = 0, hi = n;
    while (lo < hi) {
        const std::size_t mid = lo + (hi - lo + 1) / 2;
        if (fits(mid))
            lo = mid;
        else
            hi = mid - 1;
    }
    return thresholdAt(lo);
}

namespace {

// A base mip's texels as prefilter_ggx.comp's exact sum reads them: (direction, 0),
// (radiance x solid angle, solid angle).
std::vector<glm::vec4> exactSumTexels(const CubeImage& level)
{
    std::vector<glm::vec4> texels;
    texels.reserve(2 * level.texels.size());
    for (int face = 0; face < 6; ++face)
        for (int row = 0; row < level.size; ++row)
            for (int x = 0; x < level.size; ++x) {
                const ExactSumEntry entry = exactSumEntry(level, face, x, row);
                texels.emplace_back(entry.direction, 0.0f);
                texels.emplace_back(entry.flux, entry.solidAngle);
            }
    return texels;
}

// A level's per-tile cuts of its base's mip (exact_tiles.hpp), each list bound as a uniform
// block of `capacity` vec4 at its own start: at most capacity / 2 entries a list, starting at
// the driver's offset alignment, the buffer padded so that the last tile's block stays in it.
void addExactTiles(PrefilterBrightTexels::Level& level, const CubeImage& source, int outputFaceSize, int capacity)
{
    GLint alignmentBytes = 16;
    glGetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &alignmentBytes);
    const int alignmentVec4 = std::max(1, int((alignmentBytes + GLint(sizeof(glm::vec4)) - 1) / GLint(sizeof(glm::vec4))));
    ExactTiles tiles = exactSumTiles(source, outputFaceSize, capacity / 2, alignmentVec4, capacity);
    if (tiles.tilesPerEdge == 0)
        return; // a block too small for a tile's nearest texels: the level stays sampled
    level.exactTiles = gl::createBufferWith<glm::vec4>(tiles.buffer);
    level.exactTileFirst = std::move(tiles.first);
    level.exactTileCount = std::move(tiles.count);
    level.exactTilesPerEdge = tiles.tilesPerEdge;
}

} // namespace

int brightBlockCapacity(const PrefilterSettings& settings) { return settings.brightTexels > 0 ? 2 * kMaxBrightLights : 0; }

int brightTexelCap(const PrefilterSettings& settings, int level)
{
    // Mip 2 has a quarter of mip 1's texels, so eight times the far cells cost it twice what
    // mip 1's cost it. Four times left a dozen lamps of a few degrees (more far cells than 4N)
    // to mip 2's samples, 0.12-0.15 relative RMSE from the exact prefilter; eight times sums
    // them (bake_bright_gltest's ADozenLampsMeetThePerMipBoundAtEveryMip). Each further mip
    // has a quarter of the texels again, so four times the cells cost it what mip 2's cost
    // it. With 8N at every rough mip, mip 3's far cells capped the rough threshold and left
    // 400 small lamps in the rough mips' base; 32N at mip 3 sums them.
    if (level <= 1)
        return settings.brightTexels;
    const int shift = std::min(2 * (level - 2), 16);
    return int(std::min<std::int64_t>(std::int64_t(8 * settings.brightTexels) << shift, kMaxBrightLights));
}

double spikyBaseRatio(int scale, double exponent) { return std::exp2(exponent * double(scale)); }

bool spikyBase(const BrightCandidates& candidates, float threshold, int mip, double exponent, int coarser)
{
    const auto blocks = std::find_if(candidates.refinedMipBlocks.begin(), candidates.refinedMipBlocks.end(),
                                     [&](const BlockLuminance& b) { return b.mip == mip; });
    if (blocks == candidates.refinedMipBlocks.end())
        return false;
    const int scale = blocks->scale + coarser;
    const double overFootprint = clampedBlocksRms(candidates, threshold, coarser > 0 ? coarsenedBlocks(*blocks, scale, mip) : *blocks);
    return overFootprint > 0.0 && clampedLuminanceRms(candidates, threshold) > spikyBaseRatio(scale, exponent) * overFootprint;
}

BrightSplitPlan planBrightSplit(BrightCandidates candidates, const PrefilterSettings& settings)
{
    BrightSplitPlan plan;
    plan.levels.resize(std::size_t(std::max(0, settings.levels)));
    auto roughnessOf = [&](int level) { return level < settings.levels ? double(prefilterMipRoughness(settings, level)) : 0.0; };
    auto faceOf = [&](int level) { return std::max(settings.faceSize >> level, 1); };
    const bool tiled = settings.tileLights > 0;
    // Two groups, mip 1 and the rougher mips, each with the threshold its caps allow: the
    // blocks' caps (brightThresholdFor), and where the lights are tiled, the tiles' (mip 1's
    // band below its block's threshold; mip 2's lights, which have no block).
    plan.mip1LightsThreshold = brightThresholdFor(candidates, {roughnessOf(1)}, {brightTexelCap(settings, 1)});
    TileLights mip1Tiles, mip2Tiles;
    std::vector<double> blockRoughness;
    std::vector<int> blockCaps;
    for (int level = tiled ? 3 : 2; level < settings.levels; ++level)
        if (roughnessOf(level) > 0.0) {
            blockRoughness.push_back(roughnessOf(level));
            blockCaps.push_back(brightTexelCap(settings, level));
        }
    plan.roughThreshold = brightThresholdFor(candidates, blockRoughness, blockCaps);
    // Four times the caps where the base they leave is spiky at mip 2's footprint: a thousand
    // one-texel stars fill mip 3's 512 far cells, and mip 2, which shares the base, cannot go
    // below that threshold; mips 2 and 3 sampled them (docs/bake.md, "Dense star fields").
    if (plan.roughThreshold > candidates.floorThreshold && spikyBase(candidates, plan.roughThreshold, 2)) {
        for (int& cap : blockCaps)
            cap = std::min(kSpikyBaseCapFactor * cap, kMaxBrightLights);
        plan.roughThreshold = brightThresholdFor(candidates, blockRoughness, blockCaps);
    }
    // Mip 2's tiles on a thread of their own beside mip 1's (each a few milliseconds).
    std::future<TileLights> mip2Planned;
    if (tiled && roughnessOf(2) > 0.0) // reach: the hemisphere, beyond which a light's weight is 0
        mip2Planned = std::async(std::launch::async, [&] {
            return planTileLights(candidates, std::numeric_limits<float>::infinity(), roughnessOf(2), faceOf(2), settings.tileLights, 0.5 * kPi,
                                  plan.roughThreshold);
        });
    plan.mip1Threshold = plan.mip1LightsThreshold;
    if (tiled && roughnessOf(1) > 0.0) {
        mip1Tiles = planTileLights(candidates, plan.mip1LightsThreshold, roughnessOf(1), faceOf(1), settings.tileLights, bandReach(roughnessOf(1)));
        // Mip 1's band the same where its cap leaves the base spiky: thousands of one-texel
        // stars (or a few hundred packed near a pole) fill its lists past the cap.
        if (mip1Tiles.threshold > candidates.floorThreshold && spikyBase(candidates, mip1Tiles.threshold, 1))
            mip1Tiles = planTileLights(candidates, plan.mip1LightsThreshold, roughnessOf(1), faceOf(1), kSpikyBaseCapFactor * settings.tileLights,
                                       bandReach(roughnessOf(1)), 0.0f, true);
        plan.mip1Threshold = std::min(mip1Tiles.threshold, plan.mip1LightsThreshold);
    }
    if (mip2Planned.valid()) {
        mip2Tiles = mip2Planned.get();
        // Lists four times as long where the cap left mip 2's base spiky and the rough blocks
        // allow a lower threshold: a few hundred one-texel stars fill the hemisphere's lists just
        // past the cap (docs/bake.md, "Dense star fields"). Maps of large areas never pay for it.
        if (mip2Tiles.threshold > plan.roughThreshold && spikyBase(candidates, mip2Tiles.threshold, 2))
            mip2Tiles = planTileLights(candidates, std::numeric_limits<float>::infinity(), roughnessOf(2), faceOf(2),
                                       kSpikyBaseCapFactor * settings.tileLights, 0.5 * kPi, plan.roughThreshold, true);
        plan.roughThreshold = mip2Tiles.threshold;
    }
    for (int level = 1; level < settings.levels; ++level) {
        const double roughness = roughnessOf(level);
        if (!(roughness > 0.0))
            continue;
        BrightSplitPlan::Level& l = plan.levels[std::size_t(level)];
        l.split = true;
        l.threshold = level == 1 ? plan.mip1Threshold : plan.roughThreshold;
        if (level == 1)
            l.tiles = std::move(mip1Tiles);
        if (level == 2 && tiled)
            l.tiles = std::move(mip2Tiles);
        else
            l.block = hierarchicalLights(candidates, level == 1 ? plan.mip1LightsThreshold : l.threshold, brightCellFaceSize(roughness), l.farCells);
        // Mips 1 and 2 (kLastRefinedMip). Mip 3's 144 samples meet the bound without it; under
        // an earlier rule (a spread against T) refining it took every texel, and it has not
        // been tried under this one.
        if (level <= kLastRefinedMip && settings.refineFactor > 1) {
            const double baseRms = clampedLuminanceRms(candidates, l.threshold, level);
            l.refineSpread = float(double(settings.refineSpread) * baseRms);
            l.refineError = float(double(settings.refineError) * baseRms);
            // Four times as many where the base keeps one-texel lights or lines, or lines a few
            // texels wide (kRefineSpikyExponent): star fields past what the lists hold sampled them
            // at 0.043-0.050 at mip 2, a grid of one-texel lines past even the candidates' larger
            // cap read 0.051 at mip 1 (0.039 so), 4-texel meridians on a 2048-wide map 0.055 (0.032).
            // Mip 1's over blocks twice as wide too: lines half a footprint wide or more read
            // at most sqrt(2) over its own blocks, under their gate, but more over blocks
            // twice as wide (8-texel meridians on a 4096-wide map 1.41 and 2.0, against gates
            // of 1.41 and 1.54: mip 1 0.055 refined eightfold, 0.033 so).
            const bool spiky = spikyBase(candidates, l.threshold, level, kRefineSpikyExponent) ||
                               (level == 1 && spikyBase(candidates, l.threshold, level, kRefineSpikyExponent, 1));
            l.refineFactor = spiky ? kSpikyBaseCapFactor * settings.refineFactor : settings.refineFactor;
        }
    }
    plan.meanLuminance = candidates.meanLuminance;
    if (candidates.sourceWidth > 0) {
        plan.sourceWidth = candidates.sourceWidth;
        plan.sourceHeight = candidates.sourceHeight;
        plan.edgeTexels = brightEdgeTexels(candidates, plan.mip1Threshold, plan.roughThreshold);
    }
    return plan;
}

PrefilterBrightTexels splitBrightTexels(BakePasses& passes, const BakedTexture& environment, const BrightSplitPlan& plan,
                                        const PrefilterSettings& settings, GLuint equirectTexture)
{
    PrefilterBrightTexels out;
    const int capacity = brightBlockCapacity(settings);
    GLint maxBlockBytes = 0;
    glGetIntegerv(GL_MAX_UNIFORM_BLOCK_SIZE, &maxBlockBytes);
    if (GLint(capacity * sizeof(glm::vec4)) > maxBlockBytes)
        throw Error("prefilter", "the bright-texel split needs a " + std::to_string(capacity * sizeof(glm::vec4)) +
                                     "-byte uniform block; this GL driver allows " + std::to_string(maxBlockBytes) +
                                     " (--prefilter-bright-texels 0 turns the split off)");
    out.meanLuminance = plan.meanLuminance;
    const float mip1Threshold = plan.mip1Threshold, roughThreshold = plan.roughThreshold;
    // Two groups' bases, or one where their thresholds agree, each from the finest level its
    // mips read: mip 1's refined samples read a level finer than the rougher mips ever do.
    std::vector<float> baseThresholds = {mip1Threshold};
    std::vector<int> topLevels;
    if (roughThreshold != mip1Threshold) {
        baseThresholds.push_back(roughThreshold);
        topLevels = {splitBaseTopLevel(settings, environment.size, environment.levels, 1, 1),
                     splitBaseTopLevel(settings, environment.size, environment.levels, 2)};
    } else {
        topLevels = {splitBaseTopLevel(settings, environment.size, environment.levels)};
    }
    for (int top : topLevels)
        out.bases.push_back(createCubeTexture(environment.internalFormat, environment.size >> top, environment.levels - top));
    std::vector<std::uint8_t> marks;
    if (equirectTexture != 0 && plan.nearLightsFaceSize != environment.size)
        marks = nearLightsMarks(plan, environment.size);
    const std::vector<std::uint8_t>& nearMarks = plan.nearLightsFaceSize == environment.size ? plan.nearLightsMarks : marks;
    NearLights nearLights;
    if (equirectTexture != 0 && !nearMarks.empty())
        nearLights = {equirectTexture, &nearMarks};
    passes.clampedBases(environment, out.bases, baseThresholds, nearLights);
    auto baseFor = [&](float threshold) { return threshold == mip1Threshold ? 0 : 1; };
    out.levels.resize(plan.levels.size());
    for (std::size_t level = 1; level < plan.levels.size(); ++level) {
        const BrightSplitPlan::Level& planned = plan.levels[level];
        if (!planned.split)
            continue;
        const float roughness = prefilterMipRoughness(settings, int(level));
        PrefilterBrightTexels::Level& l = out.levels[level];
        l.threshold = planned.threshold;
        l.base = baseFor(l.threshold);
        l.count = planned.farCells;
        l.capacity = capacity;
        // GL leaves reads undefined where the bound range is shorter than the block: padded.
        std::vector<glm::vec4> padded(std::size_t(capacity), glm::vec4(0.0f));
        std::copy(planned.block.begin(), planned.block.begin() + std::ptrdiff_t(std::min(planned.block.size(), padded.size())), padded.begin());
        l.texels = gl::createBufferWith<glm::vec4>(padded);
        if (const int exact = exactSumSourceLevel(settings, environment.size, environment.levels, roughness); exact >= 0) {
            std::vector<glm::vec4> texels = exactSumTexels(readCubeLevel(out.bases[std::size_t(l.base)], exact - topLevels[std::size_t(l.base)]));
            l.exactCount = int(texels.size() / 2);
            // A uniform block reads undefined past a bound range shorter than itself: padded.
            texels.resize(std::max(texels.size(), std::size_t(passes.exactTableCapacity(settings))), glm::vec4(0.0f));
            l.exactTexels = gl::createBufferWith<glm::vec4>(texels);
        } else if (const int tiled = tiledExactSumSourceLevel(settings, environment.size, environment.levels, roughness);
                   tiled >= 0 && passes.exactTableCapacity(settings) > 0) {
            addExactTiles(l, readCubeLevel(out.bases[std::size_t(l.base)], tiled - topLevels[std::size_t(l.base)]),
                          std::max(settings.faceSize >> level, 1), passes.exactTableCapacity(settings));
        }
        // A level that sums its base exactly has no samples to refine.
        if (l.exactCount == 0 && l.exactTilesPerEdge == 0) {
            l.refineSpread = planned.refineSpread;
            l.refineError = planned.refineError;
            l.refineFactor = planned.refineFactor;
        }
        if (planned.tiles.tilesPerEdge > 0) {
            l.tileLights = gl::createBufferWith<glm::vec4>(planned.tiles.buffer);
            l.tileLightsPerEdge = planned.tiles.tilesPerEdge;
        }
    }
    return out;
}

PrefilterBrightTexels splitBrightTexels(BakePasses& passes, const BakedTexture& environment, const ImageRGB32F& equirect,
                                        const PrefilterSettings& settings, GLuint equirectTexture)
{
    BrightCandidates candidates = equirect.empty()
                                      ? brightCandidates(readCubeLevel(environment, 0), settings.brightThreshold, kMaxBrightCandidates)
                                      : splitCandidates(equirect, settings);
    return splitBrightTexels(passes, environment, planBrightSplit(std::move(candidates), settings), settings, equirectTexture);
}


} // namespace iblab::bake
