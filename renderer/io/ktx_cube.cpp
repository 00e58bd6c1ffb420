// What the KTX 1.1 and KTX 2.0 readers share: the texel decoders, the size checks, reading
// the file, and telling the two containers apart.
#include "io/ktx_cube.hpp"

#include <bit>
#include <cmath>
#include <cstring>
#include <cerrno>
#include <fstream>

#include <Imath/half.h>

#include "io/atomic_file.hpp"
#include "io/error.hpp"
#include "io/ktx_format.hpp"

namespace iblab {
namespace ktx_detail {

const char* formatName(TexelFormat format)
{
    switch (format) {
    case TexelFormat::R11G11B10F: return "R11F_G11F_B10F";
    case TexelFormat::RGB9E5: return "RGB9_E5";
    case TexelFormat::RGB16F: return "RGB16F";
    case TexelFormat::RGBA16F: return "RGBA16F";
    case TexelFormat::RGB32F: return "RGB32F";
    case TexelFormat::RGBA32F: return "RGBA32F";
    }
    return "?";
}

std::size_t texelBytes(TexelFormat format)
{
    switch (format) {
    case TexelFormat::R11G11B10F:
    case TexelFormat::RGB9E5: return 4;
    case TexelFormat::RGB16F: return 6;
    case TexelFormat::RGBA16F: return 8;
    case TexelFormat::RGB32F: return 12;
    case TexelFormat::RGBA32F: return 16;
    }
    return 0;
}

namespace {

// An unsigned small float (the 11- and 10-bit channels of R11F_G11F_B10F): 5 exponent bits
// with bias 15, `mantissaBits` mantissa bits, no sign; exponent 31 is Inf/NaN (GL 4.6
// spec, section 2.3.4.3 and 2.3.4.4).
float unsignedSmallFloat(std::uint32_t bits, int mantissaBits)
{
    const std::uint32_t mantissa = bits & ((1u << mantissaBits) - 1u);
    const std::uint32_t exponent = (bits >> mantissaBits) & 31u;
    const float scale = float(1u << mantissaBits);
    if (exponent == 0) return std::ldexp(float(mantissa) / scale, -14);
    if (exponent == 31) return mantissa == 0 ? INFINITY : NAN;
    return std::ldexp(1.0f + float(mantissa) / scale, int(exponent) - 15);
}

// RGB9_E5: three 9-bit mantissas sharing a 5-bit exponent, bias 15 (GL 4.6 spec, 8.5.2).
void rgb9e5(std::uint32_t bits, float* rgb)
{
    const int exponent = int(bits >> 27) - 15 - 9;
    for (int c = 0; c < 3; ++c)
        rgb[c] = std::ldexp(float((bits >> (9 * c)) & 511u), exponent);
}

std::uint32_t loadU32(const std::byte* p)
{
    std::uint32_t v;
    std::memcpy(&v, p, 4);
    return v;
}

} // namespace

std::uint64_t decodeFace(TexelFormat format, const std::byte* data, std::size_t rowPitch, int size, int face, ImageRGB32F& strip)
{
    std::uint64_t repaired = 0;
    const std::size_t bytes = texelBytes(format);
    for (int row = 0; row < size; ++row) {
        const std::byte* in = data + std::size_t(row) * rowPitch;
        for (int x = 0; x < size; ++x, in += bytes) {
            float rgb[3] = {0.0f, 0.0f, 0.0f};
            switch (format) {
            case TexelFormat::R11G11B10F: {
                const std::uint32_t v = loadU32(in);
                rgb[0] = unsignedSmallFloat(v & 0x7FFu, 6);
                rgb[1] = unsignedSmallFloat((v >> 11) & 0x7FFu, 6);
                rgb[2] = unsignedSmallFloat(v >> 22, 5);
                break;
            }
            case TexelFormat::RGB9E5: rgb9e5(loadU32(in), rgb); break;
            case TexelFormat::RGB16F:
            case TexelFormat::RGBA16F:
                for (int c = 0; c < 3; ++c) {
                    std::uint16_t h;
                    std::memcpy(&h, in + 2 * c, 2);
                    Imath::half value;
                    value.setBits(h);
                    rgb[c] = float(value);
                }
                break;
            case TexelFormat::RGB32F:
            case TexelFormat::RGBA32F: std::memcpy(rgb, in, 12); break;
            }
            for (float& c : rgb)
                if (!std::isfinite(c) || c < 0.0f) {
                    c = 0.0f;
                    ++repaired;
                }
            strip.set(x, face * size + row, {rgb[0], rgb[1], rgb[2]});
        }
    }
    return repaired;
}

void checkFaceSize(std::uint64_t width, std::uint64_t height, std::uint64_t depth, const KtxReadOptions& options, std::string_view name)
{
    if (width == 0) throw Error(name, "not a cube map: its width is 0");
    if (height != width)
        throw Error(name, "not a cube map: faces are " + std::to_string(width) + "x" + std::to_string(height) + ", a cube's are square");
    if (depth > 1) throw Error(name, "not a cube map: a 3D texture of depth " + std::to_string(depth));
    if (width > std::uint64_t(options.maxFaceSize))
        throw Error(name, "face size " + std::to_string(width) + " is over the limit of " + std::to_string(options.maxFaceSize));
}

int checkedLevelCount(std::uint64_t levels, int faceSize, std::string_view name)
{
    const int most = std::bit_width(unsigned(faceSize));
    if (levels > std::uint64_t(most))
        throw Error(name, std::to_string(levels) + " mip levels declared, a " + std::to_string(faceSize) + "^2 cube has at most " +
                              std::to_string(most));
    return levels == 0 ? 1 : int(levels);
}

std::uint32_t readU32(std::span<const std::byte> bytes, std::size_t offset) { return loadU32(bytes.data() + offset); }

std::uint64_t readU64(std::span<const std::byte> bytes, std::size_t offset)
{
    std::uint64_t v;
    std::memcpy(&v, bytes.data() + offset, 8);
    return v;
}

std::pair<std::string, std::string> splitKeyValue(std::span<const std::byte> entry, std::string_view name)
{
    const char* text = reinterpret_cast<const char*>(entry.data());
    const std::string_view all(text, entry.size());
    const std::size_t nul = all.find('\0');
    if (nul == std::string_view::npos) throw Error(name, "a key/value entry's key has no terminating NUL");
    std::string_view value = all.substr(nul + 1);
    if (!value.empty() && value.back() == '\0') value.remove_suffix(1);
    return {std::string(all.substr(0, nul)), std::string(value)};
}

} // namespace ktx_detail

const std::string* KtxCube::value(std::string_view key) const
{
    for (const auto& [k, v] : keyValues)
        if (k == key) return &v;
    return nullptr;
}

KtxCube parseKtxCube(std::span<const std::byte> bytes, std::string_view name, const KtxReadOptions& options)
{
    if (bytes.size() >= 12 && std::memcmp(bytes.data(), ktx::kKtx1Identifier.data(), 12) == 0) return parseKtx1Cube(bytes, name, options);
    if (bytes.size() >= 12 && std::memcmp(bytes.data(), ktx::kKtx2Identifier.data(), 12) == 0) return parseKtx2Cube(bytes, name, options);
    throw Error(name, "not a KTX file: it starts with neither the KTX 1.1 nor the KTX 2.0 identifier");
}

KtxCube readKtxCube(const std::string& path, const KtxReadOptions& options)
{
    requireFile(path);
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) throw cannotOpenForReading(path, errno);
    const std::streamoff size = in.tellg();
    if (size < 0) throw Error(path, "cannot read");
    // The largest legal file: an RGBA32F cube of maxFaceSize with every mip, and some slack
    // for the key/value data. Anything larger is refused before it is read into memory.
    const std::uint64_t most = std::uint64_t(options.maxFaceSize) * std::uint64_t(options.maxFaceSize) * 6u * 16u * 4u / 3u + (1u << 20);
    if (std::uint64_t(size) > most) throw Error(path, "file of " + std::to_string(size) + " bytes is larger than any cube this reader accepts");
    std::vector<std::byte> bytes(static_cast<std::size_t>(size));
    in.seekg(0);
    if (!in.read(reinterpret_cast<char*>(bytes.data()), size)) throw Error(path, "cannot read");
    return rethrowAsError(path, "reading the KTX file", "cannot read", [&] { return parseKtxCube(bytes, path, options); });
}

} // namespace iblab
