// Image writing and atomic replacement. Files are read back with OpenImageIO and
// nlohmann_json directly.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <OpenImageIO/imageio.h>
#include <nlohmann/json.hpp>

#include "io/atomic_file.hpp"
#include "io/error.hpp"
#include "io/image_writer.hpp"
#include "temp_dir.hpp"

namespace fs = std::filesystem;
using namespace iblab;

namespace {

using iblab::testing::TempDir;

struct ReadBack {
    OIIO::ImageSpec spec;
    std::vector<float> pixels; // as float, file order (row 0 = first scanline)
};

ReadBack readBack(const std::string& path)
{
    ReadBack r;
    // Ask for the stored values: by default OpenImageIO premultiplies PNG colour by alpha.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(path, &config);
    EXPECT_TRUE(in) << OIIO::geterror();
    if (!in)
        return r;
    r.spec = in->spec();
    r.pixels.resize(std::size_t(r.spec.width) * r.spec.height * r.spec.nchannels);
    EXPECT_TRUE(in->read_image(0, 0, 0, r.spec.nchannels, OIIO::TypeDesc::FLOAT, r.pixels.data()));
    return r;
}

std::string slurp(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

const char* kSettings = R"({"exposure": -1.5, "environment": "builtin:sun?elevation=30", "samples": [64, 256]})";

void expectSettingsAttached(const std::string& path, const ReadBack& r)
{
    const nlohmann::json expected = nlohmann::json::parse(kSettings);
    EXPECT_EQ(nlohmann::json::parse(r.spec.get_string_attribute("iblab:settings", "null")), expected);
    EXPECT_EQ(nlohmann::json::parse(r.spec.get_string_attribute("ImageDescription", "null")), expected);
    ASSERT_TRUE(fs::exists(settingsSidecarPath(path)));
    EXPECT_EQ(settingsSidecarPath(path), path + ".json");
    EXPECT_EQ(nlohmann::json::parse(slurp(path + ".json")), expected);
}

} // namespace

TEST(ImageWriter, PngBottomUpRowsAreFlippedAndSettingsAttached)
{
    TempDir dir;
    const int w = 5, h = 3, ch = 3;
    // Pixel value encodes (row, column, channel) of the BUFFER: row 0 is the bottom row.
    std::vector<std::uint8_t> px(std::size_t(w) * h * ch);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < ch; ++c)
                px[(std::size_t(y) * w + x) * ch + c] = std::uint8_t(80 * y + 10 * x + c);
    const std::string path = dir.file("shot.png");
    ImageWriteOptions options;
    options.bottomUp = true;
    options.settingsJson = kSettings;
    writePng8(path, w, h, ch, px, options);

    const ReadBack r = readBack(path);
    ASSERT_EQ(r.spec.width, w);
    ASSERT_EQ(r.spec.height, h);
    ASSERT_EQ(r.spec.nchannels, ch);
    for (int fileRow = 0; fileRow < h; ++fileRow)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < ch; ++c)
                ASSERT_EQ(std::lround(r.pixels[(std::size_t(fileRow) * w + x) * ch + c] * 255.0f),
                          80 * (h - 1 - fileRow) + 10 * x + c)
                    << fileRow << "," << x << "," << c;
    expectSettingsAttached(path, r);
    EXPECT_EQ(dir.entries(), (std::vector<std::string>{"shot.png", "shot.png.json"}));
}

TEST(ImageWriter, PngRgbaTopDownKeepsOrderAndAlpha)
{
    TempDir dir;
    const int w = 4, h = 2, ch = 4;
    std::vector<std::uint8_t> px(std::size_t(w) * h * ch);
    for (std::size_t i = 0; i < px.size(); ++i)
        px[i] = std::uint8_t(i * 7);
    const std::string path = dir.file("rgba.png");
    writePng8(path, w, h, ch, px);
    const ReadBack r = readBack(path);
    ASSERT_EQ(r.spec.nchannels, 4);
    for (std::size_t i = 0; i < px.size(); ++i)
        ASSERT_EQ(std::lround(r.pixels[i] * 255.0f), px[i]) << i;
    EXPECT_FALSE(fs::exists(path + ".json")); // no settings, no sidecar
}

