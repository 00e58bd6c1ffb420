// Loading and validating environments: real maps (bundled and shared candidates), and
// bad files generated on the fly. Expected values come from independent sources: the
// shared assets' README, a raw OpenImageIO read done here, or closed-form formulas.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include "io/environment.hpp"
#include "io/error.hpp"
#include "environment_test_support.hpp"
#include "temp_dir.hpp"

namespace fs = std::filesystem;
using namespace iblab;

using namespace iblab::environment_test;

TEST(Environment, BundledCourtyardLoadsCleanly)
{
    const std::string path = defaultEnvironmentPath((kSourceDir / "assets").string());
    const Environment env = loadEnvironment(path);
    EXPECT_EQ(env.image.width, 1024);
    EXPECT_EQ(env.image.height, 512);
    EXPECT_EQ(env.source, path);
    expectFiniteNonNegative(env.image);
    // DWAB leaves a few tiny negatives (about -0.003 per the assets README), nothing else.
    EXPECT_EQ(env.repair.nanComponents, 0u);
    EXPECT_EQ(env.repair.positiveInfComponents + env.repair.negativeInfComponents, 0u);
    EXPECT_GT(env.repair.mostNegative, -0.01);
    EXPECT_LT(env.repair.negativeEnergyShare(), 1e-5);
    EXPECT_FALSE(hasWarningContaining(env, "dynamic range"));
    // The assets README measured mean luminance 0.77 (two digits, so +-0.005): a wrong
    // decode, a scale error or a channel mix-up would miss it by far more than 2%.
    EXPECT_NEAR(meanLuminance(env.image), 0.77, 0.77 * 0.02);
}

TEST(Environment, SharedCourtyardIsTheBundledOne)
{
    const fs::path shared = kSharedAssets / "hdri" / "blender-world" / "courtyard.exr";
    if (!fs::exists(shared))
        GTEST_SKIP() << "shared assets not present at " << kSharedAssets;
    const Environment a = loadEnvironment(shared.string());
    const Environment b = loadEnvironment(defaultEnvironmentPath((kSourceDir / "assets").string()));
    EXPECT_EQ(a.image.width, 1024);
    EXPECT_EQ(a.contentHash, b.contentHash); // same texels -> same cache key, whatever the path
}

TEST(Environment, PmndrsSkyNegativesAreReportedAndRemoved)
{
    const fs::path path = kSharedAssets / "hdri" / "pmndrs" / "sky.exr";
    if (!fs::exists(path))
        GTEST_SKIP() << "shared assets not present at " << kSharedAssets;
    const Environment env = loadEnvironment(path.string());
    EXPECT_EQ(env.image.width, 512);
    EXPECT_EQ(env.image.height, 256);
    expectFiniteNonNegative(env.image);
    EXPECT_GT(env.repair.negativeComponents, 0u);
    EXPECT_LT(env.repair.mostNegative, -1000.0); // README: down to -3361 (luminance), a -3394 component
    EXPECT_GT(env.repair.negativeEnergyShare(), 0.01);
    EXPECT_LT(env.repair.negativeEnergyShare(), 0.30);
    EXPECT_TRUE(hasWarningContaining(env, "negative"));
    EXPECT_NE(env.repair.summary().find("negative"), std::string::npos);
    EXPECT_EQ(env.repair.summary().find('\n'), std::string::npos);

    // Recompute the report from a raw read, independently of the loader.
    int w = 0, h = 0;
    const std::vector<float> raw = readRaw(path.string(), w, h);
    const double k[3] = {0.2126, 0.7152, 0.0722};
    double pos = 0.0, neg = 0.0;
    std::uint64_t negatives = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                const float v = raw[(std::size_t(y) * w + x) * 3 + c];
                (v < 0 ? neg : pos) += rowOmega(y, w, h) * k[c] * std::abs(double(v));
                negatives += v < 0 ? 1 : 0;
                // Every texel that was valid comes through unchanged, negatives become 0.
                ASSERT_EQ(env.image.texels[(std::size_t(y) * w + x) * 3 + c], v < 0 ? 0.0f : v);
            }
    EXPECT_EQ(env.repair.negativeComponents, negatives);
    EXPECT_NEAR(env.repair.negativeEnergyShare(), neg / pos, 1e-9 + 1e-6 * neg / pos);
}

