// KTX 1.1 cube maps (registry.khronos.org/KTX/specs/1.0/ktxspec.v1.html). What cmgen
// --format=ktx writes (Filament 1.9.25): glInternalFormat GL_R11F_G11F_B10F, glFormat GL_RGB,
// glType 0x8C3A (the internal format's enum where the spec wants
// GL_UNSIGNED_INT_10F_11F_11F_REV, 0x8C3B), so the format is told by glInternalFormat alone.
#include <optional>

#include "io/error.hpp"
#include "io/ktx_cube.hpp"
#include "io/ktx_format.hpp"

namespace iblab {

using namespace ktx_detail;

namespace {

constexpr std::size_t kHeaderBytes = 64; // identifier (12) + 13 UInt32 (section 2.1)

std::optional<TexelFormat> ktx1Format(std::uint32_t internalFormat)
{
    switch (internalFormat) {
    case ktx::kGlR11fG11fB10f: return TexelFormat::R11G11B10F;
    case 0x8C3D: return TexelFormat::RGB9E5;     // GL_RGB9_E5
    case 0x881B: return TexelFormat::RGB16F;     // GL_RGB16F
    case ktx::kGlRgba16f: return TexelFormat::RGBA16F;
    case 0x8815: return TexelFormat::RGB32F;     // GL_RGB32F
    case ktx::kGlRgba32f: return TexelFormat::RGBA32F;
    default: return std::nullopt;
    }
}

std::string hex(std::uint32_t v)
{
    static const char* digits = "0123456789ABCDEF";
    std::string s = "0x";
    for (int shift = 12; shift >= 0; shift -= 4)
        s += digits[(v >> shift) & 15u];
    return v > 0xFFFFu ? std::to_string(v) : s;
}

std::size_t padTo4(std::size_t n) { return (n + 3u) & ~std::size_t(3); }

// Bytes left from offset (0 once padding has stepped past the end).
std::size_t remaining(std::span<const std::byte> bytes, std::size_t offset) { return offset < bytes.size() ? bytes.size() - offset : 0; }

std::string truncated(std::string_view what, std::uint64_t need, std::size_t offset, std::size_t have)
{
    return "truncated: " + std::string(what) + " needs " + std::to_string(need) + " bytes at offset " + std::to_string(offset) +
           ", the file has " + std::to_string(have);
}

} // namespace

KtxCube parseKtx1Cube(std::span<const std::byte> bytes, std::string_view name, const KtxReadOptions& options)
{
    if (bytes.size() < kHeaderBytes) throw Error(name, truncated("the KTX 1.1 header", kHeaderBytes, 0, bytes.size()));
    // Section 2.2: 0x04030201 as the writer's endianness wrote it. A big-endian writer's file
    // (0x01020304) would need its texels swapped too; no bake tool writes one.
    const std::uint32_t endianness = readU32(bytes, 12);
    if (endianness == 0x01020304u) throw Error(name, "big-endian KTX files are not supported");
    if (endianness != ktx::kKtx1Endianness) throw Error(name, "bad KTX 1.1 endianness field " + std::to_string(endianness));
    auto field = [&](int k) { return readU32(bytes, 16 + 4 * std::size_t(k)); };
    const std::uint32_t glType = field(0), glTypeSize = field(1), glFormat = field(2), glInternalFormat = field(3);
    const std::uint32_t width = field(5), height = field(6), depth = field(7), arrayElements = field(8), faces = field(9);
    const std::uint32_t levelCount = field(10), keyValueBytes = field(11);
    (void)glType;
    (void)glTypeSize;
    (void)glFormat;
    const std::optional<TexelFormat> format = ktx1Format(glInternalFormat);
    if (!format)
        throw Error(name, "unsupported format: glInternalFormat " + hex(glInternalFormat) +
                              " (readable: R11F_G11F_B10F, RGB9_E5, RGB16F, RGBA16F, RGB32F, RGBA32F)");
    if (arrayElements != 0) throw Error(name, "not a cube map: an array of " + std::to_string(arrayElements) + " textures");
    if (faces != 6) throw Error(name, "not a cube map: " + std::to_string(faces) + " face(s), a cube has 6");
    checkFaceSize(width, height, depth, options, name);
    KtxCube cube;
    cube.version = 1;
    cube.formatName = formatName(*format);
    cube.faceSize = int(width);
    const int levels = checkedLevelCount(levelCount, cube.faceSize, name);

    // Section 2.16: key/value pairs, each UInt32 keyAndValueByteSize, the bytes, and padding
    // to a multiple of 4.
    if (keyValueBytes > bytes.size() - kHeaderBytes)
        throw Error(name, truncated("the key/value data", keyValueBytes, kHeaderBytes, bytes.size()));
    std::size_t offset = kHeaderBytes;
    const std::size_t keyValueEnd = kHeaderBytes + keyValueBytes;
    while (offset < keyValueEnd) {
        if (keyValueEnd - offset < 4) throw Error(name, "a key/value entry's size runs past the key/value data");
        const std::uint32_t entryBytes = readU32(bytes, offset);
        offset += 4;
        if (entryBytes > keyValueEnd - offset)
            throw Error(name, "a key/value entry of " + std::to_string(entryBytes) + " bytes runs past the key/value data");
        cube.keyValues.push_back(splitKeyValue(bytes.subspan(offset, entryBytes), name));
        offset += padTo4(entryBytes);
    }
    offset = keyValueEnd;

    // Sections 2.17-2.19: per level a UInt32 imageSize, then (a non-array cube) each face's
    // imageSize bytes padded to 4 (cubePadding), rows padded to 4 bytes (GL_UNPACK_ALIGNMENT).
    const std::size_t texel = texelBytes(*format);
    for (int level = 0; level < levels; ++level) {
        const int size = cube.levelSize(level);
        const std::size_t rowPitch = padTo4(std::size_t(size) * texel);
        const std::size_t faceBytes = rowPitch * std::size_t(size);
        if (remaining(bytes, offset) < 4) throw Error(name, truncated("level " + std::to_string(level) + "'s imageSize", 4, offset, bytes.size()));
        const std::uint32_t imageSize = readU32(bytes, offset);
        offset += 4;
        if (imageSize != faceBytes)
            throw Error(name, "level " + std::to_string(level) + " declares imageSize " + std::to_string(imageSize) + ", a " + std::to_string(size) +
                                  "^2 face of " + cube.formatName + " is " + std::to_string(faceBytes) + " bytes");
        ImageRGB32F strip(size, 6 * size);
        for (int face = 0; face < 6; ++face) {
            if (remaining(bytes, offset) < faceBytes)
                throw Error(name, truncated("level " + std::to_string(level) + " face " + std::to_string(face), faceBytes, offset, bytes.size()));
            cube.repairedComponents += decodeFace(*format, bytes.data() + offset, rowPitch, size, face, strip);
            offset += padTo4(faceBytes);
        }
        cube.levels.push_back(std::move(strip));
    }
    return cube;
}

} // namespace iblab
