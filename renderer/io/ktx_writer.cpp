// KTX writers. Section numbers are those of the KTX 1.1 specification
// (registry.khronos.org/KTX/specs/1.0/ktxspec.v1.html) and the KTX 2.0 specification
// (registry.khronos.org/KTX/specs/2.0/ktxspec.v2.html); docs/engine-export.md lists them.
#include "io/ktx_writer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>

#include <Imath/half.h>

#include "io/error.hpp"

namespace iblab::ktx {
namespace {

// Little-endian appends: both specifications' fields are written in the writer's order and
// KTX 2.0 requires little-endian; every machine iblab builds for is little-endian, and the
// bytes are assembled explicitly so the files are the same on any.
void putU32(std::string& out, std::uint32_t v)
{
    for (int i = 0; i < 4; ++i) out.push_back(char((v >> (8 * i)) & 0xFFu));
}
void setU64(std::string& out, std::size_t at, std::uint64_t v)
{
    for (int i = 0; i < 8; ++i) out[at + std::size_t(i)] = char((v >> (8 * i)) & 0xFFu);
}
void setU32(std::string& out, std::size_t at, std::uint32_t v)
{
    for (int i = 0; i < 4; ++i) out[at + std::size_t(i)] = char((v >> (8 * i)) & 0xFFu);
}
void padTo(std::string& out, std::size_t alignment)
{
    while (out.size() % alignment != 0) out.push_back('\0');
}

// One level's texels in the file's pixel type, faces in order.
void putTexels(std::string& out, const std::vector<float>& texels, PixelType type)
{
    if (type == PixelType::Float) {
        const std::size_t at = out.size();
        out.resize(at + texels.size() * sizeof(float));
        std::memcpy(out.data() + at, texels.data(), texels.size() * sizeof(float));
        return;
    }
    // Past 65504 a half is +Inf, which an engine's filtering spreads as NaN: a bake of a map
    // brighter than that (in floats, BakeJob::cubeFormat) is clipped there, as a half-float
    // bake of it would be (the exporter says so: ExportReport::clippedToHalf).
    for (float v : texels) {
        const std::uint16_t bits = Imath::half(std::clamp(v, -float(HALF_MAX), float(HALF_MAX))).bits();
        out.push_back(char(bits & 0xFFu));
        out.push_back(char(bits >> 8));
    }
}

std::string faceBytes(const KtxTexture& t, int level, int face)
{
    const std::size_t n = std::size_t(t.levelSize(level)) * std::size_t(t.levelSize(level)) * 4;
    const std::vector<float>& all = t.levels[std::size_t(level)];
    const std::vector<float> one(all.begin() + std::ptrdiff_t(n * std::size_t(face)), all.begin() + std::ptrdiff_t(n * std::size_t(face + 1)));
    std::string out;
    putTexels(out, one, t.pixelType);
    return out;
}

// KTX 1.1 section 2.16 / KTX 2.0 section 3.11: keyAndValueByteSize, key, NUL, value, padding.
void putKeyValue(std::string& out, const std::string& key, const std::string& value, bool nulTerminateValue)
{
    const std::size_t length = key.size() + 1 + value.size() + (nulTerminateValue ? 1 : 0);
    putU32(out, std::uint32_t(length));
    out += key;
    out.push_back('\0');
    out += value;
    if (nulTerminateValue) out.push_back('\0');
    padTo(out, 4);
}

// The basic data format descriptor of linear RGBA floats (KTX 2.0 section 3.10; Khronos
// Data Format 1.3 sections 5 and 5.18): four samples R, G, B, A, each flagged float and
// signed, with lower/upper -1.0 / 1.0 as the format's normalisation (section 5.17.14).
std::string dataFormatDescriptor(PixelType type)
{
    const std::uint32_t bits = type == PixelType::Half ? 16 : 32;
    std::string block;
    const std::uint32_t blockSize = 24 + 16 * 4;
    putU32(block, 0); // vendorId 0 (Khronos), descriptorType 0 (basic)
    putU32(block, kDfdVersion | (blockSize << 16));
    putU32(block, kDfdModelRgbsda | (kDfdPrimariesBt709 << 8) | (kDfdTransferLinear << 16)); // flags 0: straight alpha
    putU32(block, 0); // texelBlockDimension 1x1x1x1 (stored minus one)
    putU32(block, bits / 8 * 4); // bytesPlane0
    putU32(block, 0);            // bytesPlane1..7
    const std::uint32_t channels[4] = {kDfdChannelR, kDfdChannelG, kDfdChannelB, kDfdChannelA};
    for (std::uint32_t i = 0; i < 4; ++i) {
        putU32(block, (i * bits) | ((bits - 1) << 16) | ((channels[i] | kDfdQualifierFloat | kDfdQualifierSigned) << 24));
        putU32(block, 0);           // sample position
        putU32(block, 0xBF800000u); // sampleLower: -1.0f
        putU32(block, 0x3F800000u); // sampleUpper: 1.0f
    }
    std::string dfd;
    putU32(dfd, std::uint32_t(4 + block.size())); // dfdTotalSize
    return dfd + block;
}

} // namespace

bool KtxTexture::clipsToHalf() const
{
    if (pixelType != PixelType::Half)
        return false;
    for (const std::vector<float>& level : levels)
        for (float v : level)
            if (std::abs(v) > float(HALF_MAX))
                return true;
    return false;
}

void KtxTexture::validate() const
{
    if (size < 1) throw std::invalid_argument("KTX texture: size must be at least 1, got " + std::to_string(size));
    if (faces != 1 && faces != 6) throw std::invalid_argument("KTX texture: 1 or 6 faces, got " + std::to_string(faces));
    if (levels.empty()) throw std::invalid_argument("KTX texture: no levels");
    int maxLevels = 1;
    while ((size >> maxLevels) > 0) ++maxLevels;
    if (int(levels.size()) > maxLevels)
        throw std::invalid_argument("KTX texture: " + std::to_string(levels.size()) + " levels for a size of " + std::to_string(size) +
                                    " (at most " + std::to_string(maxLevels) + ")");
    for (std::size_t m = 0; m < levels.size(); ++m) {
        const std::size_t edge = std::size_t(levelSize(int(m)));
        const std::size_t expected = std::size_t(faces) * edge * edge * 4;
        if (levels[m].size() != expected)
            throw std::invalid_argument("KTX texture: level " + std::to_string(m) + " has " + std::to_string(levels[m].size()) +
                                        " floats, expected " + std::to_string(expected));
    }
}

std::string encodeKtx1(const KtxTexture& t)
{
    t.validate();
    std::string kv;
    for (const auto& [key, value] : t.keyValues) putKeyValue(kv, key, value, /*nulTerminateValue=*/true);
    std::string out(reinterpret_cast<const char*>(kKtx1Identifier.data()), kKtx1Identifier.size()); // 2.1
    putU32(out, kKtx1Endianness);                                                                    // 2.2
    const bool half = t.pixelType == PixelType::Half;
    putU32(out, half ? kGlHalfFloat : kGlFloat);   // 2.3 glType
    putU32(out, half ? 2 : 4);                     // 2.4 glTypeSize
    putU32(out, kGlRgba);                          // 2.5 glFormat
    putU32(out, half ? kGlRgba16f : kGlRgba32f);   // 2.6 glInternalFormat
    putU32(out, kGlRgba);                          // 2.7 glBaseInternalFormat
    putU32(out, std::uint32_t(t.size));            // 2.8 pixelWidth
    putU32(out, std::uint32_t(t.size));            //     pixelHeight
    putU32(out, 0);                                //     pixelDepth
    putU32(out, 0);                                // 2.9 numberOfArrayElements
    putU32(out, std::uint32_t(t.faces));           // 2.10 numberOfFaces
    putU32(out, std::uint32_t(t.levels.size()));   // 2.11 numberOfMipmapLevels
    putU32(out, std::uint32_t(kv.size()));         // 2.12 bytesOfKeyValueData
    out += kv;                                     // 2.13
    for (int m = 0; m < int(t.levels.size()); ++m) {
        // 2.16 imageSize: for a non-array cube map, the bytes of one face.
        const std::size_t faceSize = std::size_t(t.levelSize(m)) * std::size_t(t.levelSize(m)) * t.bytesPerTexel();
        putU32(out, std::uint32_t(faceSize));
        for (int f = 0; f < t.faces; ++f) {
            out += faceBytes(t, m, f);
            padTo(out, 4); // 2.17 cubePadding (none for 8- or 16-byte texels)
        }
        padTo(out, 4); // 2.18 mipPadding
    }
    return out;
}

std::string encodeKtx2(const KtxTexture& t)
{
    t.validate();
    const std::size_t levelCount = t.levels.size();
    // 3.11: keys sorted by their UTF-8 bytes; KTXwriter identifies the tool.
    std::vector<std::pair<std::string, std::string>> pairs = t.keyValues;
    if (std::none_of(pairs.begin(), pairs.end(), [](const auto& p) { return p.first == "KTXwriter"; }))
        pairs.emplace_back("KTXwriter", "iblab");
    std::sort(pairs.begin(), pairs.end());
    std::string kv;
    for (const auto& [key, value] : pairs) putKeyValue(kv, key, value, /*nulTerminateValue=*/true);
    const std::string dfd = dataFormatDescriptor(t.pixelType);

    std::string out(reinterpret_cast<const char*>(kKtx2Identifier.data()), kKtx2Identifier.size()); // 3.1
    putU32(out, t.pixelType == PixelType::Half ? kVkR16g16b16a16Sfloat : kVkR32g32b32a32Sfloat);     // 3.2 vkFormat
    putU32(out, t.pixelType == PixelType::Half ? 2 : 4);                                              // 3.3 typeSize
    putU32(out, std::uint32_t(t.size));         // 3.4 pixelWidth
    putU32(out, std::uint32_t(t.size));         //     pixelHeight
    putU32(out, 0);                             //     pixelDepth
    putU32(out, 0);                             // 3.5 layerCount
    putU32(out, std::uint32_t(t.faces));        // 3.6 faceCount
    putU32(out, std::uint32_t(levelCount));     // 3.7 levelCount
    putU32(out, 0);                             // 3.8 supercompressionScheme: none
    const std::size_t indexAt = out.size();     // 3.9 index, filled in below
    out.resize(out.size() + 4 * 4 + 2 * 8 + levelCount * kKtx2LevelIndexEntryBytes, '\0');
    const std::size_t dfdAt = out.size();
    out += dfd;                                 // 3.10
    padTo(out, 4);
    const std::size_t kvAt = out.size();
    out += kv;                                  // 3.11
    // 3.12 sgd: none. 3.13 mip level array, smallest level first, each level aligned to
    // lcm(texel block size, 4) = the texel size (8 or 16).
    std::vector<std::pair<std::size_t, std::size_t>> placed(levelCount);
    for (std::size_t k = levelCount; k-- > 0;) {
        padTo(out, t.bytesPerTexel());
        const std::size_t start = out.size();
        for (int f = 0; f < t.faces; ++f) out += faceBytes(t, int(k), f);
        placed[k] = {start, out.size() - start};
    }
    setU32(out, indexAt + 0, std::uint32_t(dfdAt));
    setU32(out, indexAt + 4, std::uint32_t(dfd.size()));
    setU32(out, indexAt + 8, kv.empty() ? 0u : std::uint32_t(kvAt));
    setU32(out, indexAt + 12, std::uint32_t(kv.size()));
    setU64(out, indexAt + 16, 0); // sgdByteOffset
    setU64(out, indexAt + 24, 0); // sgdByteLength
    for (std::size_t m = 0; m < levelCount; ++m) {
        const std::size_t entry = indexAt + 32 + m * kKtx2LevelIndexEntryBytes;
        setU64(out, entry, placed[m].first);
        setU64(out, entry + 8, placed[m].second);
        setU64(out, entry + 16, placed[m].second); // uncompressedByteLength
    }
    return out;
}

void writeKtx1(const std::string& path, const KtxTexture& texture, Durability durability)
{
    const std::string bytes = rethrowAsError(path, "encoding KTX", "cannot encode", [&] { return encodeKtx1(texture); });
    writeTextFileAtomic(path, bytes, durability);
}

void writeKtx2(const std::string& path, const KtxTexture& texture, Durability durability)
{
    const std::string bytes = rethrowAsError(path, "encoding KTX2", "cannot encode", [&] { return encodeKtx2(texture); });
    writeTextFileAtomic(path, bytes, durability);
}

} // namespace iblab::ktx