TEST(Environment, EveryPmndrsMapLoadsFiniteAndNonNegative)
{
    const fs::path dir = kSharedAssets / "hdri" / "pmndrs";
    if (!fs::exists(dir))
        GTEST_SKIP() << "shared assets not present at " << kSharedAssets;
    int maps = 0;
    for (const auto& entry : fs::directory_iterator(dir)) {
        if (entry.path().extension() != ".exr")
            continue;
        const Environment env = loadEnvironment(entry.path().string());
        expectFiniteNonNegative(env.image);
        EXPECT_GT(env.repair.negativeComponents, 0u) << entry.path(); // all six have some
        ++maps;
    }
    EXPECT_EQ(maps, 6);
}

TEST(Environment, WrongAspectRatioNamesSizeAndFile)
{
    TempDir dir;
    const std::string path = dir.file("wide.exr");
    writeImage(path, 96, 32, 3, std::vector<float>(96 * 32 * 3, 1.0f));
    const std::string msg = errorOf([&] { loadEnvironment(path); }, "wide.exr");
    EXPECT_NE(msg.find("3:1"), std::string::npos) << msg;
    EXPECT_NE(msg.find("96x32"), std::string::npos) << msg;
}

TEST(Environment, OneTexelOfAspectRoundingIsAccepted)
{
    TempDir dir;
    const std::string path = dir.file("odd.exr");
    writeImage(path, 65, 32, 3, std::vector<float>(65 * 32 * 3, 0.5f));
    const Environment env = loadEnvironment(path);
    EXPECT_EQ(env.image.width, 65);
    EXPECT_EQ(env.image.height, 32);
    const std::string tall = dir.file("tall.exr");
    writeImage(tall, 66, 32, 3, std::vector<float>(66 * 32 * 3, 0.5f));
    errorOf([&] { loadEnvironment(tall); }, "tall.exr");
}

TEST(Environment, SmallestEnvironmentIs8x4)
{
    TempDir dir;
    const std::string smallest = dir.file("smallest.exr");
    writeImage(smallest, 8, 4, 3, std::vector<float>(8 * 4 * 3, 0.5f));
    EXPECT_EQ(loadEnvironment(smallest).image.width, 8);
    const std::string tiny = dir.file("tiny.exr");
    writeImage(tiny, 6, 3, 3, std::vector<float>(6 * 3 * 3, 0.5f));
    errorOf([&] { loadEnvironment(tiny); }, "tiny.exr: too small for an environment: 6x3 (at least 8x4)");
}

TEST(Environment, TruncatedExrIsAnErrorNotZeros)
{
    TempDir dir;
    const std::string good = dir.file("good.exr");
    std::vector<float> px(256 * 128 * 3);
    for (std::size_t i = 0; i < px.size(); ++i)
        px[i] = 1.0f + float(i % 97) * 0.25f;
    writeImage(good, 256, 128, 3, px);
    ASSERT_NO_THROW(loadEnvironment(good));

    std::ifstream in(good, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string cut = dir.file("cut.exr");
    std::ofstream(cut, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size() / 2));
    errorOf([&] { loadEnvironment(cut); }, "cut.exr");
}

