// Properties every correct bake has, whatever its sampling error: a white furnace stays
// white, and turning the environment turns every result with it.
#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "bake_test_support.hpp"
#include "gl_test_fixture.hpp"
#include "ibl/conventions.hpp"
#include "ibl/sh.hpp"

namespace iblab {
namespace {

using testing::GlTest;
using testing::environmentFromImage;
using testing::runBake;
using testing::smallBakeSettings;


TEST_F(GlTest, WhiteFurnace)
{
    auto shaders = testing::bakeShaderLibrary();
    const bake::BakeResult result = runBake(shaders, loadEnvironment("builtin:white?width=64"), smallBakeSettings());
    // A uniform environment of radiance 1: every weighted average of it is 1 and every
    // cosine integral pi, whatever the lobe, sample set or lod. 0.5%: the 1 and pi stored
    // in half floats (pi rounds by 3e-4) and float sums of up to 512 terms.
    for (int level = 0; level < result.prefiltered.levels; ++level) {
        const bake::CubeImage image = bake::readCubeLevel(result.prefiltered, level);
        for (const glm::vec4& t : image.texels)
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(t[c], 1.0f, 0.005f) << "prefiltered mip " << level;
    }
    for (bake::IrradianceMethod method : testing::kIrradianceCubeMethods) {
        const std::string name(enumName(method));
        const bake::BakeResult withCube =
            method == result.settings.irradiance ? bake::BakeResult{} : runBake(shaders, loadEnvironment("builtin:white?width=64"), smallBakeSettings(method));
        const bake::BakedTexture& cube = method == result.settings.irradiance ? result.irradianceCube : withCube.irradianceCube;
        ASSERT_TRUE(cube) << name;
        const bake::CubeImage image = bake::readCubeLevel(cube, 0);
        for (const glm::vec4& t : image.texels)
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(t[c], kPi, 0.005 * kPi) << name;
    }
    for (int i = 0; i < 50; ++i) {
        const glm::dvec3 n = glm::normalize(glm::dvec3(std::sin(i * 0.7), std::cos(i * 1.3), std::sin(i * 2.1 + 0.3)));
        const glm::dvec3 E = evaluate(result.sh.irradiance, n);
        const glm::dvec3 Ew = evaluate(result.sh.irradianceWindowed, n);
        // The projection sums texel-centre values of Y_lm times exact row solid angles: exact
        // for band 0, but the bands above pick up the midpoint rule's error within each row,
        // O(1 / height^2): 2e-4 of pi at 64 x 32. (Windowing only scales those bands.)
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(E[c], kPi, 1e-3 * kPi);
            EXPECT_NEAR(Ew[c], kPi, 1e-3 * kPi);
        }
    }
}

// The equirect turned by a quarter turn about +Y: column x of the result is column
// x + W/4 of the input, which is exact (no resampling). Then the result at direction d is
// the input at R d with R = rotateAboutY(., -90 degrees) = (x, y, z) -> (-z, y, x).
ImageRGB32F quarterTurn(const ImageRGB32F& image)
{
    ImageRGB32F out(image.width, image.height);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            out.set(x, y, image.at((x + image.width / 4) % image.width, y));
    return out;
}

glm::vec3 turn(glm::vec3 d) { return rotateAboutY(d, float(-0.5 * kPi)); }

// Relative RMSE between a cube level of the turned bake and the original bake read at the
// turned directions. A quarter turn about Y maps cube texels onto cube texels (faces onto
// faces, the grid onto itself), so the comparison reads texels, no interpolation.
double turnedDifference(const bake::BakedTexture& turned, const bake::BakedTexture& original, int level)
{
    const bake::CubeImage a = bake::readCubeLevel(turned, level);
    const bake::CubeImage b = bake::readCubeLevel(original, level);
    double err2 = 0.0;
    double ref2 = 0.0;
    for (int face = 0; face < 6; ++face)
        for (int row = 0; row < a.size; ++row)
            for (int x = 0; x < a.size; ++x) {
                const glm::vec3 fst = directionToCubeFaceUv(turn(a.texelDirection(face, x, row)));
                const float s = fst.y * float(b.size) - 0.5f;
                const float t = fst.z * float(b.size) - 0.5f;
                EXPECT_NEAR(s, std::round(s), 1e-3f);
                EXPECT_NEAR(t, std::round(t), 1e-3f);
                const glm::dvec3 expected(b.rgb(int(fst.x), int(std::lround(s)), int(std::lround(t))));
                const glm::dvec3 d = glm::dvec3(a.rgb(face, x, row)) - expected;
                err2 += glm::dot(d, d);
                ref2 += glm::dot(expected, expected);
            }
    return std::sqrt(err2 / ref2);
}

void expectBakesTurnTogether(const std::string& spec)
{
    auto shaders = testing::bakeShaderLibrary();
    const Environment original = loadEnvironment(spec);
    const Environment turned = environmentFromImage(quarterTurn(original.image), spec + " turned");
    const bake::BakeSettings settings = smallBakeSettings();
    const bake::BakeResult a = runBake(shaders, original, settings);
    const bake::BakeResult b = runBake(shaders, turned, settings);

    // The environment cube reads the same equirect texels at uv shifted by exactly 1/4 for
    // each pair of texels. Only the top and bottom faces' footprints turn (their edges swap),
    // and where both edges are equally long the taps may run along the other one: measured
    // 2e-3 RMSE on the sun's sharp edge, which a 0.5% bound allows. A swapped or mirrored face
    // moves the sun altogether (differences of 50% and more).
    EXPECT_LT(turnedDifference(b.environmentCube, a.environmentCube, 0), 5e-3) << spec;
    // Irradiance and prefilter place their samples in a tangent frame built from the normal,
    // and that frame does not turn with the environment, so the two bakes integrate with
    // different (equally good) sample sets and differ by twice their sampling error: measured
    // up to 0.5% (Riemann), 2.5% (importance sampling) and 4.7% (prefilter mip 3) on the
    // sun, which has a contrast of 100. A flipped face, a seam, or a mirrored frame puts the
    // sun's light somewhere else: differences of 20% and more.
    auto turnedIrradianceDifference = [&](bake::IrradianceMethod method) {
        const bake::BakeSettings withMethod = smallBakeSettings(method);
        return turnedDifference(runBake(shaders, turned, withMethod).irradianceCube, runBake(shaders, original, withMethod).irradianceCube, 0);
    };
    EXPECT_LT(turnedIrradianceDifference(bake::IrradianceMethod::Riemann), 0.015) << spec;
    EXPECT_LT(turnedIrradianceDifference(bake::IrradianceMethod::Importance), 0.05) << spec;
    // The moment cube has no sample set to turn: a quarter turn maps its groups onto groups
    // and its texels onto texels, so the two agree up to float sums in another order and the
    // half-float store (measured below 1e-3). A group or face read from the wrong place moves
    // the sun's light by a group's width: 10% and more near the terminator.
    ASSERT_EQ(settings.irradiance, bake::IrradianceMethod::Moments);
    EXPECT_LT(turnedDifference(b.irradianceCube, a.irradianceCube, 0), 2e-3) << spec;
    for (int level = 0; level < a.prefiltered.levels; ++level)
        EXPECT_LT(turnedDifference(b.prefiltered, a.prefiltered, level), 0.08) << spec << " prefiltered mip " << level;
    // SH: the projection of the exactly shifted image is the exactly rotated projection.
    for (int i = 0; i < 64; ++i) {
        const glm::dvec3 d = glm::normalize(glm::dvec3(std::sin(i * 0.7), std::cos(i * 1.3), std::sin(i * 2.1 + 0.3)));
        const glm::dvec3 expected = evaluate(a.sh.irradiance, glm::dvec3(turn(glm::vec3(d))));
        EXPECT_LT(glm::length(evaluate(b.sh.irradiance, d) - expected), 1e-4 * glm::length(expected)) << spec;
    }
}

TEST_F(GlTest, QuarterTurnOfTheSunTurnsEveryResult)
{
    // The sun off every axis, large enough to span several texels of the smallest mips.
    expectBakesTurnTogether("builtin:sun?width=128&elevation=30&azimuth=40&size=15&intensity=20&sky=0.2");
}

TEST_F(GlTest, QuarterTurnOfTheStudioTurnsEveryResult)
{
    // Coloured lights in every direction: a swapped or flipped face shows in some channel.
    expectBakesTurnTogether("builtin:studio?width=128");
}

} // namespace
} // namespace iblab
