// The default prefilter (the bright-texel split, docs/bake.md, "The prefilter's estimator")
// on a small, very bright sun: every mip with roughness > 0 within 5% relative RMSE of the
// exact prefilter at its texel centres, wherever the sun is and however the sample set is
// turned, and a white furnace within 0.1%. The same sun bakes with every texel sampled
// (prefilter.brightTexels = 0, the estimator before the split) break the bound, which the
// sun tests check too, so that they cannot pass by being lax.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bake/bake_accuracy.hpp"
#include "bake/bake_passes.hpp"
#include "bake/bright_texels.hpp"
#include "bake/tile_lights.hpp"
#include "bake_test_support.hpp"
#include "gl_test_fixture.hpp"
#include "ibl/conventions.hpp"
#include "ibl/equirect.hpp"
#include "ibl/image.hpp"
#include "ibl/luminance.hpp"

namespace iblab {
namespace {

using testing::GlTest;
using testing::expectWithinPerMipBound;
using testing::kPerMipBound;
using testing::perMipErrors;
using testing::runBake;


// The real sun's size (0.5 degrees) at 1e4 over a sky of 0.05 (builtin:sun's): its flux is
// as large as the whole sky's, on about one texel of the 256 environment cube that a
// 1024 x 512 map gets.
std::string sunSpec(double elevation, double azimuth)
{
    return "builtin:sun?width=1024&size=0.5&intensity=1e4&elevation=" + std::to_string(elevation) + "&azimuth=" + std::to_string(azimuth);
}


std::vector<double> perMipErrors(gl::ShaderLibrary& shaders, const std::string& spec, const bake::BakeSettings& settings)
{
    return perMipErrors(shaders, loadEnvironment(spec), settings);
}

double largest(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }

// Each of the five mips from firstMip (1: every mip with roughness > 0) within the bound.
bake::BakeSettings everyTexelSampled()
{
    bake::BakeSettings s = bake::defaultPreset();
    s.prefilter.brightTexels = 0;
    return s;
}

// The default preset, whose prefilter splits the bright texels off.
bake::BakeSettings brightTexelsSplit()
{
    bake::BakeSettings s = bake::defaultPreset();
    EXPECT_GT(s.prefilter.brightTexels, 0);
    return s;
}

// Relative RMS difference of two bakes' prefiltered mip (every texel).
double relativeDifference(const bake::BakeResult& a, const bake::BakeResult& b, int level)
{
    const bake::CubeImage x = bake::readCubeLevel(a.prefiltered, level), y = bake::readCubeLevel(b.prefiltered, level);
    double diff = 0.0, norm = 0.0;
    for (std::size_t i = 0; i < x.texels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            diff += double(x.texels[i][c] - y.texels[i][c]) * double(x.texels[i][c] - y.texels[i][c]);
            norm += double(y.texels[i][c]) * double(y.texels[i][c]);
        }
    return std::sqrt(diff / norm);
}

// `count` one-texel lamps at random places of rows [firstRow, firstRow + rows), each of
// minRadiance + [0, radianceRange) in red and greenBlue times that in green and blue, from a
// seeded linear congruential generator: the same map every run.
void scatterLamps(ImageRGB32F& map, int count, int firstRow, int rows, float minRadiance, std::uint32_t radianceRange, float greenBlue,
                  std::uint32_t seed)
{
    std::uint32_t state = seed;
    auto next = [&state] { return (state = state * 1664525u + 1013904223u) >> 8; };
    for (int lamp = 0; lamp < count; ++lamp) {
        const int x = int(next() % std::uint32_t(map.width)), y = firstRow + int(next() % std::uint32_t(rows));
        const float radiance = minRadiance + float(next() % radianceRange);
        for (int c = 0; c < 3; ++c)
            map.texels[map.offset(x, y) + std::size_t(c)] = radiance * (c == 0 ? 1.0f : greenBlue);
    }
}

// The band flux (luminance above threshold, up to upper, times solid angle) of the candidates
// within reach radians of direction, or of all of them with reach pi.
double bandFlux(const bake::BrightCandidates& candidates, float threshold, float upper, const glm::dvec3& direction, double reach)
{
    double flux = 0.0;
    for (const bake::BrightTexel& t : candidates.texels)
        if (t.luminance > threshold && std::acos(std::clamp(glm::dot(direction, t.direction), -1.0, 1.0)) <= reach)
            flux += (std::min(double(t.luminance), double(upper)) - double(threshold)) * t.solidAngle;
    return flux;
}

// Every tile's list holds at least the band flux within reach of its centre (a node summed
// whole holds all of its lights' flux) and at most the whole band's.
void expectTilesHoldTheFluxNearThem(const bake::TileLights& lights, const bake::BrightCandidates& candidates, float upper, double reach)
{
    const double total = bandFlux(candidates, lights.threshold, upper, glm::dvec3(0.0, 1.0, 0.0), kPi);
    const int tiles = lights.tilesPerEdge;
    for (int face = 0; face < 6; ++face)
        for (int row = 0; row < tiles; ++row)
            for (int column = 0; column < tiles; ++column) {
                const glm::vec4 entry = lights.buffer[std::size_t((face * tiles + row) * tiles + column)];
                const glm::dvec3 centre = glm::normalize(
                    glm::dvec3(cubeFaceUvToDirection(face, glm::vec2((column + 0.5f) / float(tiles), (row + 0.5f) / float(tiles)))));
                double listed = 0.0;
                for (int k = 0; k < int(entry.y); ++k)
                    listed += double(luminance(glm::vec3(lights.buffer[std::size_t(entry.x) + 2 * std::size_t(k) + 1])));
                EXPECT_GE(listed, bandFlux(candidates, lights.threshold, upper, centre, reach) * (1.0 - 1e-4)) << "tile " << face << " " << row << " " << column;
                EXPECT_LE(listed, total * (1.0 + 1e-4));
            }
}

TEST_F(GlTest, BrightSunMeetsThePerMipBoundAtEveryMip)
{
    auto shaders = testing::bakeShaderLibrary();
    // builtin:sun's own place (on the edge between the +Y and -Z faces) and one off every
    // axis and edge.
    for (const auto& [elevation, azimuth] : {std::pair{45.0, 0.0}, std::pair{23.0, 37.0}}) {
        const std::string spec = sunSpec(elevation, azimuth);
        expectWithinPerMipBound(perMipErrors(shaders, spec, brightTexelsSplit()), spec);
        // Every texel sampled, the sun aliases into the sample table's pattern.
        EXPECT_GT(largest(perMipErrors(shaders, spec, everyTexelSampled())), kPerMipBound) << spec;
    }
}

// Maps coarser than mip 1's lobe (about 1.3 degrees; a texel of a 160-wide map is 2.25): the
// sun is one texel, which the bake and the reference both read as the map's bilinear upsample
// (bakeSourceUpsampleFactor, referenceUpsampleFactor). Baked from the map's own texels, its
// cube 32 wide and each bright texel a point light, mip 1 read 0.145 and 0.215 against the
// upsampled reference (0.081 and 0.116 against the texel centres). An 8 x 4 sky is too coarse
// even for the wide lobes (roughness 0.5 needs 38 texels), whose references read the upsample
// too: against its texel centres mips 4 and 5 read 0.085 and 0.051.
// A sun at the zenith of a 256- or 512-wide map lies in its first row, whose light the clamped
// bilinear upsample grew by 9-12%: the wide mips, measured against the map's own texels, read
// 0.09 and 0.12; with the upsample keeping each texel's flux (fluxConservingRowBlends), 0.004.
TEST_F(GlTest, CoarseMapsMeetThePerMipBoundAtEveryMip)
{
    auto shaders = testing::bakeShaderLibrary();
    for (const char* spec : {"builtin:sun?width=128&size=0.5&intensity=1e4", "builtin:sun?width=160&size=0.5&intensity=1e4", "builtin:sky?width=8",
                             "builtin:sun?width=256&elevation=90&size=0.5&intensity=1e5",
                             "builtin:sun?width=512&elevation=-90&size=0.5&intensity=1e5"})
        expectWithinPerMipBound(perMipErrors(shaders, spec, brightTexelsSplit()), spec);
}

// Which maps are upsampled, and how far: as far as a sum over the texels resolves mip 1's
// lobe (845 wide for the default's 0.106), in powers of two, never past 1024 wide once the map
// is that wide, whatever a preset's mip 1 asks.
TEST(BakeSource, UpsampledAsFarAsMipOneNeedsUpToAThousandWide)
{
    const bake::PrefilterSettings settings = bake::defaultPreset().prefilter;
    EXPECT_EQ(bake::bakeSourceUpsampleFactor(settings, 1024), 1);
    EXPECT_EQ(bake::bakeSourceUpsampleFactor(settings, 900), 1);
    EXPECT_EQ(bake::bakeSourceUpsampleFactor(settings, 800), 2); // 845 needed
    EXPECT_EQ(bake::bakeSourceUpsampleFactor(settings, 512), 2);
    EXPECT_EQ(bake::bakeSourceUpsampleFactor(settings, 160), 8);
    EXPECT_EQ(bake::bakeSourceUpsampleFactor(settings, 32), 16);
    bake::PrefilterSettings sharp = settings;
    sharp.levels = 9; // mip 1 at roughness 0.065: a sum over 2258 texels resolves it
    ASSERT_LT(bake::prefilterMipRoughness(sharp, 1), 0.07f);
    EXPECT_EQ(bake::bakeSourceUpsampleFactor(sharp, 1024), 1);
    EXPECT_EQ(bake::bakeSourceUpsampleFactor(sharp, 512), 2);
    EXPECT_EQ(bake::bakeSourceUpsampleFactor(sharp, 300), 4);
    bake::PrefilterSettings mirrorOnly = settings;
    mirrorOnly.levels = 1;
    EXPECT_EQ(bake::bakeSourceUpsampleFactor(mirrorOnly, 64), 1);
}

TEST_F(GlTest, BrightSunDoesNotDependOnTheSampleSetsRotation)
{
    // The sample table is one set for every texel; turned about the normal, the sampled base
    // reads other directions. With the sun summed exactly the result moves by far less than
    // the bound at every mip.
    auto shaders = testing::bakeShaderLibrary();
    const Environment environment = loadEnvironment(sunSpec(45.0, 0.0));
    const bake::BakeResult plain = runBake(shaders, environment, brightTexelsSplit());
    for (float degrees : {17.0f, 45.0f}) {
        bake::BakeSettings turned = brightTexelsSplit();
        turned.prefilter.sampleRotation = degrees;
        const bake::BakeResult result = runBake(shaders, environment, turned);
        for (int level = 1; level < result.prefiltered.levels; ++level)
            EXPECT_LE(relativeDifference(result, plain, level), kPerMipBound) << degrees << " degrees, mip " << level;
    }
}

TEST_F(GlTest, BrightSunErrorDoesNotDependOnYaw)
{
    // The bake has one sample table for every texel and no per-texel rotation; the sun
    // turned about the vertical crosses faces, edges and texel grids differently. Each yaw
    // meets the bound against the exact prefilter of its own map.
    auto shaders = testing::bakeShaderLibrary();
    // Three yaws (one on a face edge), and the sampled contrast at one of them only: each
    // bake of this 1024 x 512 map with its errors takes seconds on llvmpipe.
    double worst = 0.0;
    for (double azimuth : {0.0, 11.25, 52.5}) {
        const std::string spec = sunSpec(32.0, azimuth);
        const double e = largest(perMipErrors(shaders, spec, brightTexelsSplit()));
        EXPECT_LE(e, kPerMipBound) << spec;
        worst = std::max(worst, e);
    }
    const double worstSampled = largest(perMipErrors(shaders, sunSpec(32.0, 11.25), everyTexelSampled()));
    EXPECT_LE(worst, kPerMipBound);
    EXPECT_GT(worstSampled, kPerMipBound);
}

TEST_F(GlTest, LargeBrightAreasMeetThePerMipBoundAtEveryMip)
{
    // Six discs of 15 degrees at 200 over a black sky: far more bright texels than the caps
    // hold, so the threshold rises and most of their radiance stays in the base. Sampled,
    // the rough mips (4, 5) see the discs through a table that every texel shares and alias
    // them (0.036 and 0.045, measured at every texel of their 16 and 8 faces); summed over
    // every texel of a small source mip they do not (0.004 and 0.009).
    auto shaders = testing::bakeShaderLibrary();
    const std::string spec = "builtin:lights?width=1024&count=6&size=15&intensity=200";
    const std::vector<double> errors = perMipErrors(shaders, spec, brightTexelsSplit());
    expectWithinPerMipBound(errors, spec);
    ASSERT_EQ(errors.size(), 5u);
    EXPECT_LE(std::max(errors[3], errors[4]), 0.02) << spec;
    bake::BakeSettings sampledBase = brightTexelsSplit();
    sampledBase.prefilter.exactSumTexels = 0;
    sampledBase.prefilter.exactSumTiledTexels = 0; // else mips 3-5 go to the per-tile sums
    const std::vector<double> sampled = perMipErrors(shaders, spec, sampledBase);
    EXPECT_GT(std::max(sampled[3], sampled[4]), 3.0 * std::max(errors[3], errors[4])) << spec;
}

// A dozen lamps of 5 degrees at 1000 on black: more far cells than the rough mips summed at
// 4 times mip 1's cap, and more lights than a merge at an eighth of alpha let under 8 times
// it, so mip 2 was left to its samples (0.12). Merged at alpha / 2 and capped at 8 times, they
// are summed. Mip 1's cap keeps most of the lamps in its sampled base, whose 8 samples alias
// their edges; refined where the samples disagree (PrefilterSettings::refineFactor), it meets
// the bound too, and so it does with the lamps in mip 1's lists per tile (0.002 unrefined), which
// the refinement's check turns off. Mip 1 is measured at the default 16 x 16 texels a
// face (1536 directions): at 4 x 4 the figure rests on the two or three directions that fall
// near a lamp (0.34 refined, 0.40 not; docs/bake.md, "How many directions the per-mip figure
// needs").
TEST_F(GlTest, ADozenLampsMeetThePerMipBoundAtEveryMip)
{
    auto shaders = testing::bakeShaderLibrary();
    const std::string spec = "builtin:lights?width=1024&count=12&size=5&intensity=1000";
    ASSERT_EQ(bake::AccuracyOptions{}.texelsPerFaceEdge, 16);
    expectWithinPerMipBound(perMipErrors(shaders, spec, brightTexelsSplit()), spec);
    bake::BakeSettings refinedOnly = brightTexelsSplit();
    refinedOnly.prefilter.tileLights = 0;
    EXPECT_LE(perMipErrors(shaders, spec, refinedOnly).front(), kPerMipBound) << spec << ", mip 1 without lights per tile";
    bake::BakeSettings unrefined = refinedOnly;
    unrefined.prefilter.refineFactor = 1;
    EXPECT_GT(perMipErrors(shaders, spec, unrefined).front(), kPerMipBound) << spec << ", mip 1 unrefined";
}

// Mip 2 is refined as mip 1 is (kLastRefinedMip): on courtyard.exr its 24 samples alias the
// sunlit walls that mip 2's caps leave in its base, 0.028-0.030 at 1536 and 6144 directions,
// and refined where they disagree 0.010. Held to half the unrefined figure, it fails if mip 2
// is left unrefined (both are within the 0.05 bound, which cannot tell them apart).
TEST_F(GlTest, RefiningMipTwoHalvesItsErrorOnCourtyard)
{
    auto shaders = testing::bakeShaderLibrary();
    const std::string spec = std::string(IBLAB_ASSET_DIR) + "/environments/courtyard.exr";
    const std::vector<double> refined = perMipErrors(shaders, spec, brightTexelsSplit());
    bake::BakeSettings unrefined = brightTexelsSplit();
    unrefined.prefilter.refineFactor = 1;
    const std::vector<double> plain = perMipErrors(shaders, spec, unrefined);
    ASSERT_EQ(refined.size(), 5u);
    ASSERT_EQ(plain.size(), 5u);
    EXPECT_LE(refined[1], 0.5 * plain[1]) << "mip 2";
    expectWithinPerMipBound(refined, spec);
}

// Every prefiltered texel of the default bake of a white environment, within 0.1% of 1 (the
// half-float store rounds 1 by at most 4.9e-4). A guard on the sampled part's normalisation:
// a uniform map has no texel above the threshold, so this cannot tell the estimators apart.
// The forced split below checks the exact sum's normalisation Z(alpha).
void expectWhite(const bake::BakeResult& result, float tolerance, const char* what)
{
    for (int level = 1; level < result.prefiltered.levels; ++level) {
        const bake::CubeImage image = bake::readCubeLevel(result.prefiltered, level);
        for (const glm::vec4& t : image.texels)
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(t[c], 1.0f, tolerance) << what << ", prefiltered mip " << level;
    }
}

TEST_F(GlTest, WhiteFurnace)
{
    auto shaders = testing::bakeShaderLibrary();
    expectWhite(runBake(shaders, loadEnvironment("builtin:white?width=64"), bake::defaultPreset()), 1e-3f, "default");
    expectWhite(runBake(shaders, loadEnvironment("builtin:white?width=64"), brightTexelsSplit()), 1e-3f, "bright texels");

    // The split forced onto it: a threshold of half the mean puts every texel of a 32 x 16
    // equirect (512 of them, the lights' source) above it, so half of every result is the
    // exact sum of 512 points of light (none merged: they are further apart than an eighth
    // of either lobe) and half the sampled base. The points are at most 11 degrees apart,
    // and a sum of the lobe over them is within 0.5% of its integral at roughness 0.5 and 1;
    // a wrong Z or solid angle is off by far more.
    bake::BakeSettings settings = testing::smallBakeSettings();
    settings.cube.faceSize = 8;
    settings.prefilter.faceSize = 4;
    settings.prefilter.levels = 3;
    settings.prefilter.brightTexels = 512;
    settings.prefilter.brightThreshold = 0.5f;
    expectWhite(runBake(shaders, loadEnvironment("builtin:white?width=32"), settings), 5e-3f, "split forced");
}

// The split's bases on the GPU (BakePasses::clampedBases) against the same arithmetic on
// the CPU: each texel's luminance clamped to the base's threshold (chroma kept; a texel that
// is not finite becomes grey at the threshold), blocks of 2 x 2 and 4 x 4 texels averaged
// into faces a half and a quarter the size, and the first of those levels' mips. Two
// thresholds from one pass, so that a swapped or shared threshold fails; one face is dim
// (its 2 x 2 blocks are taken whole from the environment's level 1, as too dim to hold a
// texel above either threshold) but for one bright texel, whose block must be clamped.
TEST_F(GlTest, SplitBasesAreTheClampedEnvironmentBoxAveraged)
{
    auto shaders = testing::bakeShaderLibrary();
    bake::BakePasses passes(shaders);
    constexpr int kFace = 8;
    constexpr int kDimFace = 3;
    bake::CubeImage source;
    source.size = kFace;
    source.texels.resize(6 * kFace * kFace);
    for (std::size_t i = 0; i < source.texels.size(); ++i) {
        const float v = float((i * 37) % 11) + 0.25f;
        source.texels[i] = int(i) / (kFace * kFace) == kDimFace ? glm::vec4(0.05f * v, 0.04f * v, 0.03f * v, 1.0f)
                                                                : glm::vec4(v, 0.5f * v, i % 7 == 0 ? 40.0f * v : 0.1f, 1.0f);
    }
    source.texels[kDimFace * kFace * kFace + 2 * kFace + 5] = glm::vec4(80.0f, 60.0f, 40.0f, 1.0f);
    source.texels[5] = glm::vec4(std::numeric_limits<float>::infinity(), 1.0f, 1.0f, 1.0f);
    const bake::BakedTexture environment = bake::createCubeTexture(GL_RGBA32F, kFace, 4);
    bake::uploadCubeLevel(environment, 0, source);
    passes.generateMips(environment);
    const std::vector<float> thresholds = {30.0f, 4.0f};

    auto clamped = [](glm::vec3 rgb, float threshold) {
        const float y = 0.2126f * rgb.r + 0.7152f * rgb.g + 0.0722f * rgb.b;
        if (!std::isfinite(y))
            return glm::vec3(threshold);
        return y > threshold ? rgb * (threshold / y) : rgb;
    };
    // The clamped average of the step x step block of source texels at (x, row) of a face step times smaller.
    auto expected = [&](int face, int x, int row, int step, float threshold) {
        glm::vec3 sum(0.0f);
        for (int dy = 0; dy < step; ++dy)
            for (int dx = 0; dx < step; ++dx)
                sum += clamped(source.rgb(face, step * x + dx, step * row + dy), threshold);
        return sum / float(step * step);
    };
    for (int step : {2, 4}) {
        std::vector<bake::BakedTexture> bases;
        bases.push_back(bake::createCubeTexture(GL_RGBA32F, kFace / step, 2));
        bases.push_back(bake::createCubeTexture(GL_RGBA32F, kFace / step, 2));
        passes.clampedBases(environment, bases, thresholds);
        for (std::size_t b = 0; b < bases.size(); ++b)
            for (int level = 0; level < 2; ++level) {
                const bake::CubeImage image = bake::readCubeLevel(bases[b], level);
                const int texelStep = step << level;
                for (int face = 0; face < 6; ++face)
                    for (int row = 0; row < image.size; ++row)
                        for (int x = 0; x < image.size; ++x) {
                            const glm::vec3 want = expected(face, x, row, texelStep, thresholds[b]);
                            for (int k = 0; k < 3; ++k)
                                ASSERT_NEAR(image.rgb(face, x, row)[k], want[k], 1e-4f * std::max(1.0f, want[k]))
                                    << "step " << step << ", base " << b << ", mip " << level << ", face " << face << ", texel " << x << ", " << row;
                        }
            }
    }
}

// The bases start at the level nearest the finest any split mip reads: the default's mip 1
// refines with 64 samples (8 x refineFactor 8 at roughness 0.11), which read about lod -0.55
// of a 256 cube at its lobe's peak (0.45 of a 512 cube, 1.45 of a 1024 one), but no finer than
// the level with a 256 face (texels half of mip 1's); its first 8 alone read lod 0.95 (1.95,
// 2.95). A table of 512 samples reads below lod 0 of a 256 cube, and without the PDF's source
// mips every sample reads level 0.
TEST(BrightTexelSplit, BasesStartAtTheFinestLevelTheSamplesRead)
{
    bake::PrefilterSettings settings = bake::defaultPreset().prefilter;
    EXPECT_EQ(bake::splitBaseTopLevel(settings, 256, 9), 0);
    EXPECT_EQ(bake::splitBaseTopLevel(settings, 512, 10), 1);
    EXPECT_EQ(bake::splitBaseTopLevel(settings, 1024, 11), 2);
    settings.refineFactor = 1;
    EXPECT_EQ(bake::splitBaseTopLevel(settings, 256, 9), 1);
    EXPECT_EQ(bake::splitBaseTopLevel(settings, 512, 10), 2);
    EXPECT_EQ(bake::splitBaseTopLevel(settings, 1024, 11), 3);
    settings.samples = 512;
    EXPECT_EQ(bake::splitBaseTopLevel(settings, 256, 9), 0);
    settings = bake::defaultPreset().prefilter;
    settings.mipFiltering = false;
    EXPECT_EQ(bake::splitBaseTopLevel(settings, 256, 9), 0);
}

// The scale of mip 1's refinement: the RMS of the luminance clamped at a threshold, over the
// sphere by solid angle, with the texels the candidate list left out (below its raised floor)
// counted once and the listed ones clamped. Checked against a direct sum over the map, for
// thresholds at the floor, between the listed texels' values and above all of them.
TEST(BrightTexelSplit, ClampedRmsCountsEveryTexelOnce)
{
    ImageRGB32F map(64, 32);
    for (int y = 0; y < map.height; ++y)
        for (int x = 0; x < map.width; ++x) {
            const float v = 0.5f + 0.01f * float((x * 7 + y * 3) % 13) + (x % 16 == 3 && y % 8 == 4 ? 40.0f + float(x) + 2.0f * float(y) : 0.0f);
            for (int c = 0; c < 3; ++c)
                map.texels[map.offset(x, y) + std::size_t(c)] = v;
        }
    // Four listed texels of the 16 above 4 x the mean: the floor rises to the fifth brightest.
    const bake::BrightCandidates candidates = bake::brightCandidates(map, 4.0f, 4);
    ASSERT_EQ(candidates.texels.size(), 4u);
    for (float threshold : {candidates.floorThreshold, 0.5f * (candidates.floorThreshold + candidates.texels.front().luminance), 1e4f}) {
        double squared = 0.0;
        for (int y = 0; y < map.height; ++y)
            for (int x = 0; x < map.width; ++x) {
                const double clamped = std::min(double(map.at(x, y).x), double(threshold)); // grey: luminance = value
                squared += clamped * clamped * equirectTexelSolidAngle(y, map.width, map.height);
            }
        EXPECT_NEAR(bake::clampedLuminanceRms(candidates, threshold), std::sqrt(squared / (4.0 * kPi)), 1e-4) << threshold;
    }
}

// The refined mips' spread is compared with the RMS of the clamped base averaged in blocks as
// wide as their samples' footprint (block_luminance.hpp). Checked against a direct sum: each
// texel clamped at the threshold, each block's mean by solid angle, their RMS over the sphere.
// Blocks of one texel are the unblocked RMS.
TEST(BrightTexelSplit, BlockRmsIsTheClampedMapAveragedOverBlocks)
{
    ImageRGB32F map(64, 32);
    for (int y = 0; y < map.height; ++y)
        for (int x = 0; x < map.width; ++x) {
            // A line one texel wide every 8 columns, brighter down the map, on a dim ramp.
            const float v = 0.2f + 0.01f * float(y) + (x % 8 == 5 ? 30.0f + float(y) : 0.0f);
            for (int c = 0; c < 3; ++c)
                map.texels[map.offset(x, y) + std::size_t(c)] = v;
        }
    bake::BlockLuminance texels; // blocks of one texel, from the candidates' scan of the map
    texels.scale = 0;
    bake::BrightCandidates candidates = bake::brightCandidates(map, 4.0f, 1 << 14, &texels);
    ASSERT_FALSE(candidates.texels.empty());
    candidates.refinedMipBlocks = {bake::coarsenedBlocks(texels, 0, 1), bake::coarsenedBlocks(texels, 2, 2)};
    for (float threshold : {candidates.floorThreshold, 45.0f, 1e4f}) {
        EXPECT_NEAR(bake::clampedLuminanceRms(candidates, threshold, 1), bake::clampedLuminanceRms(candidates, threshold), 1e-5) << threshold;
        double squared = 0.0;
        for (int by = 0; by < map.height; by += 4)
            for (int bx = 0; bx < map.width; bx += 4) {
                double sum = 0.0, solidAngle = 0.0;
                for (int y = by; y < by + 4; ++y)
                    for (int x = bx; x < bx + 4; ++x) {
                        const double omega = equirectTexelSolidAngle(y, map.width, map.height);
                        sum += std::min(double(map.at(x, y).x), double(threshold)) * omega; // grey: luminance = value
                        solidAngle += omega;
                    }
                squared += (sum / solidAngle) * (sum / solidAngle) * solidAngle;
            }
        const double blocked = bake::clampedLuminanceRms(candidates, threshold, 2);
        EXPECT_NEAR(blocked, std::sqrt(squared / (4.0 * kPi)), 1e-6) << threshold;
        // Lines a quarter of a block wide: diluted, their RMS about half the texels' (sqrt 1/4).
        EXPECT_LT(blocked, 0.6 * bake::clampedLuminanceRms(candidates, threshold)) << threshold;
    }
}

// A block is as wide as the median sample's footprint: wider for mip 2 (a wider lobe, 24
// samples) than for mip 1 (8), one step more on a map twice as wide, and narrower with 8 times
// the samples (each a solid angle 8 times smaller: 1.5 levels).
TEST(BrightTexelSplit, BlockScaleFollowsTheSamplesFootprint)
{
    bake::PrefilterSettings settings = bake::defaultPreset().prefilter;
    const int mip1 = bake::refinedSampleScale(settings, 1, 1024, 512), mip2 = bake::refinedSampleScale(settings, 2, 1024, 512);
    EXPECT_GT(mip1, 0);
    EXPECT_GT(mip2, mip1);
    EXPECT_EQ(bake::refinedSampleScale(settings, 1, 2048, 1024), mip1 + 1);
    EXPECT_EQ(bake::refinedSampleScale(settings, 2, 2048, 1024), mip2 + 1);
    settings.samples *= 8;
    const int finer = bake::refinedSampleScale(settings, 1, 1024, 512);
    EXPECT_TRUE(finer == mip1 - 1 || finer == mip1 - 2) << finer << " against " << mip1;
}

// Thin bright lines (builtin:slits: 48 of 0.3 degrees at 100 on black, the map that showed the
// problem, docs/bake.md): mip 2's 24 samples each read a source texel several lines wide and
// spread little against the full-resolution RMS, so they were not refined (0.093 at mip 2).
// Against the RMS of the base in blocks as wide as their footprint (under half of it here)
// mips 2-5 meet the bound. Mip 1 does not (0.083): "What is not met" in docs/bake.md.
TEST_F(GlTest, ThinBrightLinesMeetThePerMipBoundFromMipTwo)
{
    auto shaders = testing::bakeShaderLibrary();
    const std::string spec = "builtin:slits?width=1024";
    const Environment environment = loadEnvironment(spec);
    const bake::PrefilterSettings settings = brightTexelsSplit().prefilter;
    const bake::BrightCandidates candidates = bake::splitCandidates(environment.image, settings);
    const bake::BrightSplitPlan plan = bake::planBrightSplit(candidates, settings);
    const float threshold = plan.levels.at(2).threshold;
    EXPECT_LT(bake::clampedLuminanceRms(candidates, threshold, 2), 0.5 * bake::clampedLuminanceRms(candidates, threshold));
    expectWithinPerMipBound(perMipErrors(shaders, spec, brightTexelsSplit()), spec, 2);
}

// 300 lamps of one texel each, at 200 to 2000 below the horizon of a dim sky: more far cells
// than the rough mips' blocks hold. The lights hold each lamp's excess from the map, while the
// environment pass spreads each lamp over several cube texels; where the spread fell under the
// threshold, the clamp in the cube left it in the base too, and mips 2-5 were about a quarter
// too bright (0.26-0.29 on the held-out citylights map). Resampled from the map clamped near
// the lamps (near_lights.hpp), mips 4-5 (exact sums of the base) are within 0.02. With mips 1
// and 2 listing their lights per tile (tile_lights.hpp) every mip meets the bound. With a
// block at mip 2 instead, capped at 128 far cells, the lamps it left to its samples put it over
// (0.053); the base that cap leaves is spiky, so the rough blocks' caps are four times as large
// (planBrightSplit) and it reads 0.0005 (mip 1, without its band per tile, 0.119).
TEST_F(GlTest, ManySmallLampsAreNotCountedTwice)
{
    auto shaders = testing::bakeShaderLibrary();
    Environment environment;
    environment.source = "300 one-texel lamps";
    environment.image = ImageRGB32F(1024, 512);
    for (int y = 0; y < environment.image.height; ++y)
        for (int x = 0; x < environment.image.width; ++x)
            for (int c = 0; c < 3; ++c)
                environment.image.texels[environment.image.offset(x, y) + std::size_t(c)] = y < 256 ? 0.05f : 0.02f;
    scatterLamps(environment.image, 300, 262, 70, 200.0f, 1800u, 1.0f, 29);
    environment.contentHash = 0x29;
    const std::vector<double> errors = perMipErrors(shaders, environment, brightTexelsSplit());
    ASSERT_EQ(errors.size(), 5u);
    // Mips 4 and 5 sum their base exactly, so what is left there is what was counted twice.
    EXPECT_LE(std::max(errors[3], errors[4]), 0.02) << environment.source;
    expectWithinPerMipBound(errors, environment.source);
    bake::BakeSettings blocks = brightTexelsSplit();
    blocks.prefilter.tileLights = 0;
    EXPECT_LE(perMipErrors(shaders, environment, blocks).at(1), kPerMipBound) << environment.source << ", mip 2 from a block";
}

// 32 lamps of 0.3 degrees at 1000 below the horizon, on black: far more lights than mip 1's
// far-cell cap, which leaves them to its base, where its samples alias them (0.076 at mip 1
// without lights per tile). Listed per tile (tile_lights.hpp), every mip meets the bound.
TEST_F(GlTest, ManySmallLampsMeetThePerMipBoundAtMipOne)
{
    auto shaders = testing::bakeShaderLibrary();
    const std::string spec = "builtin:lights?width=1024&count=32&size=0.3&intensity=1000&elevation=-10";
    expectWithinPerMipBound(perMipErrors(shaders, spec, brightTexelsSplit()), spec);
    bake::BakeSettings withoutTileLights = brightTexelsSplit();
    withoutTileLights.prefilter.tileLights = 0;
    EXPECT_GT(perMipErrors(shaders, spec, withoutTileLights).front(), kPerMipBound) << spec << ", mip 1 without lights per tile";
}

// Lights per tile on lamps at random places. Mip 1's kind, a band below a block's threshold
// within bandReach: no tile lists more than the cap, the threshold is as low as the cap
// allows, and every tile's list holds the band's flux within reach of its centre. Mip 2's kind,
// every light within the hemisphere and a threshold no lower than the one given: the same.
TEST(BrightTexelSplit, TileLightsHoldTheBandNearEveryTile)
{
    ImageRGB32F map(512, 256);
    std::fill(map.texels.begin(), map.texels.end(), 0.05f);
    scatterLamps(map, 200, 40, 176, 50.0f, 500u, 0.8f, 7);
    const bake::BrightCandidates candidates = bake::brightCandidates(map, 4.0f, bake::kMaxBrightCandidates);
    const int cap = 24;

    const double roughness = 0.1;
    const float upper = 400.0f;
    const double reach = bake::bandReach(roughness);
    const bake::TileLights band = bake::planTileLights(candidates, upper, roughness, 64, cap, reach);
    ASSERT_EQ(band.tilesPerEdge, 64 / bake::kTileLightsTile);
    EXPECT_LT(band.threshold, upper);
    EXPECT_GE(band.threshold, candidates.floorThreshold);
    EXPECT_LE(band.longestList, cap);
    EXPECT_GT(band.longestList, cap / 2); // the threshold is as low as the cap allows
    expectTilesHoldTheFluxNearThem(band, candidates, upper, reach);

    const float infinite = std::numeric_limits<float>::infinity(), lowest = 450.0f;
    // The tiles alone would take a lower threshold than `lowest`, which then sets it.
    EXPECT_LT(bake::planTileLights(candidates, infinite, 0.23, 32, cap, 0.5 * kPi).threshold, lowest);
    const bake::TileLights hemisphere = bake::planTileLights(candidates, infinite, 0.23, 32, cap, 0.5 * kPi, lowest);
    ASSERT_EQ(hemisphere.tilesPerEdge, 32 / bake::kTileLightsTile);
    EXPECT_GE(hemisphere.threshold, lowest);
    EXPECT_GT(hemisphere.lights, 0);
    EXPECT_LE(hemisphere.longestList, cap);
    expectTilesHoldTheFluxNearThem(hemisphere, candidates, infinite, 0.5 * kPi);
}

} // namespace
} // namespace iblab