TEST(Environment, GarbageEmptyMissingAndDirectoryAreErrors)
{
    TempDir dir;
    const std::string garbage = dir.file("garbage.exr");
    std::string junk(4096, '\0');
    for (std::size_t i = 0; i < junk.size(); ++i)
        junk[i] = char((i * 2654435761u) >> 13);
    std::ofstream(garbage, std::ios::binary) << junk;
    errorOf([&] { loadEnvironment(garbage); }, "garbage.exr");

    const std::string empty = dir.file("empty.exr");
    std::ofstream(empty, std::ios::binary).flush();
    EXPECT_NE(errorOf([&] { loadEnvironment(empty); }, "empty.exr").find("0 bytes"), std::string::npos);

    const std::string missing = dir.file("missing.hdr");
    EXPECT_NE(errorOf([&] { loadEnvironment(missing); }, "missing.hdr").find("no such file"), std::string::npos);

    errorOf([&] { loadEnvironment(dir.path.string()); }, dir.path.string());
    errorOf([&] { loadEnvironment(""); }, "empty");
}

TEST(Environment, AbsurdHeaderSizeIsRejectedBeforeReading)
{
    // A Radiance header promising 40000x20000 texels (8e8 > 2^28) with no pixel data: the
    // loader must refuse it from the header alone (allocating would need 9.6 GB).
    TempDir dir;
    const std::string path = dir.file("huge.hdr");
    std::ofstream(path, std::ios::binary) << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 20000 +X 40000\n";
    const std::string msg = errorOf([&] { loadEnvironment(path); }, "huge.hdr");
    EXPECT_NE(msg.find("40000x20000"), std::string::npos) << msg;
}

namespace {

// An EXR header by hand: magic, version 2 (single-part scanline), then each attribute as
// name, type, declared size and payload.
std::string exrHeader(const std::vector<std::tuple<std::string, std::string, std::int32_t, std::string>>& attributes)
{
    std::string bytes("\x76\x2f\x31\x01\x02\x00\x00\x00", 8);
    for (const auto& [name, type, size, payload] : attributes) {
        bytes += name + '\0' + type + '\0';
        bytes.append(reinterpret_cast<const char*>(&size), 4);
        bytes += payload;
    }
    return bytes + '\0';
}

} // namespace

TEST(Environment, ExrAttributesMustEndWhereTheirSizeSays)
{
    // OpenEXR reads a channel list to its empty name and a box2i as 16 bytes, whatever size
    // the attribute declares; the fuzzer built a channel list longer than declared, behind
    // which OpenEXR found a string claiming 1.8 GB that a walk by the declared sizes skipped.
    TempDir dir;
    const std::string channel = std::string("R\0", 2) + std::string(16, '\x01');
    const std::string huge = "\x72\x65\x61\x70"; // 0x70616572 = 1.88e9 when read as a size
    struct Case {
        const char* file;
        std::string bytes;
        const char* expected;
    };
    const std::vector<Case> cases = {
        {"overrun.exr", exrHeader({{"channels", "chlist", 10, channel + '\0'}}) + std::string("comments\0string\0", 16) + huge,
         "attribute 'channels' (chlist) declares 10 bytes but its channel list runs past them"},
        {"short.exr", exrHeader({{"channels", "chlist", 40, channel + '\0' + std::string(21, '\0')}}),
         "attribute 'channels' (chlist) declares 40 bytes but its channel list ends before them"},
        {"box.exr", exrHeader({{"dataWindow", "box2i", 4, std::string(16, '\0')}}),
         "attribute 'dataWindow' (box2i) declares 4 bytes but its type has 16"},
        {"preview.exr", exrHeader({{"preview", "preview", 12, std::string("\x40\0\0\0\x40\0\0\0\0\0\0\0", 12)}}),
         "a 64x64 preview holds 4096 pixels of 4 bytes after them"},
        // 4 x 1380655685 x 3340214413 = 2^64 + 4: in 64-bit arithmetic 8 + 4 w h wraps to 12.
        {"wrap.exr", exrHeader({{"preview", "preview", 12, std::string("\x45\x22\x4b\x52\x8d\xa0\x17\xc7\0\0\0\0", 12)}}),
         "a 1380655685x3340214413 preview holds 4611686018427387905 pixels"},
        {"strings.exr", exrHeader({{"multiView", "stringvector", 8, std::string("\x05\0\0\0left", 8)}}),
         "holds a string of 5 bytes that does not fit"},
    };
    for (const Case& c : cases) {
        const std::string path = dir.file(c.file);
        std::ofstream(path, std::ios::binary) << c.bytes;
        const std::string message = errorOf([&] { loadEnvironment(path); }, c.file);
        EXPECT_NE(message.find(c.expected), std::string::npos) << message;
    }
}

