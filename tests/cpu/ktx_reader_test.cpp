// The KTX 1.1 / 2.0 cube readers (io/ktx_cube.hpp) on hand-made files (tests/support/
// ktx_test_files.hpp), each kind of bad input, and cmgen's own output (skipped with a message
// where Debian's libfilament-tools is not installed).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>

#include "ibl/conventions.hpp"
#include "io/environment.hpp"
#include "io/error.hpp"
#include "io/imported_bake.hpp"
#include "io/ktx_cube.hpp"
#include "ktx_test_files.hpp"

namespace fs = std::filesystem;
using namespace iblab;
using iblab::test::makeKtx1Cube;
using iblab::test::makeKtx2Cube;
using iblab::test::testTexel;

namespace {

std::span<const std::byte> asBytes(const std::vector<std::uint8_t>& v) { return std::as_bytes(std::span(v)); }

void expectTexels(const KtxCube& cube, int levels)
{
    ASSERT_EQ(int(cube.levels.size()), levels);
    for (int level = 0; level < levels; ++level) {
        const int s = cube.levelSize(level);
        ASSERT_EQ(cube.levels[std::size_t(level)].width, s);
        for (int face = 0; face < 6; ++face)
            for (int row = 0; row < s; ++row)
                for (int x = 0; x < s; ++x)
                    for (int c = 0; c < 3; ++c)
                        ASSERT_EQ(cube.levels[std::size_t(level)].at(x, face * s + row)[c], testTexel(level, face, x, row, c))
                            << "level " << level << " face " << face << " x " << x << " row " << row;
    }
}

// The message of parsing `bytes` as the file "bad.ktx".
std::string errorOf(const std::vector<std::uint8_t>& bytes)
{
    try {
        parseKtxCube(asBytes(bytes), "bad.ktx");
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

void expectError(const std::vector<std::uint8_t>& bytes, const std::string& phrase)
{
    const std::string message = errorOf(bytes);
    EXPECT_EQ(message.rfind("bad.ktx: ", 0), 0u) << message;
    EXPECT_NE(message.find(phrase), std::string::npos) << "expected \"" << phrase << "\" in: " << message;
}

void put32(std::vector<std::uint8_t>& b, std::size_t at, std::uint32_t v)
{
    for (int i = 0; i < 4; ++i) b[at + std::size_t(i)] = std::uint8_t(v >> (8 * i));
}

} // namespace

TEST(KtxReader, Ktx1HalfCubeWithMipsAndKeys)
{
    const KtxCube cube = parseKtxCube(asBytes(makeKtx1Cube(4, 3, {{"sh", "1 2 3"}, {"other", ""}})), "a.ktx");
    EXPECT_EQ(cube.version, 1);
    EXPECT_EQ(cube.formatName, "RGBA16F");
    EXPECT_EQ(cube.faceSize, 4);
    expectTexels(cube, 3);
    ASSERT_NE(cube.value("sh"), nullptr);
    EXPECT_EQ(*cube.value("sh"), "1 2 3");
    EXPECT_EQ(cube.value("missing"), nullptr);
}

TEST(KtxReader, Ktx2FloatCubeWithEveryMip)
{
    const KtxCube cube = parseKtxCube(asBytes(makeKtx2Cube(8, 4)), "a.ktx2");
    EXPECT_EQ(cube.version, 2);
    EXPECT_EQ(cube.formatName, "RGBA32F");
    expectTexels(cube, 4);
    ASSERT_NE(cube.value("KTXwriter"), nullptr);
}

TEST(KtxReader, BadInputNamesTheFileAndTheProblem)
{
    expectError({1, 2, 3}, "not a KTX file");
    auto k1 = makeKtx1Cube(4, 3);
    expectError(std::vector<std::uint8_t>(k1.begin(), k1.begin() + 40), "truncated");
    expectError(std::vector<std::uint8_t>(k1.begin(), k1.end() - 4), "truncated: level 2 face 5");
    auto unknown = k1;
    put32(unknown, 28, 0x8058); // GL_RGBA8
    expectError(unknown, "unsupported format: glInternalFormat 0x8058");
    auto flat = k1;
    put32(flat, 52, 1); // numberOfFaces
    expectError(flat, "not a cube map: 1 face(s)");
    auto array = k1;
    put32(array, 48, 2);
    expectError(array, "not a cube map: an array of 2");
    auto wide = k1;
    put32(wide, 36, 8); // pixelWidth 8, height 4
    expectError(wide, "faces are 8x4");
    auto huge = k1;
    put32(huge, 36, 1u << 30);
    put32(huge, 40, 1u << 30);
    expectError(huge, "over the limit");
    auto levels = k1;
    put32(levels, 56, 9);
    expectError(levels, "9 mip levels declared, a 4^2 cube has at most 3");
    auto imageSize = k1;
    put32(imageSize, 64, 12345); // level 0's imageSize (no key/values)
    expectError(imageSize, "declares imageSize 12345");
    auto keyValues = k1;
    put32(keyValues, 60, 1u << 20);
    expectError(keyValues, "truncated: the key/value data");
    auto bigEndian = k1;
    put32(bigEndian, 12, 0x01020304);
    expectError(bigEndian, "big-endian");

    auto k2 = makeKtx2Cube(4, 3);
    expectError(std::vector<std::uint8_t>(k2.begin(), k2.begin() + 60), "truncated: the KTX 2.0 header");
    expectError(makeKtx2Cube(4, 3, 2), "supercompressed with Zstandard");
    expectError(makeKtx2Cube(4, 3, 1), "supercompressed with BasisLZ");
    auto basis = k2;
    put32(basis, 12, 0);
    expectError(basis, "VK_FORMAT_UNDEFINED");
    auto past = k2;
    put32(past, 80, 0x7FFFFFF0); // level 0's byteOffset
    expectError(past, "level 0 (");
    expectError(past, "runs past the end of the file");
    auto length = k2;
    put32(length, 88, 7); // level 0's byteLength
    expectError(length, "level 0 has byteLength 7");
    expectError(std::vector<std::uint8_t>(k2.begin(), k2.end() - 100), "runs past the end of the file");
}

TEST(KtxReader, FileErrorsNameThePath)
{
    const fs::path dir = fs::temp_directory_path() / ("iblab-ktx-test-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string path = (dir / "short_ibl.ktx").string();
    auto bytes = makeKtx1Cube(4, 3);
    bytes.resize(bytes.size() - 30);
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    try {
        loadEnvironment(path);
        ADD_FAILURE() << "a truncated bake loaded";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()).rfind(path + ": truncated", 0), 0u) << e.what();
    }
    try {
        loadEnvironment((dir / "missing_ibl.ktx").string());
        ADD_FAILURE() << "a missing bake loaded";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("missing_ibl.ktx: no such file"), std::string::npos) << e.what();
    }
    // A directory named like a bake is said to be one (an open of it said only "cannot open").
    fs::create_directories(dir / "folder_ibl.ktx");
    try {
        loadEnvironment((dir / "folder_ibl.ktx").string());
        ADD_FAILURE() << "a directory loaded";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("folder_ibl.ktx: is a directory"), std::string::npos) << e.what();
    }
    fs::remove_all(dir);
}