TEST(ImageWriter, ExrFromImageIsExactAndCarriesSettings)
{
    TempDir dir;
    ImageRGB32F img(8, 4);
    for (std::size_t i = 0; i < img.texels.size(); ++i)
        img.texels[i] = float(i) * 0.37f + (i == 5 ? 31337.25f : 0.0f);
    const std::string path = dir.file("env.exr");
    ImageWriteOptions options;
    options.settingsJson = kSettings;
    writeExr(path, img, options);
    const ReadBack r = readBack(path);
    ASSERT_EQ(r.spec.width, 8);
    ASSERT_EQ(r.spec.nchannels, 3);
    EXPECT_EQ(r.spec.format, OIIO::TypeDesc::FLOAT);
    EXPECT_EQ(r.pixels, img.texels); // float EXR, lossless compression: bit-exact
    expectSettingsAttached(path, r);
}

TEST(ImageWriter, ExrHalfRgbaBottomUp)
{
    TempDir dir;
    const int w = 3, h = 4, ch = 4;
    std::vector<float> px(std::size_t(w) * h * ch);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < ch; ++c)
                px[(std::size_t(y) * w + x) * ch + c] = float(y * 100 + x * 10 + c); // exact in half
    const std::string path = dir.file("frame.exr");
    ImageWriteOptions options;
    options.bottomUp = true;
    options.exrPixelType = ExrPixelType::Half;
    writeExr(path, w, h, ch, px, options);
    const ReadBack r = readBack(path);
    EXPECT_EQ(r.spec.format, OIIO::TypeDesc::HALF);
    ASSERT_EQ(r.spec.nchannels, 4);
    for (int fileRow = 0; fileRow < h; ++fileRow)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < ch; ++c)
                ASSERT_EQ(r.pixels[(std::size_t(fileRow) * w + x) * ch + c], float((h - 1 - fileRow) * 100 + x * 10 + c));
}

TEST(ImageWriter, RejectsBadInputWithoutTouchingTheDisk)
{
    TempDir dir;
    const std::string path = dir.file("bad.png");
    std::vector<std::uint8_t> px(4 * 2 * 3, 9);
    ImageWriteOptions options;
    options.settingsJson = "{not json";
    EXPECT_THROW(writePng8(path, 4, 2, 3, px, options), Error);
    EXPECT_THROW(writePng8(path, 4, 3, 3, px), Error); // buffer too small
    EXPECT_THROW(writePng8(path, 4, 2, 5, px), Error); // channel count
    EXPECT_THROW(writeExr(path + ".exr", 2, 2, 2, std::vector<float>(8)), Error);
    EXPECT_TRUE(dir.entries().empty());
}

TEST(ImageWriter, MissingDirectoryThrowsNamingThePath)
{
    TempDir dir;
    const std::string path = dir.file("no/such/dir/shot.png");
    std::vector<std::uint8_t> px(2 * 1 * 3, 0);
    try {
        writePng8(path, 2, 1, 3, px);
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(path), std::string::npos) << what;
        EXPECT_NE(what.find("does not exist"), std::string::npos) << what;
    }
    EXPECT_THROW(writeExr(dir.file("missing/x.exr"), ImageRGB32F(2, 1)), Error);
    EXPECT_TRUE(dir.entries().empty());
}

TEST(ImageWriter, OverwritesAnExistingImage)
{
    TempDir dir;
    const std::string path = dir.file("a.png");
    writePng8(path, 1, 1, 3, std::vector<std::uint8_t>{1, 2, 3});
    writePng8(path, 2, 1, 3, std::vector<std::uint8_t>{4, 5, 6, 7, 8, 9});
    const ReadBack r = readBack(path);
    EXPECT_EQ(r.spec.width, 2);
    EXPECT_EQ(std::lround(r.pixels[5] * 255.0f), 9);
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"a.png"});
}

