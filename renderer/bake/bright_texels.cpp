#include "bake/bright_texels.hpp"
#include "bake/bright_texels_block.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "bake/bake_passes.hpp"
#include "ibl/conventions.hpp"
#include "ibl/equirect.hpp"
#include "io/error.hpp"

namespace iblab::bake {
namespace {

float luminance(glm::vec3 c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

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

double ggxPrefilterNormalization(double roughness)
{
    // With v = n, dOmega_l = 4 (n.h) dOmega_h, so Z = 4 E[max(0, n.l)] for h drawn with
    // density D(h) (n.h), whose inverse CDF is cos^2(theta_h) = (1 - u) / (1 + (alpha^2 - 1) u);
    // n.l = 2 cos^2(theta_h) - 1. The integrand is smooth in u: the midpoint rule with 2^16
    // points is exact to well under 1e-6.
    const double a2 = roughness * roughness * roughness * roughness;
    constexpr int kSteps = 1 << 16;
    double sum = 0.0;
    for (int i = 0; i < kSteps; ++i) {
        const double u = (i + 0.5) / kSteps;
        const double cos2 = (1.0 - u) / (1.0 + (a2 - 1.0) * u);
        sum += std::max(0.0, 2.0 * cos2 - 1.0);
    }
    return 4.0 * sum / kSteps;
}

namespace {

// Keeps the brightest maxCandidates (ties in texel order), brightest first, and raises the
// floor to the first one left out.
BrightCandidates finishCandidates(std::vector<BrightTexel> texels, float floorThreshold, float meanLuminance, int maxCandidates)
{
    BrightCandidates c;
    c.meanLuminance = meanLuminance;
    c.floorThreshold = floorThreshold;
    std::stable_sort(texels.begin(), texels.end(), [](const BrightTexel& a, const BrightTexel& b) { return a.luminance > b.luminance; });
    if (texels.size() > std::size_t(std::max(0, maxCandidates))) {
        c.floorThreshold = texels[std::size_t(std::max(0, maxCandidates))].luminance;
        // Only texels strictly above the floor are lights: drop the ties with it too.
        while (!texels.empty() && !(texels.back().luminance > c.floorThreshold))
            texels.pop_back();
    }
    c.texels = std::move(texels);
    return c;
}

std::uint64_t cellOf(const glm::dvec3& direction, int faceSize)
{
    const glm::vec3 fuv = directionToCubeFaceUv(glm::vec3(direction));
    const int x = std::clamp(int(fuv.y * float(faceSize)), 0, faceSize - 1);
    const int row = std::clamp(int(fuv.z * float(faceSize)), 0, faceSize - 1);
    return (std::uint64_t(fuv.x) * std::uint64_t(faceSize) + std::uint64_t(row)) * std::uint64_t(faceSize) + std::uint64_t(x);
}

// Candidates strictly above threshold: a prefix, since they are sorted brightest first.
std::size_t countAbove(const BrightCandidates& c, float threshold)
{
    return std::size_t(std::partition_point(c.texels.begin(), c.texels.end(),
                                            [&](const BrightTexel& t) { return t.luminance > threshold; }) -
                       c.texels.begin());
}

std::size_t mergedCount(const BrightCandidates& c, std::size_t count, int cellFaceSize)
{
    std::vector<std::uint64_t> cells(count);
    for (std::size_t i = 0; i < count; ++i)
        cells[i] = cellOf(c.texels[i].direction, cellFaceSize);
    std::sort(cells.begin(), cells.end());
    return std::size_t(std::unique(cells.begin(), cells.end()) - cells.begin());
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

// Block entries of a level: 2 per far cell, 2 per light.
std::size_t hierarchyEntries(const BrightCandidates& c, std::size_t count, int cellFaceSize)
{
    const std::size_t lights = mergedCount(c, count, cellFaceSize);
    const std::size_t far = farFaceSize(cellFaceSize) == cellFaceSize ? 0 : mergedCount(c, count, farFaceSize(cellFaceSize));
    return 2 * (lights + far);
}

} // namespace

BrightCandidates brightCandidates(const ImageRGB32F& equirect, float thresholdOverMean, int maxCandidates)
{
    const int w = equirect.width, h = equirect.height;
    std::vector<double> rowSolidAngle(std::size_t(std::max(0, h)));
    double flux = 0.0;
    for (int y = 0; y < h; ++y) {
        rowSolidAngle[std::size_t(y)] = equirectTexelSolidAngle(y, w, h);
        double row = 0.0;
        for (int x = 0; x < w; ++x)
            row += double(std::max(0.0f, luminance(equirect.at(x, y))));
        flux += row * rowSolidAngle[std::size_t(y)];
    }
    const float mean = float(flux / (4.0 * kPi));
    const float floorThreshold = thresholdOverMean * mean;
    std::vector<BrightTexel> texels;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const glm::vec3 rgb = equirect.at(x, y);
            if (const float lum = luminance(rgb); lum > floorThreshold)
                texels.push_back({equirectTexelDirection(x, y, w, h), glm::dvec3(rgb), rowSolidAngle[std::size_t(y)], lum});
        }
    return finishCandidates(std::move(texels), floorThreshold, mean, maxCandidates);
}

BrightCandidates brightCandidates(const CubeImage& level0, float thresholdOverMean, int maxCandidates)
{
    const int f = level0.size;
    double flux = 0.0;
    for (int face = 0; face < 6; ++face)
        for (int row = 0; row < f; ++row)
            for (int x = 0; x < f; ++x)
                flux += double(std::max(0.0f, luminance(level0.rgb(face, x, row)))) * approximateTexelSolidAngle(x, row, f);
    const float mean = float(flux / (4.0 * kPi));
    const float floorThreshold = thresholdOverMean * mean;
    std::vector<BrightTexel> texels;
    for (int face = 0; face < 6; ++face)
        for (int row = 0; row < f; ++row)
            for (int x = 0; x < f; ++x) {
                const glm::vec3 rgb = level0.rgb(face, x, row);
                if (const float lum = luminance(rgb); lum > floorThreshold && std::isfinite(lum))
                    texels.push_back({glm::dvec3(level0.texelDirection(face, x, row)), glm::dvec3(rgb), texelSolidAngle(x, row, f), lum});
            }
    return finishCandidates(std::move(texels), floorThreshold, mean, maxCandidates);
}

int brightCellFaceSize(double roughness)
{
    // A cell of a size-S face spans about 2 / S radians; alpha / 8 of it needs S >= 16 / alpha.
    const double alpha = std::max(roughness * roughness, 1e-6);
    int size = 1;
    while (size < 1024 && size < 16.0 / alpha)
        size *= 2;
    return size;
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
        Cell& cell = cells[cellOf(t.direction, cellFaceSize)];
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
        Cell& cell = cells[cellOf(direction, farFace)];
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
    auto fits = [&](std::size_t p) {
        const std::size_t count = countAbove(candidates, thresholdAt(p));
        for (std::size_t i = 0; i < roughness.size(); ++i) {
            // The cap is on the far cells (every output texel sums each of them), the block
            // on everything the level uploads.
            const int cell = brightCellFaceSize(roughness[i]);
            const auto cap = std::size_t(std::max(0, caps[i]));
            if (mergedCount(candidates, count, farFaceSize(cell)) > cap || mergedCount(candidates, count, cell) > kLightsPerFarCell * cap ||
                hierarchyEntries(candidates, count, cell) > std::size_t(2 * kMaxBrightLights))
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

void clampLuminance(CubeImage& level, float threshold)
{
    for (glm::vec4& texel : level.texels) {
        const glm::vec3 rgb(texel);
        const float y = luminance(rgb);
        if (!std::isfinite(y))
            texel = glm::vec4(glm::vec3(threshold), texel.a);
        else if (y > threshold)
            texel = glm::vec4(rgb * (threshold / y), texel.a);
    }
}

int exactSumSourceLevel(const PrefilterSettings& settings, int baseSize, int baseLevels, double roughness)
{
    // A face-centre texel of a size-S face spans 2 / S radians: alpha / 2 needs S >= 4 / alpha.
    // Over such a texel the weight's curvature at the lobe's peak moves the midpoint rule by
    // about (texel / alpha)^2 / 12 in l (whose lobe is twice h's), about 2% for an isolated
    // point and far less for an area. At least an 8 face: at roughness 1 the lobe is the
    // cosine over a hemisphere, whose edge (the clamp of n.l at 0) a 4 face (texels of 30
    // degrees) resolves badly (0.133 against 0.009 on builtin:lights?count=6&size=15).
    constexpr int kExactSumMinFace = 8;
    const double alpha = roughness * roughness;
    if (settings.exactSumTexels <= 0 || !(alpha > 0.0))
        return -1;
    int level = 0;
    const double smallest = std::max(4.0 / alpha, double(kExactSumMinFace));
    while (level + 1 < baseLevels && double(std::max(baseSize >> (level + 1), 1)) >= smallest)
        ++level;
    const double size = std::max(baseSize >> level, 1);
    return 6.0 * size * size <= double(settings.exactSumTexels) ? level : -1;
}

int brightBlockCapacity(const PrefilterSettings& settings) { return settings.brightTexels > 0 ? 2 * kMaxBrightLights : 0; }

int brightTexelCap(const PrefilterSettings& settings, int level)
{
    // Mip 2 has a quarter of mip 1's texels: four times the lights cost it as much.
    return level <= 1 ? settings.brightTexels : std::min(4 * settings.brightTexels, kMaxBrightLights);
}

PrefilterBrightTexels splitBrightTexels(BakePasses& passes, const BakedTexture& environment, const ImageRGB32F& equirect,
                                        const PrefilterSettings& settings)
{
    PrefilterBrightTexels out;
    const int capacity = brightBlockCapacity(settings);
    GLint maxBlockBytes = 0;
    glGetIntegerv(GL_MAX_UNIFORM_BLOCK_SIZE, &maxBlockBytes);
    if (GLint(capacity * sizeof(glm::vec4)) > maxBlockBytes)
        throw Error("prefilter", "the bright-texel split needs a " + std::to_string(capacity * sizeof(glm::vec4)) +
                                     "-byte uniform block; this GL driver allows " + std::to_string(maxBlockBytes) +
                                     " (--prefilter-bright-texels 0 turns the split off)");
    CubeImage level0 = readCubeLevel(environment, 0);
    constexpr int kMaxCandidates = 1 << 14;
    const BrightCandidates candidates = equirect.empty() ? brightCandidates(level0, settings.brightThreshold, kMaxCandidates)
                                                         : brightCandidates(equirect, settings.brightThreshold, kMaxCandidates);
    out.meanLuminance = candidates.meanLuminance;

    // Two groups, mip 1 and the rougher mips, each with the threshold its caps allow.
    std::vector<double> roughRoughness;
    std::vector<int> roughCaps;
    for (int level = 2; level < settings.levels; ++level)
        if (const float r = prefilterMipRoughness(settings, level); r > 0.0f) {
            roughRoughness.push_back(r);
            roughCaps.push_back(brightTexelCap(settings, level));
        }
    const float mip1Roughness = settings.levels > 1 ? prefilterMipRoughness(settings, 1) : 0.0f;
    const float mip1Threshold = brightThresholdFor(candidates, {double(mip1Roughness)}, {brightTexelCap(settings, 1)});
    const float roughThreshold = brightThresholdFor(candidates, roughRoughness, roughCaps);

    std::vector<float> baseThresholds;
    auto baseFor = [&](float threshold) {
        for (std::size_t i = 0; i < baseThresholds.size(); ++i)
            if (baseThresholds[i] == threshold)
                return int(i);
        CubeImage base = level0;
        clampLuminance(base, threshold);
        out.bases.push_back(createCubeTexture(environment.internalFormat, environment.size, environment.levels));
        uploadCubeLevel(out.bases.back(), 0, base);
        passes.generateMips(out.bases.back());
        baseThresholds.push_back(threshold);
        return int(baseThresholds.size() - 1);
    };
    out.levels.resize(std::size_t(std::max(0, settings.levels)));
    for (int level = 1; level < settings.levels; ++level) {
        const float roughness = prefilterMipRoughness(settings, level);
        if (!(roughness > 0.0f))
            continue;
        PrefilterBrightTexels::Level& l = out.levels[std::size_t(level)];
        l.threshold = level == 1 ? mip1Threshold : roughThreshold;
        l.base = baseFor(l.threshold);
        const std::vector<glm::vec4> lights = hierarchicalLights(candidates, l.threshold, brightCellFaceSize(roughness), l.count);
        l.capacity = capacity;
        // GL leaves reads undefined where the bound range is shorter than the block: padded.
        std::vector<glm::vec4> padded(std::size_t(capacity), glm::vec4(0.0f));
        std::copy(lights.begin(), lights.begin() + std::min(lights.size(), padded.size()), padded.begin());
        l.texels = gl::createBufferWith<glm::vec4>(padded);
    }
    return out;
}


} // namespace iblab::bake
