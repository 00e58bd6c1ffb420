// The direct OpenEXR and Radiance codec (image_codec_direct.hpp) against OpenImageIO's
// module on the same files: the same header and bit-identical pixels, the files it must
// leave to OpenImageIO, and a bake's formats read and written without loading the module.
// This executable does not link OpenImageIO: its test files are written through the module.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <variant>
#include <vector>

#include <malloc.h>

#include "io/environment.hpp"
#include "io/error.hpp"
#include "io/image_codec.hpp"
#include "io/image_codec_direct.hpp"
#include "io/image_writer.hpp"
#include "temp_dir.hpp"

namespace fs = std::filesystem;
using namespace iblab;
using iblab::testing::TempDir;

namespace {

const fs::path kSourceDir = IBLAB_SOURCE_DIR;

struct Decoded {
    ImageHeader header;
    std::vector<float> pixels;
};

// The header and every texel's first `channels` channels as float, read as the
// environment loader reads them (by bands of rows: whole tile rows for tiled files).
Decoded decode(ImageReader& reader, int channels)
{
    Decoded d{reader.header(), {}};
    const ImageHeader& h = d.header;
    d.pixels.resize(std::size_t(h.width) * std::size_t(h.height) * std::size_t(channels));
    const int band = h.tileHeight > 0 ? h.tileHeight : 16;
    for (int y0 = 0; y0 < h.height; y0 += band) {
        const int y1 = std::min(h.height, y0 + band);
        EXPECT_TRUE(reader.readRows(h.y + y0, h.y + y1, channels, PixelType::Float,
                                    &d.pixels[std::size_t(y0) * std::size_t(h.width) * std::size_t(channels)]))
            << reader.takeError();
    }
    EXPECT_FALSE(reader.hasError());
    return d;
}

// The direct reader must take the file, and decode exactly what OpenImageIO decodes.
void expectSameAsOpenImageIo(const std::string& path, int channels)
{
    SCOPED_TRACE(path);
    std::unique_ptr<ImageReader> direct =
        sniffImageFile(path) == ImageFileKind::OpenExr ? openExrDirect(path) : openHdrDirect(path);
    ASSERT_TRUE(direct) << "left to OpenImageIO";
    std::string error;
    std::unique_ptr<ImageReader> oiio = openImageIoCodec().openFile(path, error);
    ASSERT_TRUE(oiio) << error;
    const Decoded a = decode(*direct, channels);
    const Decoded b = decode(*oiio, channels);
    EXPECT_EQ(a.header.width, b.header.width);
    EXPECT_EQ(a.header.height, b.header.height);
    EXPECT_EQ(a.header.x, b.header.x);
    EXPECT_EQ(a.header.y, b.header.y);
    EXPECT_EQ(a.header.channels, b.header.channels);
    EXPECT_EQ(a.header.tileWidth, b.header.tileWidth);
    EXPECT_EQ(a.header.tileHeight, b.header.tileHeight);
    EXPECT_EQ(a.header.storedType, b.header.storedType);
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    EXPECT_EQ(std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)), 0) << "pixels differ";
}

// Writes through the module, so that the file is OpenImageIO's own.
void writeWithOpenImageIo(const std::string& path, const char* format, int w, int h, int channels, PixelType stored,
                          const std::vector<float>& pixels, std::vector<std::pair<std::string, std::variant<std::string, int>>> attributes = {})
{
    ImageWrite image{.format = format,
                     .width = w,
                     .height = h,
                     .channels = channels,
                     .storedType = stored,
                     .dataType = PixelType::Float,
                     .firstRow = pixels.data(),
                     .rowStride = std::ptrdiff_t(w) * channels * std::ptrdiff_t(sizeof(float)),
                     .attributes = std::move(attributes)};
    if (channels == 1) image.channelNames = {"Y"};
    openImageIoCodec().writeFile(path, path, image);
}

std::vector<float> ramp(std::size_t count, float scale)
{
    std::vector<float> v(count);
    for (std::size_t i = 0; i < count; ++i)
        v[i] = 0.001f + scale * float((i * 7919) % 1009) / 97.0f;
    return v;
}

