#include "bake/block_luminance.hpp"

#include <algorithm>
#include <cmath>

#include "bake/source_samples.hpp"
#include "ibl/conventions.hpp"
#include "ibl/prefilter_lod.hpp"

namespace iblab::bake {

void BlockLuminance::removeExcess(std::uint32_t sourceIndex, double excessTimesSolidAngle)
{
    if (sourceWidth <= 0)
        return;
    const auto width = std::uint32_t(sourceWidth);
    const std::size_t block = std::size_t((sourceIndex / width) >> scale) * std::size_t(blocksPerRow) + ((sourceIndex % width) >> scale);
    if (block < luminanceTimesSolidAngle.size())
        luminanceTimesSolidAngle[block] -= excessTimesSolidAngle;
}

double BlockLuminance::rms() const
{
    double squared = 0.0, total = 0.0;
    for (std::size_t b = 0; b < solidAngle.size(); ++b) {
        if (!(solidAngle[b] > 0.0))
            continue;
        const double mean = std::max(0.0, luminanceTimesSolidAngle[b]) / solidAngle[b];
        squared += mean * mean * solidAngle[b];
        total += solidAngle[b];
    }
    return total > 0.0 ? std::sqrt(squared / total) : 0.0;
}

BlockLuminance blockLuminanceFromRows(std::span<const double> rowBlockSums, std::span<const double> rowSolidAngle, int width, int scale)
{
    BlockLuminance out;
    out.scale = scale;
    out.sourceWidth = width;
    const int side = 1 << scale;
    out.blocksPerRow = (width + side - 1) / side;
    const auto rows = int(rowSolidAngle.size());
    out.blockRows = (rows + side - 1) / side;
    out.luminanceTimesSolidAngle.assign(std::size_t(out.blocksPerRow) * std::size_t(out.blockRows), 0.0);
    out.solidAngle.assign(out.luminanceTimesSolidAngle.size(), 0.0);
    for (int y = 0; y < rows; ++y) {
        const double omega = rowSolidAngle[std::size_t(y)];
        for (int b = 0; b < out.blocksPerRow; ++b) {
            const std::size_t block = std::size_t(y >> scale) * std::size_t(out.blocksPerRow) + std::size_t(b);
            out.luminanceTimesSolidAngle[block] += rowBlockSums[std::size_t(y) * std::size_t(out.blocksPerRow) + std::size_t(b)] * omega;
            out.solidAngle[block] += double(std::min(side, width - b * side)) * omega;
        }
    }
    return out;
}

BlockLuminance coarsenedBlocks(const BlockLuminance& fine, int scale, int mip)
{
    BlockLuminance out;
    out.mip = mip;
    out.scale = scale;
    out.sourceWidth = fine.sourceWidth;
    const int merge = scale - fine.scale;
    out.blocksPerRow = (fine.blocksPerRow + (1 << merge) - 1) >> merge;
    out.blockRows = (fine.blockRows + (1 << merge) - 1) >> merge;
    out.luminanceTimesSolidAngle.assign(std::size_t(out.blocksPerRow) * std::size_t(out.blockRows), 0.0);
    out.solidAngle.assign(out.luminanceTimesSolidAngle.size(), 0.0);
    for (int y = 0; y < fine.blockRows; ++y)
        for (int x = 0; x < fine.blocksPerRow; ++x) {
            const std::size_t from = std::size_t(y) * std::size_t(fine.blocksPerRow) + std::size_t(x);
            const std::size_t to = std::size_t(y >> merge) * std::size_t(out.blocksPerRow) + std::size_t(x >> merge);
            out.luminanceTimesSolidAngle[to] += fine.luminanceTimesSolidAngle[from];
            out.solidAngle[to] += fine.solidAngle[from];
        }
    return out;
}

int refinedSampleScale(const PrefilterSettings& settings, int level, int width, int height)
{
    if (width <= 0 || height <= 0)
        return 0;
    const float equatorTexel = float(2.0 * kPi / double(width) * (kPi / double(height)));
    std::vector<float> lods;
    for (const glm::vec4& sample : ggxReflectedSampleTable(prefilterMipRoughness(settings, level), prefilterSamples(settings, level),
                                                           settings.mipBias, settings.sampleRotation))
        lods.push_back(sourceLodFromSampleTerm(sample.w, equatorTexel));
    if (lods.empty())
        return 0;
    std::nth_element(lods.begin(), lods.begin() + std::ptrdiff_t(lods.size() / 2), lods.end());
    const int largest = int(std::floor(std::log2(double(height))));
    return std::clamp(int(std::lround(lods[lods.size() / 2])), 0, largest);
}

} // namespace iblab::bake
