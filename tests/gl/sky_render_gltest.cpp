// The sky and tone-map passes, checked against values known without the code under test:
// a uniform environment, the horizon splitting the view in half, and where a small sun
// must land for a given camera and environment rotation.
#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>

#include <glm/glm.hpp>

#include "bake/bake_job.hpp"
#include "io/environment.hpp"
#include "gl_test_fixture.hpp"
#include "frame/renderer.hpp"

namespace iblab {
namespace {

using testing::GlTest;

class SkyRender : public GlTest {
protected:
    FrameReadback render(const std::string& environment, const FrameSettings& base, int width, int height)
    {
        Renderer renderer(shaderDirectory());
        renderer.setEnvironment(loadEnvironment(environment).image);
        FrameSettings settings = base;
        settings.environment.source = environment;
        settings.scene.kind = SceneKind::None; // the sky alone
        renderer.renderFrame(settings, width, height);
        lastDisplay = renderer.readDisplayImage();
        return renderer.readHdrFrame();
    }
    DisplayReadback lastDisplay;
};

float pixel(const FrameReadback& frame, int x, int y, int channel = 0)
{
    return frame.rgba[(std::size_t(y) * std::size_t(frame.width) + std::size_t(x)) * 4 + std::size_t(channel)];
}

TEST_F(SkyRender, WhiteFurnaceIsOneEverywhere)
{
    FrameSettings settings;
    settings.toneMap.op = ToneMapOperator::None;
    settings.toneMap.exposureEv = 0.0f;
    const FrameReadback frame = render("builtin:white", settings, 96, 64);
    float worst = 0.0f;
    for (std::size_t i = 0; i < frame.rgba.size(); i += 4)
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(frame.rgba[i + std::size_t(c)] - 1.0f));
    // 1.0 is exact in half float; anything but 0 would be a filtering or scaling bug.
    EXPECT_EQ(worst, 0.0f);
    // "none" clamps to [0, 1] and sRGB(1) = 1, so every display byte is 255.
    EXPECT_TRUE(std::all_of(lastDisplay.rgba.begin(), lastDisplay.rgba.end(), [](std::uint8_t v) { return v == 255; }));
}

TEST_F(SkyRender, IntensityIsInStops)
{
    FrameSettings settings;
    settings.environment.intensityEv = -3.0f;
    const FrameReadback frame = render("builtin:white", settings, 32, 32);
    EXPECT_FLOAT_EQ(pixel(frame, 16, 16), 0.125f);
}

TEST_F(SkyRender, HorizonSplitsTheViewAtTheAnalyticMean)
{
    // Looking at the horizon (pitch 0) the horizon is the middle scanline, so with an even
    // height half the pixels see the sky and half the ground: mean = (top + ground) / 2.
    FrameSettings settings;
    const FrameReadback frame = render("builtin:sky", settings, 64, 64);
    double sum = 0.0;
    for (int y = 0; y < frame.height; ++y)
        for (int x = 0; x < frame.width; ++x) sum += pixel(frame, x, y);
    const double mean = sum / double(frame.width * frame.height);
    // 0.5%: bilinear blending is symmetric about the horizon, but the half-float frame and
    // mip filtering round the two sides slightly differently.
    EXPECT_NEAR(mean, (1.0 + 0.1) / 2.0, 0.0055);
    // Orientation: readback row 0 is the bottom of the image, which must be the ground.
    EXPECT_NEAR(pixel(frame, 32, 0), 0.1f, 1e-3f);
    EXPECT_NEAR(pixel(frame, 32, frame.height - 1), 1.0f, 1e-3f);
}

// Pixel of the brightest value in the frame.
glm::ivec2 brightestPixel(const FrameReadback& frame)
{
    glm::ivec2 best(0);
    float bestValue = -1.0f;
    for (int y = 0; y < frame.height; ++y)
        for (int x = 0; x < frame.width; ++x)
            if (pixel(frame, x, y) > bestValue) {
                bestValue = pixel(frame, x, y);
                best = {x, y};
            }
    return best;
}

TEST_F(SkyRender, SunLandsWhereTheCameraAndRotationSay)
{
    const std::string sun = "builtin:sun?elevation=0&azimuth=90&size=4&intensity=100&width=1024";
    FrameSettings lookEast; // yaw 90: the camera looks down +X, where azimuth 90 puts the sun
    lookEast.camera.yawDegrees = 90.0f;
    const FrameReadback east = render(sun, lookEast, 65, 65);
    EXPECT_LE(glm::length(glm::vec2(brightestPixel(east) - glm::ivec2(32, 32))), 1.5f);

    // Turning the environment by +90 degrees brings the +X sun to -Z, in front of the
    // default camera.
    FrameSettings rotated;
    rotated.environment.yawDegrees = 90.0f;
    const FrameReadback front = render(sun, rotated, 65, 65);
    EXPECT_LE(glm::length(glm::vec2(brightestPixel(front) - glm::ivec2(32, 32))), 1.5f);

    // Positive camera yaw turns right: the sun straight ahead at yaw 0 moves left in view.
    FrameSettings turnedRight = rotated;
    turnedRight.camera.yawDegrees = 10.0f;
    EXPECT_LT(brightestPixel(render(sun, turnedRight, 65, 65)).x, 32 - 5);
}

// With a bake, the background is the bake's environment cube, not the map last given: sky
// and lighting change together when an environment is switched (the GUI shows a cached
// bake before its map has decoded), and a new map draws nothing new until its bake is set.
TEST_F(SkyRender, WithABakeTheSkyIsTheBakesEnvironment)
{
    Renderer renderer(shaderDirectory());
    const Environment black = loadEnvironment("builtin:black?width=64");
    renderer.setEnvironment(loadEnvironment("builtin:white?width=64").image);
    FrameSettings settings;
    settings.scene.kind = SceneKind::None;
    renderer.renderFrame(settings, 32, 32);
    EXPECT_EQ(pixel(renderer.readHdrFrame(), 16, 16), 1.0f) << "no bake yet: the map";

    auto shaders = gl::ShaderLibrary(IBLAB_SHADER_DIR);
    bake::BakeSettings small = bake::defaultPreset();
    small.prefilter.faceSize = 16;
    small.prefilter.levels = 3;
    small.lut = {.size = 16, .samples = 64, .schlickGgx = true, .heightCorrelatedSmith = false};
    renderer.setBake(std::make_shared<bake::BakeResult>(bake::BakeJob(shaders, black, small).runToCompletion()));
    renderer.renderFrame(settings, 32, 32);
    const FrameReadback shown = renderer.readHdrFrame();
    float brightest = 0.0f;
    for (std::size_t i = 0; i < shown.rgba.size(); i += 4) brightest = std::max(brightest, shown.rgba[i]);
    EXPECT_EQ(brightest, 0.0f) << "the black bake's sky over the white map";

    const std::uint64_t revision = renderer.contentRevision();
    renderer.setEnvironment(loadEnvironment("builtin:sky?width=64").image);
    EXPECT_EQ(renderer.contentRevision(), revision) << "the new map is not drawn until its bake is set";
}

} // namespace
} // namespace iblab