TEST(Environment, TexelLimitIsTheCallersAndNamedInTheError)
{
    // 4096x2048 is 2^23 texels: under the default limit, over a caller's 2^22.
    TempDir dir;
    const std::string path = dir.file("big.hdr");
    std::ofstream(path, std::ios::binary) << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2048 +X 4096\n";
    const std::string truncated = errorOf([&] { loadEnvironment(path); }, "big.hdr");
    EXPECT_EQ(truncated.find("limit"), std::string::npos) << "the default limit admits 2^23 texels: " << truncated;
    EnvironmentLoadOptions options;
    options.maxSourceTexels = std::uint64_t(1) << 22;
    const std::string refused = errorOf([&] { loadEnvironment(path, options); }, "big.hdr");
    EXPECT_NE(refused.find("4096x2048 is 8388608 texels, more than the limit of 4194304 (2^22)"), std::string::npos) << refused;
}

TEST(Environment, NanInfAndNegativeTexelsAreCountedAndZeroed)
{
    TempDir dir;
    const std::string path = dir.file("bad_values.exr");
    const int w = 16, h = 8;
    std::vector<float> px(std::size_t(w) * h * 3, 2.0f);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    px[0] = nan;        // texel 0
    px[1] = nan;        // texel 0 again
    px[3 * 5 + 2] = inf;   // texel 5
    px[3 * 9 + 1] = -inf;  // texel 9
    px[3 * 20 + 0] = -4.0f; // texel 20
    writeImage(path, w, h, 3, px);
    const Environment env = loadEnvironment(path);
    EXPECT_EQ(env.repair.nanComponents, 2u);
    EXPECT_EQ(env.repair.positiveInfComponents, 1u);
    EXPECT_EQ(env.repair.negativeInfComponents, 1u);
    EXPECT_EQ(env.repair.negativeComponents, 1u);
    EXPECT_EQ(env.repair.repairedTexels, 4u);
    EXPECT_EQ(env.repair.mostNegative, -4.0);
    expectFiniteNonNegative(env.image);
    for (std::size_t i = 0; i < px.size(); ++i)
        EXPECT_EQ(env.image.texels[i], std::isfinite(px[i]) && px[i] >= 0 ? px[i] : 0.0f) << i;
    // Share: -4 in the red of texel 20 (row 1) against 2.0 luminance everywhere else.
    double pos = 0.0;
    for (int y = 0; y < h; ++y)
        pos += rowOmega(y, w, h) * w * 2.0;
    pos -= rowOmega(0, w, h) * 2.0 * (0.2126 + 0.7152) + rowOmega(0, w, h) * 2.0 * (0.0722 + 0.7152) +
           rowOmega(1, w, h) * 2.0 * 0.2126;
    EXPECT_NEAR(env.repair.negativeEnergyShare(), rowOmega(1, w, h) * 0.2126 * 4.0 / pos, 1e-12);
    EXPECT_NE(env.repair.summary().find("NaN"), std::string::npos);
}

TEST(Environment, EightBitPngLoadsLinearisedWithLdrWarning)
{
    TempDir dir;
    const std::string path = dir.file("ldr.png");
    std::vector<float> px(32 * 16 * 3, 128.0f / 255.0f);
    writeImage(path, 32, 16, 3, px, OIIO::TypeDesc::UINT8);
    const Environment env = loadEnvironment(path);
    EXPECT_TRUE(hasWarningContaining(env, "dynamic range"));
    // sRGB EOTF of 128/255, by the IEC 61966-2-1 formula.
    const double expected = std::pow((128.0 / 255.0 + 0.055) / 1.055, 2.4);
    EXPECT_NEAR(env.image.texels[0], expected, 1e-5);
    EXPECT_NEAR(env.image.texels.back(), expected, 1e-5);
}

