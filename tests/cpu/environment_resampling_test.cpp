// Environments past loading: the size cap's energy-preserving downsampling, builtins through
// the same entry point, texel repair and its counts, the content hash, the gallery. Expected
// values come from closed-form formulas or independent reads (environment_test_support.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <xxhash.h>

#include "environment_test_support.hpp"
#include "io/environment.hpp"
#include "io/error.hpp"

using namespace iblab;
using namespace iblab::environment_test;

TEST(Environment, SizeCapDownsamplesPreservingEnergy)
{
    const std::string path = defaultEnvironmentPath((kSourceDir / "assets").string());
    const Environment full = loadEnvironment(path);
    EnvironmentLoadOptions options;
    options.maxWidth = 200; // 1024/200 is not an integer: fractional box weights
    const Environment small = loadEnvironment(path, options);
    EXPECT_EQ(small.image.width, 200);
    EXPECT_EQ(small.image.height, 100);
    EXPECT_TRUE(hasWarningContaining(small, "downsampled"));
    expectFiniteNonNegative(small.image);
    // The filter is solid-angle weighted, so the integral of luminance is preserved up to
    // float accumulation error (~1e-6 relative; 1e-4 leaves room). The pole test below is
    // the one that tells a solid-angle filter from a plain uv-area box.
    EXPECT_NEAR(meanLuminance(small.image), meanLuminance(full.image), 1e-4 * meanLuminance(full.image));
    EXPECT_NE(small.contentHash, full.contentHash);
}

TEST(Environment, SizeCapPreservesEnergyNearThePole)
{
    // Light only in the top 3 of 256 rows, downsampled to 48 rows (5.33 source rows per
    // output row). Solid angle grows like theta^2 near the pole, so a uv-area box filter
    // would give these rows 3/5.33 of the first output row's much larger solid angle and
    // overstate the energy by ~80%; the solid-angle filter keeps it to float rounding.
    TempDir dir;
    const std::string path = dir.file("cap.exr");
    const int w = 512, h = 256;
    std::vector<float> px(std::size_t(w) * h * 3, 0.0f);
    std::fill(px.begin(), px.begin() + std::ptrdiff_t(3) * w * 3, 100.0f);
    writeImage(path, w, h, 3, px);
    double expected = 0.0;
    for (int y = 0; y < 3; ++y)
        expected += rowOmega(y, w, h) * w * 100.0;
    EnvironmentLoadOptions options;
    options.maxWidth = 96;
    const Environment env = loadEnvironment(path, options);
    ASSERT_EQ(env.image.height, 48);
    EXPECT_NEAR(meanLuminance(env.image) * 4.0 * kPiD, expected, 1e-5 * expected);
    EXPECT_EQ(env.image.at(5, 1), glm::vec3(0.0f)); // nothing leaks beyond the first output row
}

TEST(Environment, SizeCapOnConstantMapKeepsTheConstant)
{
    TempDir dir;
    const std::string path = dir.file("const.exr");
    writeImage(path, 512, 256, 3, std::vector<float>(512 * 256 * 3, 3.0f));
    EnvironmentLoadOptions options;
    options.maxWidth = 96;
    const Environment env = loadEnvironment(path, options);
    ASSERT_EQ(env.image.width, 96);
    for (float v : env.image.texels)
        ASSERT_NEAR(v, 3.0f, 3.0f * 1e-5f); // weights of each output texel sum to 1
}

TEST(Environment, BuiltinSpecsLoadThroughTheSameEntryPoint)
{
    const Environment env = loadEnvironment("builtin:sky?top=2");
    EXPECT_EQ(env.source, "builtin:sky?top=2");
    EXPECT_EQ(env.image.width, 512);
    EXPECT_TRUE(env.repair.clean());
    EXPECT_TRUE(env.warnings.empty());
    EnvironmentLoadOptions options;
    options.maxWidth = 256;
    errorOf([&] { loadEnvironment("builtin:white?width=1024", options); }, "builtin:white");
}

// -0.0 becomes +0.0 (uncounted) on rows with nothing else to repair, which take the
// one-pass check, and on rows that do, which take the counting loop: equal-looking maps
// must hash equally.
TEST(Environment, NegativeZeroIsClearedOnCleanAndRepairedRows)
{
    ImageRGB32F image(8, 4);
    for (float& v : image.texels) v = 0.5f;
    image.texels[image.offset(3, 1) + 1] = -0.0f; // a clean row otherwise
    image.texels[image.offset(2, 2)] = -0.0f;     // a row that also holds a NaN
    image.texels[image.offset(5, 2) + 2] = std::numeric_limits<float>::quiet_NaN();
    const TexelRepairReport report = repairTexels(image);
    EXPECT_FALSE(std::signbit(image.texels[image.offset(3, 1) + 1]));
    EXPECT_FALSE(std::signbit(image.texels[image.offset(2, 2)]));
    EXPECT_EQ(report.nanComponents, 1u);
    EXPECT_EQ(report.repairedComponents(), 1u);
    EXPECT_EQ(report.repairedTexels, 1u);
    EXPECT_EQ(image.texels[image.offset(5, 2) + 2], 0.0f);
    ImageRGB32F positive(8, 4);
    for (float& v : positive.texels) v = 0.5f;
    positive.texels[positive.offset(3, 1) + 1] = 0.0f;
    positive.texels[positive.offset(2, 2)] = 0.0f;
    positive.texels[positive.offset(5, 2) + 2] = 0.0f;
    EXPECT_EQ(contentHash(image), contentHash(positive));
}

