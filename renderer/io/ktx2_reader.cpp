// KTX 2.0 cube maps (registry.khronos.org/KTX/specs/2.0/ktxspec.v2.html), as the
// glTF-IBL-Sampler writes them for the glTF Sample Viewer: VK_FORMAT_R16G16B16A16_SFLOAT or
// R32G32B32A32_SFLOAT, 6 faces, every mip, no supercompression.
#include <optional>

#include "io/error.hpp"
#include "io/ktx_cube.hpp"
#include "io/ktx_format.hpp"

namespace iblab {

using namespace ktx_detail;

namespace {

constexpr std::size_t kHeaderBytes = ktx::kKtx2HeaderBytes;
constexpr std::size_t kLevelIndexEntryBytes = ktx::kKtx2LevelIndexEntryBytes;

std::optional<TexelFormat> vkFormat(std::uint32_t format)
{
    switch (format) {
    case 122: return TexelFormat::R11G11B10F; // VK_FORMAT_B10G11R11_UFLOAT_PACK32 (R in the low bits)
    case 123: return TexelFormat::RGB9E5;     // VK_FORMAT_E5B9G9R9_UFLOAT_PACK32
    case 90: return TexelFormat::RGB16F;      // VK_FORMAT_R16G16B16_SFLOAT
    case ktx::kVkR16g16b16a16Sfloat: return TexelFormat::RGBA16F;
    case 106: return TexelFormat::RGB32F;     // VK_FORMAT_R32G32B32_SFLOAT
    case ktx::kVkR32g32b32a32Sfloat: return TexelFormat::RGBA32F;
    default: return std::nullopt;
    }
}

const char* supercompressionName(std::uint32_t scheme)
{
    switch (scheme) {
    case 1: return "BasisLZ";
    case 2: return "Zstandard";
    case 3: return "ZLIB";
    default: return "an unknown scheme";
    }
}

// [offset, offset + length) inside the file, without overflow.
bool inside(std::uint64_t offset, std::uint64_t length, std::size_t fileBytes)
{
    return offset <= fileBytes && length <= fileBytes - offset;
}

} // namespace

KtxCube parseKtx2Cube(std::span<const std::byte> bytes, std::string_view name, const KtxReadOptions& options)
{
    if (bytes.size() < kHeaderBytes)
        throw Error(name, "truncated: the KTX 2.0 header needs " + std::to_string(kHeaderBytes) + " bytes, the file has " + std::to_string(bytes.size()));
    auto field = [&](int k) { return readU32(bytes, 12 + 4 * std::size_t(k)); };
    const std::uint32_t format = field(0), width = field(2), height = field(3), depth = field(4);
    const std::uint32_t layers = field(5), faces = field(6), levelCount = field(7), supercompression = field(8);
    const std::uint32_t kvdOffset = readU32(bytes, 56), kvdLength = readU32(bytes, 60);
    const std::optional<TexelFormat> texelFormat = vkFormat(format);
    if (!texelFormat)
        throw Error(name, format == 0 ? std::string("unsupported format: VK_FORMAT_UNDEFINED (a Basis Universal or other block-compressed payload)")
                                      : "unsupported format: vkFormat " + std::to_string(format) +
                                            " (readable: B10G11R11_UFLOAT, E5B9G9R9_UFLOAT, R16G16B16(A16)_SFLOAT, R32G32B32(A32)_SFLOAT)");
    if (supercompression != 0)
        throw Error(name, std::string("supercompressed with ") + supercompressionName(supercompression) + " (scheme " +
                              std::to_string(supercompression) + "), which this reader does not decode");
    if (layers != 0) throw Error(name, "not a cube map: an array of " + std::to_string(layers) + " layers");
    if (faces != 6) throw Error(name, "not a cube map: " + std::to_string(faces) + " face(s), a cube has 6");
    checkFaceSize(width, height, depth, options, name);
    KtxCube cube;
    cube.version = 2;
    cube.formatName = formatName(*texelFormat);
    cube.faceSize = int(width);
    const int levels = checkedLevelCount(levelCount, cube.faceSize, name);
    if (bytes.size() < kHeaderBytes + std::size_t(levels) * kLevelIndexEntryBytes)
        throw Error(name, "truncated: the level index of " + std::to_string(levels) + " levels runs past the end of the file (" +
                              std::to_string(bytes.size()) + " bytes)");

    // Section 3.11: key/value data, each UInt32 keyAndValueByteLength, the bytes, padding to 4.
    if (kvdLength != 0) {
        if (!inside(kvdOffset, kvdLength, bytes.size()))
            throw Error(name, "the key/value data (" + std::to_string(kvdLength) + " bytes at offset " + std::to_string(kvdOffset) +
                                  ") runs past the end of the file (" + std::to_string(bytes.size()) + " bytes)");
        std::size_t offset = kvdOffset;
        const std::size_t end = std::size_t(kvdOffset) + kvdLength;
        while (offset + 4 <= end) {
            const std::uint32_t entryBytes = readU32(bytes, offset);
            offset += 4;
            if (entryBytes > end - offset)
                throw Error(name, "a key/value entry of " + std::to_string(entryBytes) + " bytes runs past the key/value data");
            cube.keyValues.push_back(splitKeyValue(bytes.subspan(offset, entryBytes), name));
            offset += (std::size_t(entryBytes) + 3u) & ~std::size_t(3);
        }
    }

    // Section 3.9: level index entry m is level m (the largest first); a level holds the 6
    // faces one after the other, rows tightly packed (section 3.12: no row padding).
    const std::size_t texel = texelBytes(*texelFormat);
    for (int level = 0; level < levels; ++level) {
        const std::size_t entry = kHeaderBytes + std::size_t(level) * kLevelIndexEntryBytes;
        const std::uint64_t offset = readU64(bytes, entry), length = readU64(bytes, entry + 8);
        const int size = cube.levelSize(level);
        const std::size_t faceBytes = std::size_t(size) * std::size_t(size) * texel;
        if (length != 6 * faceBytes)
            throw Error(name, "level " + std::to_string(level) + " has byteLength " + std::to_string(length) + ", 6 " + std::to_string(size) +
                                  "^2 faces of " + cube.formatName + " are " + std::to_string(6 * faceBytes) + " bytes");
        if (!inside(offset, length, bytes.size()))
            throw Error(name, "level " + std::to_string(level) + " (" + std::to_string(length) + " bytes at offset " + std::to_string(offset) +
                                  ") runs past the end of the file (" + std::to_string(bytes.size()) + " bytes)");
        ImageRGB32F strip(size, 6 * size);
        for (int face = 0; face < 6; ++face)
            cube.repairedComponents +=
                decodeFace(*texelFormat, bytes.data() + offset + std::size_t(face) * faceBytes, std::size_t(size) * texel, size, face, strip);
        cube.levels.push_back(std::move(strip));
    }
    return cube;
}

} // namespace iblab
