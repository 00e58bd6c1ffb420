#pragma once
// Reading cube maps from KTX 1.1 and KTX 2.0 files: what another tool's bake (Filament's
// cmgen, the glTF-IBL-Sampler) hands over. Only what such bakes hold is accepted: a single
// (non-array) cube, 6 square faces, any number of mips, a float format that decodes to
// linear RGB without a library (ktxFormatName lists them); anything else, and every
// inconsistency of the container, is an iblab::Error naming the file and the problem:
//   "ibl.ktx: truncated: level 2 needs 1536 bytes at offset 17004, the file has 16800"
// Specs followed: KTX 1.1 (registry.khronos.org/KTX/specs/1.0/ktxspec.v1.html, sections
// 2.1-2.19: header, key/value data, imageSize, cube padding, mip padding, rows padded to 4
// bytes) and KTX 2.0 (registry.khronos.org/KTX/specs/2.0/ktxspec.v2.html, sections 3.1-3.12:
// header, index, level index, key/value data; levels stored smallest first, indexed largest
// first; no row padding).
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ibl/image.hpp"

namespace iblab {

struct KtxCube {
    int version = 0;         // 1 or 2
    std::string formatName;  // "R11F_G11F_B10F", "RGBA16F", ... (ktxFormatName)
    int faceSize = 0;        // edge of level 0
    // Level m: a "strip" of width faceSize >> m and height 6 x that, face k (file order
    // +X, -X, +Y, -Y, +Z, -Z, which is GL's) in rows [k size, (k + 1) size), each face's rows
    // in file order (the first stored row is row 0, as GL uploads it). Alpha is dropped.
    std::vector<ImageRGB32F> levels;
    // KTX key/value pairs in file order; a value's trailing NUL is removed.
    std::vector<std::pair<std::string, std::string>> keyValues;
    // Components that were NaN, infinite or negative (a half or float format can hold them),
    // replaced by 0 so that every later stage may trust the texels, as loadEnvironment does.
    std::uint64_t repairedComponents = 0;

    int levelSize(int level) const { return faceSize >> level > 0 ? faceSize >> level : 1; }
    // The value of key, or nullptr.
    const std::string* value(std::string_view key) const;
};

struct KtxReadOptions {
    // Largest face edge accepted (checked from the header before anything is allocated).
    int maxFaceSize = 8192;
};

// Reads a .ktx (KTX 1.1) or .ktx2 (KTX 2.0) file, told apart by their identifiers.
KtxCube readKtxCube(const std::string& path, const KtxReadOptions& options = {});
// The same from bytes in memory; `name` is what errors name.
KtxCube parseKtxCube(std::span<const std::byte> bytes, std::string_view name, const KtxReadOptions& options = {});
KtxCube parseKtx1Cube(std::span<const std::byte> bytes, std::string_view name, const KtxReadOptions& options = {});
KtxCube parseKtx2Cube(std::span<const std::byte> bytes, std::string_view name, const KtxReadOptions& options = {});

namespace ktx_detail {
// The float formats both readers decode, by a container-neutral id.
enum class TexelFormat { R11G11B10F, RGB9E5, RGB16F, RGBA16F, RGB32F, RGBA32F };
const char* formatName(TexelFormat format);
std::size_t texelBytes(TexelFormat format);
// Decodes `size` x `size` texels of one face, rows `rowPitch` bytes apart, into rows
// [face size, (face + 1) size) of the strip.
// Returns the components it had to repair (KtxCube::repairedComponents).
std::uint64_t decodeFace(TexelFormat format, const std::byte* data, std::size_t rowPitch, int size, int face, ImageRGB32F& strip);
// The level count a header declares (0 means 1: "generate mips", which a bake never asks
// for), checked against the face size: at most log2(faceSize) + 1.
int checkedLevelCount(std::uint64_t levels, int faceSize, std::string_view name);
void checkFaceSize(std::uint64_t width, std::uint64_t height, std::uint64_t depth, const KtxReadOptions& options, std::string_view name);
std::uint32_t readU32(std::span<const std::byte> bytes, std::size_t offset);
std::uint64_t readU64(std::span<const std::byte> bytes, std::size_t offset);
// One key/value entry's bytes ("key\0value\0?") split; throws for a key without its NUL.
std::pair<std::string, std::string> splitKeyValue(std::span<const std::byte> entry, std::string_view name);
} // namespace ktx_detail

} // namespace iblab
