// The analysis of read-back frames (renderer/frame/frame_analysis): the error report's
// pixel selection and split, the furnace view's sphere readings, and the debug views'
// texel readout, all on synthetic pixels with no GL context.
#include <cmath>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "frame/frame_analysis.hpp"
#include "frame/split_view.hpp"

namespace iblab {
namespace {

FrameReadback uniformFrame(int width, int height, glm::vec4 value)
{
    FrameReadback frame{width, height, {}};
    for (int i = 0; i < width * height; ++i)
        for (int c = 0; c < 4; ++c) frame.rgba.push_back(value[c]);
    return frame;
}

void setPixel(FrameReadback& frame, int x, int y, glm::vec4 value)
{
    for (int c = 0; c < 4; ++c) frame.rgba[(std::size_t(y) * std::size_t(frame.width) + std::size_t(x)) * 4 + std::size_t(c)] = value[c];
}

// A row of five pixels against a reference of 1: relative errors 0.1, 0.2, 0.3, 0.4, 0.5,
// except that pixel 3 is an MSAA edge (coverage 0.5) and the reference misses pixel 4.
struct ErrorRow {
    FrameReadback frame = uniformFrame(5, 1, glm::vec4(1.0f));
    FrameReadback reference = uniformFrame(5, 1, glm::vec4(1.0f));
    FrameReadback normals = uniformFrame(5, 1, glm::vec4(0.0f, 0.0f, 1.0f, 1.0f));
    ErrorRow()
    {
        for (int x = 0; x < 5; ++x) setPixel(frame, x, 0, glm::vec4(glm::vec3(1.0f + 0.1f * float(x + 1)), x == 3 ? 0.5f : 1.0f));
        setPixel(normals, 4, 0, glm::vec4(0.0f));
    }
};

TEST(FrameAnalysis, ErrorMeasuresFullyCoveredReferencePixels)
{
    const ErrorRow row;
    FrameSettings settings;
    const ErrorReport report = frameErrorReport(row.frame, row.reference, row.normals, settings);
    EXPECT_TRUE(report.valid);
    EXPECT_FALSE(report.right);
    EXPECT_EQ(report.left.pixels, 3u) << "the edge pixel and the one the reference misses are left out";
    EXPECT_NEAR(report.left.maxRelative, 0.3, 1e-6);
    EXPECT_NEAR(report.left.meanRelative, 0.2, 1e-6);
}

TEST(FrameAnalysis, ErrorSplitsAtTheDivider)
{
    const ErrorRow row;
    FrameSettings settings;
    settings.view.split = true;
    settings.view.splitPosition = 0.4f; // column 2
    ASSERT_EQ(splitColumn(settings.view, 5), 2);
    const ErrorReport report = frameErrorReport(row.frame, row.reference, row.normals, settings);
    ASSERT_TRUE(report.right);
    EXPECT_EQ(report.left.pixels, 2u);
    EXPECT_NEAR(report.left.maxRelative, 0.2, 1e-6);
    EXPECT_EQ(report.right->pixels, 1u);
    EXPECT_NEAR(report.right->maxRelative, 0.3, 1e-6);
}

TEST(FrameAnalysis, DisplaySpaceComparesToneMappedValues)
{
    const ErrorRow row;
    FrameSettings settings;
    settings.view.errorSpace = ErrorSpace::Display;
    settings.toneMap = {ToneMapOperator::AcesHill, 0.0f};
    const ErrorReport display = frameErrorReport(row.frame, row.reference, row.normals, settings);
    const ErrorReport linear = frameErrorReport(row.frame, row.reference, row.normals, FrameSettings{});
    EXPECT_EQ(display.left.pixels, linear.left.pixels);
    // The tone curve compresses highlights: the same radiance errors shrink on display.
    EXPECT_GT(display.left.maxRelative, 0.0);
    EXPECT_LT(display.left.maxRelative, linear.left.maxRelative);
}

TEST(FrameAnalysis, SphereReadingsAverageTheDiscCentre)
{
    FrameSettings settings;
    const int width = 64, height = 48;
    FrameReadback frame = uniformFrame(width, height, glm::vec4(0.25f, 0.5f, 1.0f, 1.0f));
    // A bright background pixel in a corner, outside the inner disc: it must not count.
    setPixel(frame, 0, 0, glm::vec4(100.0f));
    const std::vector<SphereInstance> spheres = {
        {glm::mat4(1.0f), 0.75f, 0.25f},
        {glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 10.0f)), 0.0f, 0.0f}, // behind the camera: no pixel
    };
    const std::vector<SphereReading> readings = sphereReadings(frame, settings.camera, spheres);
    ASSERT_EQ(readings.size(), 1u);
    EXPECT_NEAR(readings[0].pixel.x, 32.0f, 1e-4f);
    EXPECT_NEAR(readings[0].pixel.y, 24.0f, 1e-4f);
    EXPECT_NEAR(readings[0].radiance.r, 0.25f, 1e-6f);
    EXPECT_NEAR(readings[0].radiance.g, 0.5f, 1e-6f);
    EXPECT_NEAR(readings[0].radiance.b, 1.0f, 1e-6f);
    EXPECT_EQ(readings[0].metallic, 0.75f);
    EXPECT_EQ(readings[0].roughness, 0.25f);
}

