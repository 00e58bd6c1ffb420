#include "bake/bright_texels.hpp"

#include <algorithm>
#include <cmath>

#include <glm/vec4.hpp>

#include "bake/source_samples.hpp"
#include "ibl/prefilter_lod.hpp"

// The levels of the environment that the split reads: where its bases start, and which base
// mip a level sums exactly (bright_texels.hpp).
namespace iblab::bake {

namespace {

// The level an exact sum of `roughness` reads, whatever its size: the smallest whose texels
// are at most alpha / 2 across (the finest where none is); -1 where alpha is 0.
int exactSumLevel(int baseSize, int baseLevels, double roughness)
{
    // A face-centre texel of a size-S face spans 2 / S radians: alpha / 2 needs S >= 4 / alpha.
    // Over such a texel the weight's curvature at the lobe's peak moves the midpoint rule by
    // about (texel / alpha)^2 / 12 in l (whose lobe is twice h's), about 2% for an isolated
    // point and far less for an area. At least an 8 face: at roughness 1 the lobe is the
    // cosine over a hemisphere, whose edge (the clamp of n.l at 0) a 4 face (texels of 30
    // degrees) resolves badly (0.133 against 0.009 on builtin:lights?count=6&size=15).
    constexpr int kExactSumMinFace = 8;
    const double alpha = roughness * roughness;
    if (!(alpha > 0.0))
        return -1;
    int level = 0;
    const double smallest = std::max(4.0 / alpha, double(kExactSumMinFace));
    while (level + 1 < baseLevels && double(std::max(baseSize >> (level + 1), 1)) >= smallest)
        ++level;
    return level;
}

double levelTexels(int baseSize, int level)
{
    const double size = std::max(baseSize >> level, 1);
    return 6.0 * size * size;
}

} // namespace

int exactSumSourceLevel(const PrefilterSettings& settings, int baseSize, int baseLevels, double roughness)
{
    const int level = settings.exactSumTexels > 0 ? exactSumLevel(baseSize, baseLevels, roughness) : -1;
    return level >= 0 && levelTexels(baseSize, level) <= double(settings.exactSumTexels) ? level : -1;
}

int tiledExactSumSourceLevel(const PrefilterSettings& settings, int baseSize, int baseLevels, double roughness)
{
    if (settings.exactSumTiledTexels <= 0 || exactSumSourceLevel(settings, baseSize, baseLevels, roughness) >= 0)
        return -1;
    const int level = exactSumLevel(baseSize, baseLevels, roughness);
    return level >= 0 && levelTexels(baseSize, level) <= double(settings.exactSumTiledTexels) ? level : -1;
}

int splitBaseTopLevel(const PrefilterSettings& settings, int environmentSize, int environmentLevels, int firstMip, int lastMip)
{
    if (!settings.mipFiltering)
        return 0; // every sample reads level 0
    // The largest texel of a level-0 face is at its centre, about (2 / size)^2 sr: the
    // smallest lod any sample's pdf picks (readSource), whichever texel solid angle it uses.
    const float largestTexel = 4.0f / (float(environmentSize) * float(environmentSize));
    float finest = float(environmentLevels - 1);
    for (int level = std::max(firstMip, 1); level < settings.levels && (lastMip < 0 || level <= lastMip); ++level) {
        const float roughness = prefilterMipRoughness(settings, level);
        if (!(roughness > 0.0f))
            continue;
        if (const int exact = exactSumSourceLevel(settings, environmentSize, environmentLevels, roughness); exact >= 0) {
            finest = std::min(finest, float(exact));
            continue;
        }
        if (const int tiled = tiledExactSumSourceLevel(settings, environmentSize, environmentLevels, roughness); tiled >= 0) {
            finest = std::min(finest, float(tiled));
            continue;
        }
        for (const glm::vec4& sample : ggxReflectedSampleTable(roughness, prefilterSamples(settings, level), settings.mipBias, settings.sampleRotation))
            finest = std::min(finest, sourceLodFromSampleTerm(sample.w, largestTexel));
        // A refined set (PrefilterSettings::refineFactor) reads finer than its first, but no
        // base level finer than half of its mip's texels is built for it: on a 512 cube mip
        // 1's peak reads lod 0.45, and a base from level 0 would clamp four times the texels
        // of one from level 1 for texels a quarter of mip 1's.
        if (level <= kLastRefinedMip && settings.refineFactor > 1) {
            const float halfTexel = std::max(0.0f, std::log2(float(environmentSize) / float(std::max(settings.faceSize >> (level - 1), 1))));
            for (const glm::vec4& sample : ggxReflectedSampleTable(roughness, prefilterSamples(settings, level) * settings.refineFactor,
                                                                   settings.mipBias, settings.sampleRotation))
                finest = std::min(finest, std::max(halfTexel, sourceLodFromSampleTerm(sample.w, largestTexel)));
        }
    }
    // The nearest level: a read between it and the next finer one (at most half a level)
    // reads it instead, a blur of at most half a level on the few samples at a lobe's peak
    // (the default's mip 1 reads lod 0.95 of a 256 cube there). Building the finer level
    // took about a third of the split's own time on the bundled maps.
    return std::clamp(int(std::floor(finest + 0.5f)), 0, std::max(0, environmentLevels - 1));
}

} // namespace iblab::bake