TEST(KtxReader, R11G11B10AndRgb9e5Decode)
{
    // R = 1.0 (exponent 15, mantissa 0), G = 2.5 (exponent 16, mantissa 0.25 * 64),
    // B = 0.75 (exponent 14, mantissa 0.5 * 32).
    const std::uint32_t packed = (15u << 6) | (((16u << 6) | 16u) << 11) | (((14u << 5) | 16u) << 22);
    std::vector<std::byte> face(4);
    std::memcpy(face.data(), &packed, 4);
    ImageRGB32F strip(1, 6);
    ktx_detail::decodeFace(ktx_detail::TexelFormat::R11G11B10F, face.data(), 4, 1, 0, strip);
    EXPECT_EQ(strip.at(0, 0), glm::vec3(1.0f, 2.5f, 0.75f));
    // RGB9_E5: mantissas 256, 128, 64 with exponent 16: (256, 128, 64) * 2^(16 - 24).
    const std::uint32_t e5 = 256u | (128u << 9) | (64u << 18) | (16u << 27);
    std::memcpy(face.data(), &e5, 4);
    ktx_detail::decodeFace(ktx_detail::TexelFormat::RGB9E5, face.data(), 4, 1, 0, strip);
    EXPECT_EQ(strip.at(0, 0), glm::vec3(1.0f, 0.5f, 0.25f));
}