TEST(FrameAnalysis, CubeCrossTexelFollowsTheShadersLayout)
{
    // The middle row is -X +Z +X -Z; +Y sits above +Z and -Y below it; rows count from the
    // top of a cell.
    const std::optional<CubeTexel> front = cubeCrossTexel(glm::vec2(0.375f, 0.5f), 16);
    ASSERT_TRUE(front);
    EXPECT_EQ(front->face, 4);
    EXPECT_EQ(front->column, 8);
    EXPECT_EQ(front->row, 8);
    const std::optional<CubeTexel> top = cubeCrossTexel(glm::vec2(0.26f, 0.99f), 16);
    ASSERT_TRUE(top);
    EXPECT_EQ(top->face, 2);
    EXPECT_EQ(top->row, 0);
    EXPECT_EQ(cubeCrossTexel(glm::vec2(0.875f, 0.5f), 16)->face, 5);
    EXPECT_EQ(cubeCrossTexel(glm::vec2(0.1f, 0.5f), 16)->face, 1);
    EXPECT_EQ(cubeCrossTexel(glm::vec2(0.375f, 0.1f), 16)->face, 3);
    EXPECT_FALSE(cubeCrossTexel(glm::vec2(0.1f, 0.9f), 16)) << "the cross's empty corner";
}

TEST(FrameAnalysis, LutTexelStaysInsideTheTexture)
{
    EXPECT_EQ(lutTexel(glm::vec2(0.0f, 0.0f), 32), glm::ivec2(0, 0));
    EXPECT_EQ(lutTexel(glm::vec2(0.5f, 0.26f), 32), glm::ivec2(16, 8));
    EXPECT_EQ(lutTexel(glm::vec2(1.0f, 1.0f), 32), glm::ivec2(31, 31));
}

TEST(FrameAnalysis, TileLocalIsZeroToOneAcrossTheTile)
{
    DebugTile tile;
    tile.rect = glm::vec4(10.0f, 20.0f, 30.0f, 60.0f);
    EXPECT_EQ(tileLocal(tile, 10.0f, 20.0f), glm::vec2(0.0f));
    EXPECT_EQ(tileLocal(tile, 20.0f, 50.0f), glm::vec2(0.5f, 0.75f));
}

TEST(FrameAnalysis, ProbeTextNamesTheTexelAndItsValue)
{
    EXPECT_EQ(prefilterTexelText("mip 2: roughness 0.50", CubeTexel{4, 12, 30}, 64, glm::vec4(0.412f, 0.38f, 0.301f, 1.0f)),
              "mip 2: roughness 0.50, face +Z, texel (12, 30) of 64: 0.412 0.38 0.301");
    EXPECT_EQ(lutTexelText(glm::ivec2(0, 3), 4, glm::vec4(0.5f, 0.25f, 0.75f, 1.0f)), "n.v 0.125, roughness 0.875: A 0.5000, B 0.2500, A+B 0.7500");
}

} // namespace
} // namespace iblab
