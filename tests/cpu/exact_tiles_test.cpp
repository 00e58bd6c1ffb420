// The prefilter's per-tile cuts (renderer/bake/exact_tiles.hpp) against the exact sum they
// stand for, over every texel of the same source mip: for each output texel, the GGX-weighted
// mean over its tile's list and over the whole mip, weighted as prefilter_ggx.comp weighs
// (ibl/brdf.hpp's ggxPrefilterWeight), at the default's tiled mip (roughness 0.37 on a 32 face);
// and which mips the default hands to the cuts and which to the whole-table sum.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <glm/glm.hpp>

#include "bake/bake_settings.hpp"
#include "bake/bright_texels.hpp"
#include "bake/exact_tiles.hpp"
#include "ibl/brdf.hpp"
#include "ibl/conventions.hpp"
#include "ibl/prefilter_lod.hpp"

namespace iblab::bake {
namespace {

constexpr int kFace = 32;
constexpr double kRoughness = 0.37;
constexpr int kMaxEntries = 2048; // a 64 KB uniform block's pairs
constexpr int kAlignment = 16;    // vec4, as a driver with 256-byte offsets asks

struct Entry {
    glm::dvec3 direction;
    glm::dvec3 flux;
    double solidAngle;
};

glm::dvec3 weightedMean(const std::vector<Entry>& entries, const glm::dvec3& n)
{
    const double alpha2 = std::pow(kRoughness, 4.0);
    glm::dvec3 sum(0.0);
    double weights = 0.0;
    for (const Entry& e : entries) {
        const double c = glm::dot(n, e.direction);
        const double w = ggxPrefilterWeight(c, 1.0 - c, alpha2);
        sum += w * e.flux;
        weights += w * e.solidAngle;
    }
    return sum / weights;
}

std::vector<Entry> everyTexel(const CubeImage& source)
{
    std::vector<Entry> entries;
    for (int face = 0; face < 6; ++face)
        for (int row = 0; row < source.size; ++row)
            for (int x = 0; x < source.size; ++x) {
                const glm::vec3 d = source.texelDirection(face, x, row);
                const double omega = double(cubeTexelSolidAngle(d, float(source.size)));
                entries.push_back({glm::dvec3(d), glm::dvec3(source.rgb(face, x, row)) * omega, omega});
            }
    return entries;
}

std::vector<Entry> tileList(const ExactTiles& tiles, std::size_t tile)
{
    std::vector<Entry> entries;
    for (int i = 0; i < tiles.count[tile]; ++i) {
        const glm::vec4& d = tiles.buffer[std::size_t(tiles.first[tile] + 2 * i)];
        const glm::vec4& f = tiles.buffer[std::size_t(tiles.first[tile] + 2 * i + 1)];
        entries.push_back({glm::dvec3(d), glm::dvec3(f), double(f.w)});
    }
    return entries;
}

// The largest relative difference between the tiles' means and the full sum's, over every
// output texel, relative to the full sum's RMS luminance over the face (how the bake's per-mip
// error is normalised); and the RMS of the differences likewise.
struct Agreement {
    double largest = 0.0;
    double rms = 0.0;
};

Agreement agreement(const CubeImage& source)
{
    const ExactTiles tiles = exactSumTiles(source, kFace, kMaxEntries, kAlignment, 2 * kMaxEntries);
    const std::vector<Entry> all = everyTexel(source);
    std::vector<double> differences;
    double squares = 0.0;
    for (int face = 0; face < 6; ++face)
        for (int row = 0; row < kFace; ++row)
            for (int x = 0; x < kFace; ++x) {
                const std::size_t tile = (std::size_t(face) * std::size_t(tiles.tilesPerEdge) + std::size_t(row / kExactTileTexels)) *
                                             std::size_t(tiles.tilesPerEdge) +
                                         std::size_t(x / kExactTileTexels);
                const glm::dvec3 n(cubeFaceUvToDirection(face, glm::vec2((x + 0.5f) / kFace, (row + 0.5f) / kFace)));
                const glm::dvec3 exact = weightedMean(all, n);
                const glm::dvec3 cut = weightedMean(tileList(tiles, tile), n);
                differences.push_back(glm::length(cut - exact));
                squares += glm::dot(exact, exact);
            }
    const double rms = std::sqrt(squares / double(differences.size()));
    Agreement a;
    double differenceSquares = 0.0;
    for (double d : differences) {
        a.largest = std::max(a.largest, d / rms);
        differenceSquares += d * d;
    }
    a.rms = std::sqrt(differenceSquares / double(differences.size())) / rms;
    return a;
}

TEST(ExactTiles, ListsFitTheirBlockAndStartAligned)
{
    CubeImage source(kFace);
    for (glm::vec4& t : source.texels)
        t = glm::vec4(1.0f);
    const ExactTiles tiles = exactSumTiles(source, kFace, kMaxEntries, kAlignment, 2 * kMaxEntries);
    ASSERT_EQ(tiles.tilesPerEdge, kFace / kExactTileTexels);
    ASSERT_EQ(tiles.first.size(), std::size_t(6 * tiles.tilesPerEdge * tiles.tilesPerEdge));
    for (std::size_t t = 0; t < tiles.first.size(); ++t) {
        EXPECT_EQ(tiles.first[t] % kAlignment, 0);
        EXPECT_LE(tiles.count[t], kMaxEntries);
        EXPECT_GT(tiles.count[t], 0);
        EXPECT_LE(std::size_t(tiles.first[t] + 2 * kMaxEntries), tiles.buffer.size()); // a block bound at its start stays inside
    }
    // Coarser than a whole-mip table: far groups merged.
    EXPECT_LT(tiles.largest, 6 * kFace * kFace);
}

TEST(ExactTiles, ATileTooLongForItsBlockIsCutCoarser)
{
    CubeImage source(kFace);
    for (glm::vec4& t : source.texels)
        t = glm::vec4(1.0f);
    const ExactTiles tiles = exactSumTiles(source, kFace, 1200, kAlignment, 2400);
    ASSERT_GT(tiles.tilesPerEdge, 0);
    EXPECT_LE(tiles.largest, 1200);
    // Fewer entries than the texels that overlap a tile: no tiles, and the mip is sampled.
    EXPECT_EQ(exactSumTiles(source, kFace, 100, kAlignment, 200).tilesPerEdge, 0);
}

TEST(ExactTiles, AConstantMapStaysExact)
{
    CubeImage source(kFace);
    for (glm::vec4& t : source.texels)
        t = glm::vec4(2.5f, 1.0f, 0.25f, 1.0f);
    const Agreement a = agreement(source);
    EXPECT_LT(a.largest, 1e-5);
}

// Every texel its own random value: the cut's merged groups average detail that the full sum
// weighs texel by texel.
TEST(ExactTiles, TexelNoiseAgreesWithTheFullSum)
{
    CubeImage source(kFace);
    std::mt19937 random(7);
    std::uniform_real_distribution<float> value(0.0f, 1.0f);
    for (glm::vec4& t : source.texels)
        t = glm::vec4(value(random), value(random), value(random), 1.0f);
    const Agreement a = agreement(source);
    // 0.00009 and 0.00044 at the default spread; at a spread of 1, 0.00037 and 0.0028.
    EXPECT_LT(a.rms, 0.0002);
    EXPECT_LT(a.largest, 0.001);
}

// A bright texel (a base's brightest, at its clamp: four times the mean) on a dim ground, in
// every tile's far field somewhere: merged at its flux centre, it lands where it is.
TEST(ExactTiles, ABrightTexelAgreesWithTheFullSum)
{
    CubeImage source(kFace);
    for (glm::vec4& t : source.texels)
        t = glm::vec4(0.1f, 0.1f, 0.1f, 1.0f);
    source.at(2, 5, 9) = glm::vec4(400.0f, 300.0f, 200.0f, 1.0f);
    source.at(4, 20, 17) = glm::vec4(50.0f, 80.0f, 120.0f, 1.0f);
    const Agreement a = agreement(source);
    // 0.00021 and 0.0019 at the default spread; at a spread of 1, 0.0011 and 0.0095.
    EXPECT_LT(a.rms, 0.0006);
    EXPECT_LT(a.largest, 0.005);
}

// Which estimator each mip of the default gets, on a 1024 x 512 map's 256 cube (9 levels):
// mip 3 the tiles over its 32 face, mips 4 and 5 the whole-table sum over their 16 / 8 faces.
// Turning the tiles off samples mip 3; the whole-table sum off alone hands mips 3-5 to the
// tiles (their sources fit 6144 texels), so a fully sampled base needs both off.
TEST(ExactTiles, TheDefaultSumsMipThreePerTileAndMipsFourAndFiveWhole)
{
    constexpr int kCube = 256;
    constexpr int kLevels = 9;
    auto plan = [](const PrefilterSettings& p) {
        std::vector<int> whole, tiled;
        for (int mip = 1; mip < p.levels; ++mip) {
            const double roughness = prefilterMipRoughness(p, mip);
            whole.push_back(exactSumSourceLevel(p, kCube, kLevels, roughness));
            tiled.push_back(tiledExactSumSourceLevel(p, kCube, kLevels, roughness));
        }
        return std::pair{whole, tiled};
    };
    PrefilterSettings p = defaultPreset().prefilter;
    ASSERT_EQ(p.levels, 6);
    EXPECT_EQ(plan(p), std::pair(std::vector<int>{-1, -1, -1, 4, 5}, std::vector<int>{-1, -1, 3, -1, -1}));
    p.exactSumTiledTexels = 0;
    EXPECT_EQ(plan(p), std::pair(std::vector<int>{-1, -1, -1, 4, 5}, std::vector<int>(5, -1)));
    p = defaultPreset().prefilter;
    p.exactSumTexels = 0;
    EXPECT_EQ(plan(p), std::pair(std::vector<int>(5, -1), std::vector<int>{-1, -1, 3, 4, 5}));
    p.exactSumTiledTexels = 0;
    EXPECT_EQ(plan(p), std::pair(std::vector<int>(5, -1), std::vector<int>(5, -1)));
}

} // namespace
} // namespace iblab::bake