// The files of tests/fuzz/corpus/environment/ are the fuzzer's inputs: the first byte picks
// the extension, the rest is the file.
std::string corpusFile(const TempDir& dir, const std::string& name)
{
    std::ifstream in(kSourceDir / "tests" / "fuzz" / "corpus" / "environment" / name, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_GT(bytes.size(), 1u) << name;
    const std::string path = dir.file(name);
    std::ofstream(path, std::ios::binary).write(bytes.data() + 1, std::streamsize(bytes.size() - 1));
    return path;
}

} // namespace

TEST(DirectCodec, BundledMapsDecodeAsOpenImageIoDecodesThem)
{
    for (const auto& entry : fs::directory_iterator(kSourceDir / "assets" / "environments"))
        if (entry.path().extension() == ".exr") expectSameAsOpenImageIo(entry.path().string(), 3);
}

TEST(DirectCodec, FuzzSeedsOfEveryCompressionDecodeAsOpenImageIoDecodesThem)
{
    TempDir dir;
    for (const char* name : {"valid-exr", "valid-exr-b44", "valid-exr-dwab", "valid-exr-piz", "valid-exr-rle", "valid-exr-tiled",
                             "valid-exr-zip", "valid-hdr"})
        expectSameAsOpenImageIo(corpusFile(dir, name), 3);
}

TEST(DirectCodec, HalfTiledGreyAndRadianceFilesDecodeAsOpenImageIoDecodesThem)
{
    TempDir dir;
    const int w = 96, h = 48;
    const std::string half = dir.file("half-rgba.exr");
    writeWithOpenImageIo(half, "openexr", w, h, 4, PixelType::Half, ramp(std::size_t(w) * h * 4, 3.0f), {{"compression", "piz"}});
    expectSameAsOpenImageIo(half, 3);
    const std::string grey = dir.file("grey.exr");
    writeWithOpenImageIo(grey, "openexr", w, h, 1, PixelType::Float, ramp(std::size_t(w) * h, 5.0f));
    expectSameAsOpenImageIo(grey, 1); // the environment loader reads grey as one channel
    const std::string hdr = dir.file("map.hdr");
    writeWithOpenImageIo(hdr, "hdr", w, h, 3, PixelType::Float, ramp(std::size_t(w) * h * 3, 40.0f));
    expectSameAsOpenImageIo(hdr, 3);
}

TEST(DirectCodec, WhatItCannotReadExactlyIsLeftToOpenImageIo)
{
    TempDir dir;
    const std::string path = dir.file("gamma.hdr");
    std::ofstream(path, std::ios::binary) << "#?RADIANCE\nGAMMA=2.2\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 8\n" << std::string(128, '\x80');
    EXPECT_EQ(sniffImageFile(path), ImageFileKind::RadianceHdr);
    EXPECT_FALSE(openHdrDirect(path)) << "GAMMA is OpenImageIO's to interpret";
    const std::string flipped = dir.file("flipped.hdr");
    std::ofstream(flipped, std::ios::binary) << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n+Y 4 +X 8\n" << std::string(128, '\x80');
    EXPECT_FALSE(openHdrDirect(flipped));
    const std::string named = dir.file("layers.exr");
    ImageWrite image{.format = "openexr", .width = 8, .height = 4, .channels = 2, .storedType = PixelType::Float};
    const std::vector<float> pixels(64, 1.0f);
    image.firstRow = pixels.data();
    image.rowStride = 8 * 2 * sizeof(float);
    image.dataType = PixelType::Float;
    image.channelNames = {"diffuse.R", "diffuse.G"};
    openImageIoCodec().writeFile(named, named, image);
    EXPECT_EQ(sniffImageFile(named), ImageFileKind::OpenExr);
    EXPECT_FALSE(openExrDirect(named));
    EXPECT_EQ(sniffImageFile(dir.file("missing.exr")), ImageFileKind::Other);
}

