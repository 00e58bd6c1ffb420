#pragma once
// The malformed environment images of issue #6, generated into a folder so that the CLI
// tests and the GUI-session tests refuse exactly the same files. Each entry names the file
// and a phrase the one-line error must contain, so a test fails if the loader reports the
// wrong problem (a truncated file must not be called a bad aspect ratio, and so on).
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <zlib.h>

namespace iblab::testing {

struct MalformedImage {
    std::string fileName;
    std::string problem; // a phrase of the expected error, after the file name
};

namespace malformed_detail {

inline void writeFloatImage(const std::filesystem::path& path, int width, int height)
{
    auto out = OIIO::ImageOutput::create(path.string());
    if (!out) throw std::runtime_error("no OpenImageIO writer for " + path.string());
    OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::FLOAT);
    std::vector<float> pixels(std::size_t(width) * std::size_t(height) * 3);
    for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = 0.25f + float(i % 7) * 0.5f; // not constant: compressors keep data
    if (!out->open(path.string(), spec) || !out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) || !out->close())
        throw std::runtime_error("cannot write " + path.string() + ": " + out->geterror());
}

inline std::vector<char> readBytes(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

inline void writeBytes(const std::filesystem::path& path, const std::vector<char>& bytes)
{
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

// A valid image of the format, then only its first part: the header survives, the pixels do not.
inline void writeTruncated(const std::filesystem::path& path, int width, int height, double keptFraction)
{
    writeFloatImage(path, width, height);
    std::vector<char> bytes = readBytes(path);
    bytes.resize(std::size_t(double(bytes.size()) * keptFraction));
    writeBytes(path, bytes);
}

inline void appendBigEndian32(std::string& out, std::uint32_t value)
{
    for (int shift = 24; shift >= 0; shift -= 8) out += char((value >> shift) & 0xffu);
}

// A PNG signature and an IHDR chunk (8-bit RGB) with its CRC.
inline std::string pngStart(std::uint32_t width, std::uint32_t height)
{
    std::string body = "IHDR";
    appendBigEndian32(body, width);
    appendBigEndian32(body, height);
    body += std::string("\x08\x02\x00\x00\x00", 5); // 8-bit RGB, deflate, no filter, no interlace
    std::string png = "\x89PNG\r\n\x1a\n";
    appendBigEndian32(png, 13);
    png += body;
    appendBigEndian32(png, std::uint32_t(crc32(0, reinterpret_cast<const Bytef*>(body.data()), uInt(body.size()))));
    return png;
}

// A PNG whose IHDR says 0 x 0: well-formed chunks with correct CRCs, so only the size is wrong.
inline void writeZeroSizePng(const std::filesystem::path& path)
{
    std::ofstream(path, std::ios::binary) << pngStart(0, 0) + std::string("\0\0\0\0IEND\xae\x42\x60\x82", 12);
}

} // namespace malformed_detail

// A 16x8 PNG whose text chunk claims 1970828288 bytes and holds 7 (what the fuzzer found:
// libpng allocates and zeroes a chunk at its claimed length before reading it).
inline std::string pngClaimingAHugeTextChunk()
{
    std::string png = malformed_detail::pngStart(16, 8);
    malformed_detail::appendBigEndian32(png, 0x75787400u);
    return png + "tEXtComment";
}

// Writes every malformed image into folder and lists them with the problem to expect.
inline std::vector<MalformedImage> writeMalformedImages(const std::filesystem::path& folder)
{
    using namespace malformed_detail;
    writeTruncated(folder / "truncated.exr", 64, 32, 0.5);
    writeTruncated(folder / "truncated.hdr", 64, 32, 0.5);
    writeTruncated(folder / "truncated.png", 64, 32, 0.5);
    // An EXR whose magic number is wrong: the rest is a valid file.
    writeFloatImage(folder / "bad-magic.exr", 64, 32);
    std::vector<char> bytes = readBytes(folder / "bad-magic.exr");
    bytes[0] = 'X';
    bytes[1] = 'X';
    writeBytes(folder / "bad-magic.exr", bytes);
    std::ofstream(folder / "zero.hdr", std::ios::binary) << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 0 +X 0\n";
    writeZeroSizePng(folder / "zero.png");
    std::ofstream(folder / "text-chunk.png", std::ios::binary) << pngClaimingAHugeTextChunk();
    writeFloatImage(folder / "one-texel.exr", 1, 1);
    writeFloatImage(folder / "wide.exr", 48, 16);
    std::ofstream(folder / "huge.hdr", std::ios::binary) << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 32768 +X 65536\n";
    std::ofstream(folder / "empty.exr", std::ios::binary);
    return {
        {"truncated.exr", "cannot read pixels"},
        {"truncated.hdr", "cannot read pixels"},
        {"truncated.png", "cannot read pixels"},
        {"bad-magic.exr", "cannot read as an image"},
        {"zero.hdr", "no pixels (0x0)"},
        {"zero.png", "cannot read as an image"},
        {"text-chunk.png", "corrupt PNG: chunk 'tEXt' claims 1970828288 bytes, more than the 7 left"},
        {"one-texel.exr", "too small for an environment: 1x1"},
        {"wide.exr", "3:1, expected 2:1"},
        {"huge.hdr", "65536x32768 is 2147483648 texels, more than the limit"},
        {"empty.exr", "empty file"},
    };
}

} // namespace iblab::testing