// OpenImageIO names every PNM file "Rec709". Netpbm's PPM samples carry BT.709's transfer
// function; a PFM's floats are linear, and an HDR map in one loads without a colour-space note.
TEST(Environment, PfmLoadsLinearWithoutAColourSpaceNote)
{
    TempDir dir;
    const std::string path = dir.file("map.pfm");
    std::vector<float> px(32 * 16 * 3, 0.5f);
    px[3 * 40] = 2000.0f;
    // OpenImageIO reads PFM but does not write it: the header by hand, then the rows bottom
    // first, little-endian (the scale's sign says so).
    std::ofstream file(path, std::ios::binary);
    file << "PF\n32 16\n-1.0\n";
    for (int y = 15; y >= 0; --y)
        for (int x = 0; x < 32 * 3; ++x) {
            const float v = px[std::size_t(y) * 32 * 3 + std::size_t(x)];
            unsigned char bytes[4];
            std::memcpy(bytes, &v, 4);
            if constexpr (std::endian::native == std::endian::big)
                std::reverse(bytes, bytes + 4);
            file.write(reinterpret_cast<const char*>(bytes), 4);
        }
    file.close();
    const Environment env = loadEnvironment(path);
    EXPECT_TRUE(env.warnings.empty()) << ::testing::PrintToString(env.warnings);
    EXPECT_EQ(env.image.texels[0], 0.5f);
    EXPECT_EQ(*std::max_element(env.image.texels.begin(), env.image.texels.end()), 2000.0f);
}

TEST(Environment, EightBitPpmDecodesBt709sTransferFunction)
{
    TempDir dir;
    const std::string path = dir.file("ldr.ppm");
    std::vector<float> px(32 * 16 * 3, 128.0f / 255.0f);
    px[0] = 51.0f / 255.0f; // 0.2: above the linear segment's end at 0.081
    px[1] = 10.0f / 255.0f; // on the linear segment
    writeImage(path, 32, 16, 3, px, OIIO::TypeDesc::UINT8);
    const Environment env = loadEnvironment(path);
    EXPECT_TRUE(hasWarningContaining(env, "BT.709")) << ::testing::PrintToString(env.warnings);
    EXPECT_FALSE(hasWarningContaining(env, "unknown colour space"));
    // BT.709-6 item 1.2 inverted by hand: L = ((V + 0.099) / 1.099)^(1 / 0.45), or V / 4.5.
    EXPECT_NEAR(env.image.texels[0], std::pow((0.2 + 0.099) / 1.099, 1.0 / 0.45), 1e-5);
    EXPECT_NEAR(env.image.texels[1], 10.0 / 255.0 / 4.5, 1e-6);
    EXPECT_NEAR(env.image.texels.back(), std::pow((128.0 / 255.0 + 0.099) / 1.099, 1.0 / 0.45), 1e-5);
}

TEST(Environment, EnvironmentImagesAreKnownByExtensionInAnyCase)
{
    for (const char* path : {"a.exr", "b.HDR", "dir/c.pfm", "d.tif", "e.TIFF", "f.png", "g.jpg", "h.Jpeg"})
        EXPECT_TRUE(isEnvironmentImagePath(path)) << path;
    for (const char* path : {"a.glb", "b.gltf", "c.json", "d.ktx", "e.ktx2", "f.txt", "exr", "dir.exr/g", ""})
        EXPECT_FALSE(isEnvironmentImagePath(path)) << path;
}

TEST(Environment, FloatMapWithoutValuesAboveOneWarns)
{
    TempDir dir;
    const std::string path = dir.file("dim.exr");
    writeImage(path, 32, 16, 3, std::vector<float>(32 * 16 * 3, 0.25f));
    const Environment env = loadEnvironment(path);
    EXPECT_TRUE(hasWarningContaining(env, "dynamic range"));
    EXPECT_EQ(env.image.texels[7], 0.25f); // linear EXR: no decode
}

