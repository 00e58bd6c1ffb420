#include "bake/bright_texels.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "bake/block_luminance.hpp"
#include "ibl/conventions.hpp"
#include "ibl/equirect.hpp"
#include "ibl/luminance.hpp"
#include "ibl/parallel_rows.hpp"

// The split's candidates: every texel of the map above the floor, brightest first, from one
// scan that also gives the map's mean, its squared luminance and the refined mips' blocks.
namespace iblab::bake {
namespace {

// Solid angle of texel (x, row) of a size^2 face: its area (2 / size)^2 on the face plane at
// distance 1, foreshortened by 1 / r^3 at its centre (r = the centre's distance). Within
// O(1 / size^2) of the exact value (summed over the sphere: 4e-6 of 4 pi at 256, 4e-3 at 8),
// which is all the threshold needs.
double approximateTexelSolidAngle(int x, int row, int size)
{
    const double u = 2.0 * (x + 0.5) / size - 1.0, v = 2.0 * (row + 0.5) / size - 1.0;
    const double r2 = 1.0 + u * u + v * v;
    return 4.0 / (double(size) * size * r2 * std::sqrt(r2));
}

// The exact one, for the flux of a bright texel: the corner differences of the solid angle
// of the face rectangle [0, a] x [0, b], atan(a b / sqrt(a^2 + b^2 + 1)).
double texelSolidAngle(int x, int row, int size)
{
    auto corner = [](double a, double b) { return std::atan2(a * b, std::sqrt(a * a + b * b + 1.0)); };
    const double u0 = 2.0 * x / size - 1.0, u1 = 2.0 * (x + 1) / size - 1.0;
    const double v0 = 2.0 * row / size - 1.0, v1 = 2.0 * (row + 1) / size - 1.0;
    return corner(u1, v1) - corner(u0, v1) - corner(u1, v0) + corner(u0, v0);
}

} // namespace

namespace {

// A texel above the floor, by its index in scan order, before its direction is computed.
struct RankedTexel {
    float luminance;
    std::uint32_t index;
    bool operator<(const RankedTexel& o) const { return luminance != o.luminance ? luminance > o.luminance : index < o.index; }
};

// Keeps the brightest maxCandidates (ties in texel order), brightest first, and raises the
// floor to the first one left out; only those kept become BrightTexels (makeTexel(index)),
// so that a map with a million texels above the floor sorts and converts 16384 of them.
template <class MakeTexel>
BrightCandidates finishCandidates(std::vector<RankedTexel> ranked, float floorThreshold, double luminanceIntegral,
                                  double squaredLuminanceIntegral, int maxCandidates, MakeTexel makeTexel)
{
    BrightCandidates c;
    c.meanLuminance = float(luminanceIntegral / (4.0 * kPi));
    c.floorThreshold = floorThreshold;
    const auto keep = std::size_t(std::max(0, maxCandidates));
    if (ranked.size() > keep) {
        c.truncated = true;
        std::nth_element(ranked.begin(), ranked.begin() + std::ptrdiff_t(keep), ranked.end());
        c.floorThreshold = ranked[keep].luminance;
        ranked.resize(keep);
        // Only texels strictly above the floor are lights: drop the ties with it too.
        std::erase_if(ranked, [&](const RankedTexel& t) { return !(t.luminance > c.floorThreshold); });
    }
    std::sort(ranked.begin(), ranked.end());
    c.texels.reserve(ranked.size());
    double squaredInList = 0.0;
    for (const RankedTexel& t : ranked) {
        c.texels.push_back(makeTexel(t.index));
        squaredInList += double(c.texels.back().luminance) * double(c.texels.back().luminance) * c.texels.back().solidAngle;
    }
    c.squaredLuminanceOutsideList = std::max(0.0, squaredLuminanceIntegral - squaredInList);
    return c;
}

} // namespace

BrightCandidates brightCandidates(const ImageRGB32F& equirect, float thresholdOverMean, int maxCandidates, BlockLuminance* blocks,
                                  const std::function<bool(const BrightCandidates&)>& keepMore)
{
    const int w = equirect.width, h = equirect.height;
    const auto rows = std::size_t(std::max(0, h));
    std::vector<double> rowSolidAngle(rows), rowSum(rows), rowSquaredSum(rows);
    std::vector<float> lum(std::size_t(std::max(0, w)) * rows);
    const int blockScale = blocks ? blocks->scale : 0;
    const std::size_t blocksPerRow = blocks ? std::size_t((w + (1 << blockScale) - 1) >> blockScale) : 0;
    std::vector<double> rowBlockSums(blocksPerRow * rows, 0.0);
    // Rows in parallel, their sums added in row order after, so that the result does not
    // depend on the thread count.
    parallelRows(h, [&](int firstRow, int endRow) {
        for (int y = firstRow; y < endRow; ++y) {
            rowSolidAngle[std::size_t(y)] = equirectTexelSolidAngle(y, w, h);
            const float* rgb = &equirect.texels[equirect.offset(0, y)];
            float* rowLum = &lum[std::size_t(y) * std::size_t(w)];
            double row = 0.0, rowSquared = 0.0;
            for (int x = 0; x < w; ++x) {
                rowLum[x] = luminance(&rgb[3 * x]);
                const double positive = std::max(0.0f, rowLum[x]);
                row += positive;
                rowSquared += positive * positive;
                if (blocks)
                    rowBlockSums[std::size_t(y) * blocksPerRow + std::size_t(x >> blockScale)] += positive;
            }
            rowSum[std::size_t(y)] = row;
            rowSquaredSum[std::size_t(y)] = rowSquared;
        }
    });
    if (blocks)
        *blocks = blockLuminanceFromRows(rowBlockSums, rowSolidAngle, w, blockScale);
    double flux = 0.0, squared = 0.0;
    for (std::size_t y = 0; y < rows; ++y) {
        flux += rowSum[y] * rowSolidAngle[y];
        squared += rowSquaredSum[y] * rowSolidAngle[y];
    }
    const float floorThreshold = thresholdOverMean * float(flux / (4.0 * kPi));
    std::vector<RankedTexel> ranked;
    for (std::size_t i = 0; i < lum.size(); ++i)
        if (lum[i] > floorThreshold)
            ranked.push_back({lum[i], std::uint32_t(i)});
    auto makeTexel = [&](std::uint32_t i) {
        const int x = int(i % std::uint32_t(w)), y = int(i / std::uint32_t(w));
        return BrightTexel{equirectTexelDirection(x, y, w, h), glm::dvec3(equirect.at(x, y)), rowSolidAngle[std::size_t(y)], lum[i], i};
    };
    std::vector<RankedTexel> every;
    if (keepMore && ranked.size() > std::size_t(std::max(0, maxCandidates)))
        every = ranked;
    BrightCandidates candidates = finishCandidates(std::move(ranked), floorThreshold, flux, squared, maxCandidates, makeTexel);
    if (!every.empty() && keepMore(candidates))
        candidates = finishCandidates(std::move(every), floorThreshold, flux, squared, kSpikyCandidatesFactor * maxCandidates, makeTexel);
    candidates.sourceWidth = w;
    candidates.sourceHeight = h;
    return candidates;
}

BrightCandidates brightCandidates(const CubeImage& level0, float thresholdOverMean, int maxCandidates)
{
    const int f = level0.size;
    double flux = 0.0, squared = 0.0;
    for (int face = 0; face < 6; ++face)
        for (int row = 0; row < f; ++row)
            for (int x = 0; x < f; ++x) {
                const double positive = std::max(0.0f, luminance(level0.rgb(face, x, row)));
                const double solidAngle = approximateTexelSolidAngle(x, row, f);
                flux += positive * solidAngle;
                squared += positive * positive * solidAngle;
            }
    const float floorThreshold = thresholdOverMean * float(flux / (4.0 * kPi));
    std::vector<RankedTexel> ranked;
    const auto faceTexels = std::uint32_t(f) * std::uint32_t(f);
    for (std::uint32_t i = 0; i < 6 * faceTexels; ++i) {
        const int face = int(i / faceTexels), row = int(i % faceTexels) / f, x = int(i % faceTexels) % f;
        if (const float lum = luminance(level0.rgb(face, x, row)); lum > floorThreshold && std::isfinite(lum))
            ranked.push_back({lum, i});
    }
    return finishCandidates(std::move(ranked), floorThreshold, flux, squared, maxCandidates, [&](std::uint32_t i) {
        const int face = int(i / faceTexels), row = int(i % faceTexels) / f, x = int(i % faceTexels) % f;
        const glm::vec3 rgb = level0.rgb(face, x, row);
        return BrightTexel{glm::dvec3(level0.texelDirection(face, x, row)), glm::dvec3(rgb), texelSolidAngle(x, row, f), luminance(rgb)};
    });
}

BrightCandidates splitCandidates(const ImageRGB32F& equirect, const PrefilterSettings& settings)
{
    std::vector<std::pair<int, int>> refinedScales; // (mip, block scale)
    if (settings.refineFactor > 1)
        for (int level = 1; level <= std::min(kLastRefinedMip, settings.levels - 1); ++level)
            if (prefilterMipRoughness(settings, level) > 0.0f)
                refinedScales.emplace_back(level, refinedSampleScale(settings, level, equirect.width, equirect.height));
    if (refinedScales.empty())
        return brightCandidates(equirect, settings.brightThreshold, kMaxBrightCandidates);
    // The finest blocks from the scan, each mip's merged from them.
    BlockLuminance finest;
    finest.scale = std::min_element(refinedScales.begin(), refinedScales.end(), [](auto a, auto b) { return a.second < b.second; })->second;
    auto withBlocks = [&](BrightCandidates candidates) {
        for (const auto& [level, scale] : refinedScales)
            candidates.refinedMipBlocks.push_back(coarsenedBlocks(finest, scale, level));
        return candidates;
    };
    // Where the cap raised the floor into a field of one-texel lights, no threshold can take
    // them and every mip samples them (mip 1 0.059-0.081 on 3000- and 4096-wide star fields):
    // more are kept. Spiky over mip 1's blocks or over blocks twice as wide, as its refined
    // set is judged: squares nearly a footprint wide fill mip 1's blocks, and 700 squares 10
    // texels wide on a 4096-wide map kept the cap and were left to the samples (mips 1-3 0.044
    // 0.024 0.032; kept, 0.036 0.002 0.001). A map of large bright areas (16384 texels of sky
    // above the floor) is not spiky there and keeps the cap (courtyard.exr 1.07, the bundled
    // maps at most 1.23 over the wider blocks, against 1.68).
    const int firstRefined = refinedScales.front().first;
    return withBlocks(brightCandidates(equirect, settings.brightThreshold, kMaxBrightCandidates, &finest, [&](const BrightCandidates& kept) {
        const BrightCandidates withMipBlocks = withBlocks(kept);
        return spikyBase(withMipBlocks, kept.floorThreshold, firstRefined) || spikyBase(withMipBlocks, kept.floorThreshold, firstRefined, 0.25, 1);
    }));
}

} // namespace iblab::bake