TEST(AtomicFile, TextWriteReplacesContents)
{
    TempDir dir;
    const std::string path = dir.file("preset.json");
    writeTextFileAtomic(path, "first");
    writeTextFileAtomic(path, std::string("second\0with nul", 15));
    EXPECT_EQ(slurp(path), std::string("second\0with nul", 15));
    EXPECT_EQ(readTextFile(path), std::string("second\0with nul", 15));
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"preset.json"});
    EXPECT_THROW(readTextFile(dir.file("absent.json")), Error);
    // A directory is said to be one (it read as an empty text).
    std::filesystem::create_directories(dir.file("folder.json"));
    try {
        readTextFile(dir.file("folder.json"));
        ADD_FAILURE() << "a directory read as a text";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("folder.json: is a directory"), std::string::npos) << e.what();
    }
}

TEST(AtomicFile, UnflushedWritesStillReplaceWholeFiles)
{
    // Durability::NoFlush (the bake cache's) skips only the fsyncs: the file is still
    // written to a temporary and renamed over the target, images and sidecars alike.
    TempDir dir;
    const std::string path = dir.file("entry.json");
    writeTextFileAtomic(path, "first", Durability::NoFlush);
    writeTextFileAtomic(path, "second", Durability::NoFlush);
    EXPECT_EQ(slurp(path), "second");
    const std::string image = dir.file("cube.exr");
    const std::vector<float> pixels(8 * 4 * 3, 0.5f);
    writeExr(image, 8, 4, 3, pixels, {.settingsJson = "{}", .durability = Durability::NoFlush});
    EXPECT_EQ(readBack(image).pixels, pixels);
    EXPECT_EQ(dir.entries(), (std::vector<std::string>{"cube.exr", "cube.exr.json", "entry.json"}));
}

TEST(AtomicFile, FailingWriterLeavesTheOldFileIntact)
{
    // Failure injected in the middle of writing: the temporary file already holds a
    // partial payload when the writer throws.
    TempDir dir;
    const std::string path = dir.file("cache.bin");
    writeTextFileAtomic(path, "old contents");
    std::string seenTemp;
    EXPECT_THROW(writeFileAtomic(path,
                                 [&](const std::string& temp) {
                                     seenTemp = temp;
                                     std::ofstream(temp, std::ios::binary) << "half-writ";
                                     throw Error(path, "disk full (simulated)");
                                 }),
                 Error);
    EXPECT_EQ(fs::path(seenTemp).parent_path(), dir.path); // same directory, so rename is atomic
    EXPECT_EQ(slurp(path), "old contents");
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"cache.bin"}); // temp removed
}

TEST(AtomicFile, FailingRenameLeavesTargetAndNoTemp)
{
    // A non-empty directory at the target: rename(2) fails (EISDIR / ENOTEMPTY) even for
    // root, after the temporary file was written in full.
    TempDir dir;
    const std::string path = dir.file("occupied");
    fs::create_directories(path);
    writeTextFileAtomic((fs::path(path) / "inside.txt").string(), "keep");
    try {
        writeTextFileAtomic(path, "new");
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
    EXPECT_TRUE(fs::is_directory(path));
    EXPECT_EQ(slurp((fs::path(path) / "inside.txt").string()), "keep");
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"occupied"});
}

TEST(AtomicFile, FailedImageWriteKeepsThePreviousImage)
{
    // The image writer's failure path after the pixels are encoded: the final rename
    // cannot replace what sits at the target (a non-empty directory), which must survive
    // untouched, with no temporary file left beside it.
    TempDir dir;
    const std::string path = dir.file("shot.png");
    fs::create_directories(path); // something that is not a file sits at the target
    writeTextFileAtomic((fs::path(path) / "keep").string(), "x");
    EXPECT_THROW(writePng8(path, 1, 1, 3, std::vector<std::uint8_t>{1, 2, 3}), Error);
    EXPECT_EQ(slurp((fs::path(path) / "keep").string()), "x");
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"shot.png"});
}
