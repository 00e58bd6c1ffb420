// The renderer's residual for the fitted lobe (frame/shading_lights_texture.hpp) against the
// CPU's shadingLightResidual, which the accuracy study measures: the renderer subtracts the
// lights from mips 1 and up in a compute pass (shading_lights_residual.comp) and scales the
// lights' blocks of the mirror without reading the mirror back, so the two are compared at
// every texel of every level, to the precision of the bake's half floats.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bake/bake_result.hpp"
#include "bake/bake_settings.hpp"
#include "bake/residual_irradiance.hpp"
#include "bake_test_support.hpp"
#include "frame/shading_lights_texture.hpp"
#include "gl_test_fixture.hpp"
#include "ibl/shading_lights.hpp"
#include "io/environment.hpp"

namespace iblab {
namespace {

using testing::GlTest;
using testing::runBake;

struct LevelDifference {
    double relativeRms = 0.0; // the difference's RMS over the level, against the bake's RMS
    double worst = 0.0;       // the largest texel difference against max(the bake's texel, the bake's RMS)
};

// a - b at every texel, against the bake's level: near a light the residual is what is left of
// a large texel once most of it is subtracted, so it is known to the precision of that texel
// (half floats: 2^-11), not to its own.
LevelDifference difference(const bake::CubeImage& a, const CubeLevelRgb& b, const bake::CubeImage& bakeLevel)
{
    double diff = 0.0, norm = 0.0;
    for (std::size_t i = 0; i < b.texels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double d = double(a.texels[i][c]) - double(b.texels[i][c]);
            diff += d * d;
            norm += double(bakeLevel.texels[i][c]) * double(bakeLevel.texels[i][c]);
        }
    const double rms = std::sqrt(norm / double(b.texels.size() * 3));
    LevelDifference out;
    out.relativeRms = std::sqrt(diff / norm);
    for (std::size_t i = 0; i < b.texels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double d = std::abs(double(a.texels[i][c]) - double(b.texels[i][c]));
            out.worst = std::max(out.worst, d / std::max(double(bakeLevel.texels[i][c]), rms));
        }
    return out;
}

void expectResidualMatchesTheCpus(const std::string& spec, int maxLights, std::size_t minimumLights)
{
    auto shaders = testing::bakeShaderLibrary();
    const Environment environment = loadEnvironment(spec);
    bake::BakeSettings settings = bake::defaultPreset();
    settings.prefilter.shadingLights = maxLights;
    const bake::BakeResult bake = runBake(shaders, environment, settings);
    ASSERT_GE(bake.shadingLights.groups.size(), minimumLights) << spec;
    const auto texture = makeShadingLightsTexture(shaders, bake);
    ASSERT_TRUE(texture) << spec;
    EXPECT_EQ(texture->lights.size(), bake.shadingLights.groups.size());
    EXPECT_EQ(texture->minAlpha, bake.shadingLights.minAlpha());

    std::vector<bake::CubeImage> levels;
    std::vector<CubeLevelRgb> chain;
    std::vector<double> roughness;
    for (int level = 0; level < bake.prefiltered.levels; ++level) {
        levels.push_back(bake::readCubeLevel(bake.prefiltered, level));
        chain.push_back(bake::cubeLevelRgb(levels.back()));
        roughness.push_back(bake::prefilterMipRoughness(bake.settings.prefilter, level));
    }
    const std::vector<CubeLevelRgb> cpu = shadingLightResidual(chain, roughness, bake.shadingLights);
    ASSERT_EQ(int(cpu.size()), texture->residual.levels);
    for (int level = 0; level < texture->residual.levels; ++level) {
        const bake::CubeImage& bakeLevel = levels[std::size_t(level)];
        const LevelDifference d = difference(bake::readCubeLevel(texture->residual, level), cpu[std::size_t(level)], bakeLevel);
        // The GPU sums in float, whose divisions and square roots GLSL allows a few ulps; the
        // bake's texels are half floats, 2^-11 = 4.9e-4 apart.
        EXPECT_LT(d.relativeRms, 5e-4) << spec << " level " << level;
        EXPECT_LT(d.worst, 1e-3) << spec << " level " << level;
        // The lights took most of each level near them (the mirror where their blocks are,
        // every other mip around them), so the comparison is not between two copies of the bake.
        EXPECT_GT(difference(bakeLevel, cpu[std::size_t(level)], bakeLevel).worst, 0.1) << spec << " level " << level;
    }

    // The diffuse sources less the lights: the irradiance cube as subtractShadingLightsIrradiance
    // leaves it (the same arithmetic on the same read-back, rounded to the cube's format), and
    // SH9 less the lights' projection, plain and windowed as the bake windows it.
    ASSERT_TRUE(bake.irradianceCube) << spec;
    const bake::CubeImage irradiance = bake::readCubeLevel(bake.irradianceCube, 0);
    CubeLevelRgb irradianceCpu = bake::cubeLevelRgb(irradiance);
    subtractShadingLightsIrradiance(irradianceCpu, texture->lights);
    const LevelDifference d = difference(bake::readCubeLevel(texture->residualIrradiance, 0), irradianceCpu, irradiance);
    EXPECT_LT(d.worst, 1e-3) << spec;
    EXPECT_GT(difference(irradiance, irradianceCpu, irradiance).worst, 0.1) << spec << ": the lights took part of the irradiance";
    const SH9Color lightsSh = shadingLightsShIrradiance(texture->lights);
    const SH9Color lightsWindowed = applyWindow(lightsSh, bake.sh.window, bake.sh.windowWidth);
    for (std::size_t i = 0; i < lightsSh.c.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(texture->shResidual.c[i][c], bake.sh.irradiance.c[i][c] - lightsSh.c[i][c], 1e-9 * std::abs(lightsSh.c[0][c])) << i;
            EXPECT_NEAR(texture->shResidualWindowed.c[i][c], bake.sh.irradianceWindowed.c[i][c] - lightsWindowed.c[i][c], 1e-9 * std::abs(lightsSh.c[0][c])) << i;
        }
}

// A 0.5 degree sun of 1e4, off every axis and face edge, whose excess is one light or a few.
TEST_F(GlTest, ShadingLightsResidualOfASunIsTheCpus)
{
    expectResidualMatchesTheCpus("builtin:sun?width=1024&size=0.5&intensity=1e4&elevation=23&azimuth=37", bake::defaultPreset().prefilter.shadingLights, 1);
}

// Six discs of 15 degrees with as many lights as a bake may have: groups on several faces.
TEST_F(GlTest, ShadingLightsResidualOfExtendedLightsIsTheCpus)
{
    expectResidualMatchesTheCpus("builtin:lights?width=512", kMaxShadingLights, 8);
}

} // namespace
} // namespace iblab