TEST(DirectCodec, TheDecoderOpensAtTheFirstReadNotWithTheHeader)
{
    // A 16x8 scanline EXR whose header claims a data window 2^24 texels wide. OpenEXR's
    // InputFile allocates its block buffers for that width as it opens (a gigabyte, which
    // AddressSanitizer then spends tens of seconds touching: the fuzzer's timeout), before
    // the loader could refuse the file from its header. The reader must open without them.
    TempDir dir;
    const int w = 16, h = 8;
    const std::string path = dir.file("wide.exr");
    writeWithOpenImageIo(path, "openexr", w, h, 3, PixelType::Half, ramp(std::size_t(w) * h * 3, 1.0f));
    std::string bytes;
    {
        std::ifstream in(path, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    // "dataWindow", "box2i", size 16, then min x, min y, max x, max y (int32 LE). The rows
    // stay 8, so the file's table of blocks still matches its header.
    const std::size_t type = bytes.find(std::string("dataWindow\0box2i\0", 17));
    ASSERT_NE(type, std::string::npos);
    const std::int32_t maxX = (1 << 24) - 1;
    std::memcpy(&bytes[type + 17 + 4 + 8], &maxX, sizeof maxX);
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;

    // glibc serves allocations this large with mmap, and counts them in hblkhd (under
    // AddressSanitizer, which allocates itself, it counts none; the fuzzers' corpus replay
    // under scripts/fuzz.sh covers that build).
    const std::size_t mappedBefore = mallinfo2().hblkhd;
    const std::unique_ptr<ImageReader> reader = openExrDirect(path);
    ASSERT_TRUE(reader);
    EXPECT_EQ(reader->header().width, 1 << 24);
    EXPECT_EQ(reader->header().height, h);
    EXPECT_LT(mallinfo2().hblkhd, mappedBefore + (std::size_t(1) << 20)) << "the reader allocated its decoder's buffers";
    try {
        loadEnvironment(path);
        FAIL() << "loaded";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("not equirectangular: 16777216x8"), std::string::npos) << e.what();
    }
}

TEST(DirectCodec, AFileReplacedAfterItsHeaderWasReadIsAnErrorNotAnOverrun)
{
    // The decoder opens the file again at the first read (above): a larger image written over
    // it in between must not be decoded into a buffer sized for the header that was read.
    TempDir dir;
    const std::string path = dir.file("map.exr");
    writeWithOpenImageIo(path, "openexr", 16, 8, 3, PixelType::Float, ramp(16 * 8 * 3, 1.0f));
    const std::unique_ptr<ImageReader> reader = openExrDirect(path);
    ASSERT_TRUE(reader);
    writeWithOpenImageIo(path, "openexr", 64, 32, 3, PixelType::Float, ramp(64 * 32 * 3, 1.0f));
    std::vector<float> rows(16 * 8 * 3);
    EXPECT_FALSE(reader->readRows(0, 8, 3, PixelType::Float, rows.data()));
    EXPECT_NE(reader->takeError().find("the file changed"), std::string::npos);
}

TEST(DirectCodec, ChosenByContentNotByName)
{
    TempDir dir;
    const std::string exr = dir.file("really-an-exr.hdr");
    writeExr(exr, 64, 32, 3, ramp(64 * 32 * 3, 2.0f));
    EXPECT_EQ(sniffImageFile(exr), ImageFileKind::OpenExr);
    EXPECT_NO_THROW(loadEnvironment(exr));
}

TEST(DirectCodec, TruncatedRadianceFileIsAnErrorNamingIt)
{
    TempDir dir;
    const std::string good = dir.file("good.hdr");
    writeWithOpenImageIo(good, "hdr", 256, 128, 3, PixelType::Float, ramp(256 * 128 * 3, 30.0f));
    std::ifstream in(good, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (std::size_t keep : {bytes.size() / 2, bytes.size() - 1}) {
        const std::string cut = dir.file("cut-" + std::to_string(keep) + ".hdr");
        std::ofstream(cut, std::ios::binary).write(bytes.data(), std::streamsize(keep));
        ASSERT_TRUE(openHdrDirect(cut)) << "the header is intact: the direct reader takes it";
        try {
            loadEnvironment(cut);
            ADD_FAILURE() << "a file cut to " << keep << " of " << bytes.size() << " bytes loaded";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(cut), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
        }
    }
}

TEST(DirectCodec, RunOfLengthZeroIsAnErrorNotAHang)
{
    // stb_image's decoder loops forever on this (a run-length scanline whose first code is
    // a dump of 0 bytes); the fuzz corpus's truncated-hdr ends the same way.
    TempDir dir;
    const std::string path = dir.file("zero-run.hdr");
    std::string bytes = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 8\n";
    bytes += std::string("\x02\x02\x00\x08", 4) + std::string(64, '\0');
    std::ofstream(path, std::ios::binary) << bytes;
    ASSERT_TRUE(openHdrDirect(path));
    try {
        loadEnvironment(path);
        ADD_FAILURE() << "loaded";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("bad run-length data"), std::string::npos) << e.what();
    }
}

// What OpenImageIO reads from `path`, as float.
std::vector<float> readWithOpenImageIo(const std::string& path, int channels)
{
    std::string error;
    std::unique_ptr<ImageReader> oiio = openImageIoCodec().openFile(path, error);
    EXPECT_TRUE(oiio) << error;
    if (!oiio) return {};
    std::vector<float> read(std::size_t(oiio->header().width) * std::size_t(oiio->header().height) * std::size_t(channels));
    EXPECT_TRUE(oiio->readImage(channels, PixelType::Float, read.data())) << oiio->takeError();
    return read;
}

TEST(DirectCodec, WritesWhatOpenImageIoWrites)
{
    TempDir dir;
    const int w = 40, h = 20;
    const std::vector<float> pixels = ramp(std::size_t(w) * h * 4, 9.0f);
    for (ExrPixelType type : {ExrPixelType::Float, ExrPixelType::Half}) {
        const bool isHalf = type == ExrPixelType::Half;
        SCOPED_TRACE(isHalf ? "half" : "float");
        const std::string path = dir.file(isHalf ? "half.exr" : "float.exr");
        writeExr(path, w, h, 4, pixels, {.bottomUp = true, .settingsJson = R"({"a": 1})", .exrPixelType = type, .exrCompression = "rle"});
        // The same rows, top-down, written by OpenImageIO: the direct writer must round to
        // half exactly as it does.
        std::vector<float> topDown(pixels.size());
        for (int y = 0; y < h; ++y)
            std::memcpy(&topDown[std::size_t(y) * w * 4], &pixels[std::size_t(h - 1 - y) * w * 4], std::size_t(w) * 4 * sizeof(float));
        const std::string reference = dir.file(isHalf ? "half-oiio.exr" : "float-oiio.exr");
        writeWithOpenImageIo(reference, "openexr", w, h, 4, isHalf ? PixelType::Half : PixelType::Float, topDown);
        const std::vector<float> direct = readWithOpenImageIo(path, 4);
        const std::vector<float> oiio = readWithOpenImageIo(reference, 4);
        ASSERT_EQ(direct.size(), oiio.size());
        EXPECT_EQ(std::memcmp(direct.data(), oiio.data(), direct.size() * sizeof(float)), 0) << "pixels differ";
        if (!isHalf) {
            EXPECT_EQ(std::memcmp(direct.data(), topDown.data(), direct.size() * sizeof(float)), 0) << "float is lossless";
        }
    }
}

TEST(DirectCodec, BakeFormatsNeverLoadOpenImageIo)
{
    // Each test runs in a process of its own (gtest_discover_tests), so the module is
    // loaded here only if this test loads it.
    TempDir dir;
    const Environment env = loadEnvironment((kSourceDir / "assets" / "environments" / "courtyard.exr").string());
    const std::string path = dir.file("cube.exr");
    writeExr(path, env.image, {.exrPixelType = ExrPixelType::Half, .exrCompression = "rle"});
    EXPECT_NO_THROW(loadEnvironment(path));
    std::ifstream maps("/proc/self/maps");
    const std::string text((std::istreambuf_iterator<char>(maps)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text.find("libOpenImageIO"), std::string::npos);
    EXPECT_EQ(text.find("libiblab_oiio"), std::string::npos);
}

TEST(DirectCodec, HalfPixelsAreWrittenAsGivenInTilesAsOpenImageIoWritesThem)
{
    // What the bake cache writes: an RGBA half read-back stored as RGB, a tile per cube face.
    TempDir dir;
    const int w = 8, h = 48;
    std::vector<std::uint16_t> rgba(std::size_t(w) * h * 4);
    for (std::size_t i = 0; i < rgba.size(); ++i)
        rgba[i] = std::uint16_t((i * 7919) % 0x7bff); // positive finite halves, each value its own
    const std::string path = dir.file("direct.exr");
    writeExr(path, ExrPixels{.width = w, .height = h, .channels = 3, .pixelValues = 4, .type = ExrPixelType::Half, .data = rgba.data()},
             {.exrCompression = "none", .exrTileSize = w});
    ImageWrite image{.format = "openexr",
                     .width = w,
                     .height = h,
                     .channels = 3,
                     .storedType = PixelType::Half,
                     .dataType = PixelType::Half,
                     .firstRow = rgba.data(),
                     .rowStride = std::ptrdiff_t(w) * 4 * 2,
                     .pixelStride = 4 * 2,
                     .tileSize = w,
                     .attributes = {{"compression", "none"}}};
    const std::string reference = dir.file("oiio.exr");
    openImageIoCodec().writeFile(reference, reference, image);

    const std::vector<float> direct = readWithOpenImageIo(path, 3);
    const std::vector<float> oiio = readWithOpenImageIo(reference, 3);
    ASSERT_EQ(direct.size(), std::size_t(w) * h * 3);
    ASSERT_EQ(direct.size(), oiio.size());
    EXPECT_EQ(std::memcmp(direct.data(), oiio.data(), direct.size() * sizeof(float)), 0) << "pixels differ";
    EXPECT_NE(direct[3], direct[0]) << "the pixels differ from one another, so a wrong stride would show";
    expectSameAsOpenImageIo(path, 3);
    const std::unique_ptr<ImageReader> in = openExrDirect(path);
    ASSERT_TRUE(in);
    EXPECT_EQ(in->header().tileWidth, w);
    EXPECT_EQ(in->header().tileHeight, w);
    EXPECT_EQ(in->header().storedType, PixelType::Half);
}

TEST(DirectCodec, HalfPixelsAreReadBackAsStoredIntoTheirStride)
{
    // What the bake cache reads: the file above read back into an RGBA half layout, the
    // alpha values left as the caller set them, every RGB value bit for bit.
    TempDir dir;
    const int w = 8, h = 48;
    std::vector<std::uint16_t> rgba(std::size_t(w) * h * 4);
    for (std::size_t i = 0; i < rgba.size(); ++i)
        rgba[i] = std::uint16_t((i * 7919) % 0x7bff);
    const std::string path = dir.file("cube.exr");
    writeExr(path, ExrPixels{.width = w, .height = h, .channels = 3, .pixelValues = 4, .type = ExrPixelType::Half, .data = rgba.data()},
             {.exrCompression = "none", .exrTileSize = w});
    std::vector<std::uint16_t> back(rgba.size(), 0x3C00);
    readExrDirect(path, {.width = w, .height = h, .channels = 3, .pixelValues = 4, .type = ExrPixelType::Half, .data = back.data()});
    for (std::size_t i = 0; i < back.size(); ++i)
        ASSERT_EQ(back[i], i % 4 == 3 ? 0x3C00 : rgba[i]) << "value " << i;

    // As floats (a float texture's layout): OpenEXR converts each half exactly.
    std::vector<float> floats(rgba.size(), -1.0f);
    readExrDirect(path, {.width = w, .height = h, .channels = 3, .pixelValues = 4, .type = ExrPixelType::Float, .data = floats.data()});
    const std::vector<float> oiio = readWithOpenImageIo(path, 3);
    for (std::size_t p = 0; p < std::size_t(w) * h; ++p) {
        for (std::size_t c = 0; c < 3; ++c) ASSERT_EQ(floats[p * 4 + c], oiio[p * 3 + c]) << "pixel " << p;
        ASSERT_EQ(floats[p * 4 + 3], -1.0f);
    }

    // Another size, a truncated file, not an EXR: one line naming the file.
    const auto expectRefused = [&](const std::string& file, int width, int height, const std::string& problem) {
        try {
            readExrDirect(file, {.width = width, .height = height, .channels = 3, .pixelValues = 4, .type = ExrPixelType::Half, .data = back.data()});
            FAIL() << file << " was read";
        } catch (const Error& e) {
            const std::string what = e.what();
            EXPECT_EQ(what.rfind(file + ": ", 0), 0u) << what;
            EXPECT_NE(what.find(problem), std::string::npos) << what;
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        }
    };
    expectRefused(path, 4, 24, "is 8x48, expected 4x24");
    fs::resize_file(path, fs::file_size(path) / 2);
    expectRefused(path, w, h, "");
    const std::string text = dir.file("text.exr");
    std::ofstream(text) << "not an image";
    expectRefused(text, w, h, "");
}