TEST(Environment, BuiltinNanIsRepairedAndEveryInvalidTexelCounted)
{
    // builtin:nan puts `count` texels of each invalid kind (all three components) on
    // builtin:sky; the loader must count every one and leave a clean map.
    const Environment env = loadEnvironment("builtin:nan?width=128&count=25&negative=-3");
    EXPECT_EQ(env.repair.nanComponents, 75u);
    EXPECT_EQ(env.repair.positiveInfComponents, 75u);
    EXPECT_EQ(env.repair.negativeInfComponents, 75u);
    EXPECT_EQ(env.repair.negativeComponents, 75u);
    EXPECT_EQ(env.repair.repairedTexels, 100u);
    EXPECT_EQ(env.repair.mostNegative, -3.0);
    for (float v : env.image.texels)
        ASSERT_TRUE(std::isfinite(v) && v >= 0.0f);
    ASSERT_EQ(env.warnings.size(), 1u);
    EXPECT_NE(env.warnings[0].find("75 NaN"), std::string::npos) << env.warnings[0];
}

TEST(Environment, ContentHashIsXxh3OverTexelBitsSeededWithSize)
{
    // XXH3 of the documented byte stream (each component's bits, little-endian), built here
    // byte by byte, not from the image's memory.
    ImageRGB32F img(2, 1);
    img.texels = {1.0f, 0.0f, 0.5f, -2.0f, 3.0f, 0.25f};
    std::vector<std::uint8_t> bytes;
    for (float v : img.texels) {
        std::uint32_t u = 0;
        std::memcpy(&u, &v, 4);
        for (int i = 0; i < 4; ++i)
            bytes.push_back(std::uint8_t(u >> (8 * i)));
    }
    const std::uint64_t seed = (std::uint64_t(2) << 32) | 1u; // width << 32 | height
    EXPECT_EQ(contentHash(img), XXH3_64bits_withSeed(bytes.data(), bytes.size(), seed));
    ImageRGB32F other = img;
    other.texels[5] = std::nextafter(0.25f, 1.0f);
    EXPECT_NE(contentHash(other), contentHash(img));
    ImageRGB32F transposed(1, 2);
    transposed.texels = img.texels;
    EXPECT_NE(contentHash(transposed), contentHash(img));
}

TEST(Environment, GalleryListsBundledExrFiles)
{
    const std::string assets = (kSourceDir / "assets").string();
    const std::vector<std::string> gallery = galleryEnvironments(assets);
    ASSERT_FALSE(gallery.empty());
    EXPECT_TRUE(std::is_sorted(gallery.begin(), gallery.end()));
    EXPECT_NE(std::find(gallery.begin(), gallery.end(), defaultEnvironmentPath(assets)), gallery.end());
    for (const std::string& p : gallery) {
        EXPECT_EQ(fs::path(p).extension(), ".exr");
        EXPECT_TRUE(fs::is_regular_file(p));
    }
    EXPECT_TRUE(galleryEnvironments("/nonexistent-iblab-assets").empty());
}

// A map whose repair changed nothing visible (the bundled courtyard's stitching left slightly
// negative texels) gets a calm note saying so; a repair that removes real light, or NaN /
// Inf, keeps the full account. The note read as a damaged file to a newcomer.
TEST(Environment, ANegligibleRepairIsACalmNote)
{
    ImageRGB32F slight(64, 32);
    for (float& v : slight.texels) v = 0.5f;
    for (int x = 0; x < 8; ++x) slight.texels[slight.offset(x, 16) + 1] = -0.003f;
    const TexelRepairReport calm = repairTexels(slight);
    EXPECT_TRUE(calm.negligible());
    EXPECT_NE(calm.summary().find("negligible"), std::string::npos) << calm.summary();
    EXPECT_EQ(calm.summary().find("NaN"), std::string::npos) << calm.summary();

    ImageRGB32F strong(64, 32);
    for (float& v : strong.texels) v = 0.5f;
    for (int x = 0; x < 8; ++x) strong.texels[strong.offset(x, 16) + 1] = -50.0f;
    const TexelRepairReport loud = repairTexels(strong);
    EXPECT_FALSE(loud.negligible());
    EXPECT_NE(loud.summary().find("down to -50"), std::string::npos) << loud.summary();

    slight.texels[slight.offset(3, 3)] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_FALSE(repairTexels(slight).negligible());
}