TEST(Environment, RadianceHdrLoadsLinear)
{
    TempDir dir;
    const std::string path = dir.file("map.hdr");
    std::vector<float> px(64 * 32 * 3);
    for (std::size_t i = 0; i < px.size(); ++i)
        px[i] = 0.01f + float(i % 50); // up to 49: HDR
    writeImage(path, 64, 32, 3, px);
    const Environment env = loadEnvironment(path);
    EXPECT_FALSE(hasWarningContaining(env, "dynamic range"));
    // RGBE keeps 8 mantissa bits for the largest channel of a texel: smaller channels of
    // the same texel lose more, so compare each channel to the texel's maximum.
    for (std::size_t t = 0; t < 64 * 32; ++t) {
        const float m = std::max({px[t * 3], px[t * 3 + 1], px[t * 3 + 2]});
        for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(env.image.texels[t * 3 + c], px[t * 3 + c], m / 128.0f) << t;
    }
}

TEST(Environment, GreyIsReplicatedAndAlphaDropped)
{
    TempDir dir;
    const std::string grey = dir.file("grey.exr");
    std::vector<float> g(32 * 16);
    for (std::size_t i = 0; i < g.size(); ++i)
        g[i] = float(i) * 0.5f;
    writeImage(grey, 32, 16, 1, g);
    const Environment eg = loadEnvironment(grey);
    for (std::size_t i = 0; i < g.size(); ++i)
        for (int c = 0; c < 3; ++c)
            ASSERT_EQ(eg.image.texels[i * 3 + c], g[i]);

    const std::string rgba = dir.file("rgba.exr");
    std::vector<float> p(32 * 16 * 4);
    for (std::size_t i = 0; i < p.size(); ++i)
        p[i] = i % 4 == 3 ? 0.0f : float(i);
    writeImage(rgba, 32, 16, 4, p);
    const Environment ea = loadEnvironment(rgba);
    for (std::size_t i = 0; i < 32 * 16; ++i)
        for (int c = 0; c < 3; ++c)
            ASSERT_EQ(ea.image.texels[i * 3 + c], p[i * 4 + c]);
}

TEST(Environment, TiledExrReadsLikeScanlines)
{
    TempDir dir;
    const int w = 160, h = 80; // not a multiple of the 64-texel tiles
    std::vector<float> px(std::size_t(w) * h * 3);
    for (std::size_t i = 0; i < px.size(); ++i)
        px[i] = float(i % 1013) * 0.125f;
    const std::string tiled = dir.file("tiled.exr");
    writeImage(tiled, w, h, 3, px, OIIO::TypeDesc::FLOAT, 64);
    const Environment env = loadEnvironment(tiled);
    ASSERT_EQ(env.image.texels.size(), px.size());
    EXPECT_EQ(env.image.texels, px);
}

TEST(Environment, AbsurdTileSizeIsRejectedBeforeReading)
{
    // A 16x8 tiled EXR whose header claims tiles 2^24 texels high: the fuzzer found that the
    // reader then allocated a band of whole tile rows, 3 GB for an 8-row image.
    TempDir dir;
    const int w = 16, h = 8;
    const std::string path = dir.file("tall-tiles.exr");
    writeImage(path, w, h, 3, std::vector<float>(std::size_t(w) * h * 3, 1.0f), OIIO::TypeDesc::HALF, 8);
    std::string bytes;
    {
        std::ifstream in(path, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    // The "tiles" attribute: name, "tiledesc", size 9, then x size, y size (uint32 LE), mode.
    const std::size_t type = bytes.find(std::string("tiledesc\0", 9));
    ASSERT_NE(type, std::string::npos);
    const std::size_t ySize = type + 9 + 4 + 4;
    const std::uint32_t tall = 1u << 24;
    std::memcpy(&bytes[ySize], &tall, sizeof tall);
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
    const std::string msg = errorOf([&] { loadEnvironment(path); }, "tall-tiles.exr");
    EXPECT_NE(msg.find("tiles of 8x16777216"), std::string::npos) << msg;
}

