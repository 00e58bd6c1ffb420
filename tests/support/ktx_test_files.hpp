#pragma once
// Hand-made KTX 1.1 and KTX 2.0 cube files for the reader tests and the fuzz seeds, written
// from the specs' layouts here, independently of renderer/io/ktx*.cpp. Texel value of
// (level, face, x, row), channel c: testTexel(...).
#include <cstdint>
#include <algorithm>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

namespace iblab::test {

inline float testTexel(int level, int face, int x, int row, int c)
{
    return 0.25f * float(level + 1) + 0.5f * float(face) + 0.125f * float(x) + 0.0625f * float(row) + 2.0f * float(c);
}

// IEEE half of a value exactly representable (the test values are).
inline std::uint16_t toHalf(float f)
{
    std::uint32_t bits;
    std::memcpy(&bits, &f, 4);
    const std::uint32_t sign = (bits >> 16) & 0x8000u;
    const int exponent = int((bits >> 23) & 0xFF) - 127 + 15;
    const std::uint32_t mantissa = bits & 0x7FFFFFu;
    if ((bits & 0x7FFFFFFFu) == 0) return std::uint16_t(sign);
    return std::uint16_t(sign | (std::uint32_t(exponent) << 10) | (mantissa >> 13));
}

struct Bytes {
    std::vector<std::uint8_t> data;
    void u32(std::uint32_t v) { for (int i = 0; i < 4; ++i) data.push_back(std::uint8_t(v >> (8 * i))); }
    void u64(std::uint64_t v) { for (int i = 0; i < 8; ++i) data.push_back(std::uint8_t(v >> (8 * i))); }
    void pad4() { while (data.size() % 4) data.push_back(0); }
    void put(const void* p, std::size_t n) { data.insert(data.end(), static_cast<const std::uint8_t*>(p), static_cast<const std::uint8_t*>(p) + n); }
    void setU32(std::size_t at, std::uint32_t v) { for (int i = 0; i < 4; ++i) data[at + std::size_t(i)] = std::uint8_t(v >> (8 * i)); }
};

// One face of RGBA16F (KTX1 rows are 8-byte multiples here: no row padding to add).
inline void appendFaceHalf(Bytes& b, int level, int face, int size)
{
    for (int row = 0; row < size; ++row)
        for (int x = 0; x < size; ++x)
            for (int c = 0; c < 4; ++c) {
                const std::uint16_t h = toHalf(c == 3 ? 1.0f : testTexel(level, face, x, row, c));
                b.put(&h, 2);
            }
}

// KTX 1.1, GL_RGBA16F, non-array cube, `levels` mips of `size`, key/values.
inline std::vector<std::uint8_t> makeKtx1Cube(int size, int levels, const std::vector<std::pair<std::string, std::string>>& keyValues = {})
{
    Bytes b;
    const std::uint8_t id[12] = {0xAB, 'K', 'T', 'X', ' ', '1', '1', 0xBB, '\r', '\n', 0x1A, '\n'};
    b.put(id, 12);
    Bytes kv;
    for (const auto& [k, v] : keyValues) {
        kv.u32(std::uint32_t(k.size() + 1 + v.size() + 1));
        kv.put(k.c_str(), k.size() + 1);
        kv.put(v.c_str(), v.size() + 1);
        kv.pad4();
    }
    for (std::uint32_t v : {0x04030201u, 0x140Bu /*GL_HALF_FLOAT*/, 2u, 0x1908u /*GL_RGBA*/, 0x881Au /*GL_RGBA16F*/, 0x1908u, std::uint32_t(size),
                            std::uint32_t(size), 0u, 0u, 6u, std::uint32_t(levels), std::uint32_t(kv.data.size())})
        b.u32(v);
    b.put(kv.data.data(), kv.data.size());
    for (int level = 0; level < levels; ++level) {
        const int s = std::max(size >> level, 1);
        b.u32(std::uint32_t(s * s * 8));
        for (int face = 0; face < 6; ++face)
            appendFaceHalf(b, level, face, s);
    }
    return b.data;
}

// KTX 2.0, VK_FORMAT_R32G32B32A32_SFLOAT, cube, levels stored smallest first (section 3.12).
inline std::vector<std::uint8_t> makeKtx2Cube(int size, int levels, std::uint32_t supercompression = 0)
{
    Bytes b;
    const std::uint8_t id[12] = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
    b.put(id, 12);
    for (std::uint32_t v : {109u, 4u, std::uint32_t(size), std::uint32_t(size), 0u, 0u, 6u, std::uint32_t(levels), supercompression})
        b.u32(v);
    const std::string key = "KTXwriter", value = "iblab test";
    const std::size_t indexAt = b.data.size();
    for (int i = 0; i < 4; ++i) b.u32(0);
    b.u64(0);
    b.u64(0);
    const std::size_t levelIndexAt = b.data.size();
    for (int level = 0; level < levels; ++level) { b.u64(0); b.u64(0); b.u64(0); }
    const std::size_t kvdAt = b.data.size();
    b.u32(std::uint32_t(key.size() + 1 + value.size() + 1));
    b.put(key.c_str(), key.size() + 1);
    b.put(value.c_str(), value.size() + 1);
    const std::size_t kvdLength = b.data.size() - kvdAt;
    b.setU32(indexAt + 8, std::uint32_t(kvdAt));
    b.setU32(indexAt + 12, std::uint32_t(kvdLength));
    while (b.data.size() % 16) b.data.push_back(0);
    for (int level = levels - 1; level >= 0; --level) {
        const int s = std::max(size >> level, 1);
        const std::size_t at = b.data.size();
        for (int face = 0; face < 6; ++face)
            for (int row = 0; row < s; ++row)
                for (int x = 0; x < s; ++x)
                    for (int c = 0; c < 4; ++c) {
                        const float f = c == 3 ? 1.0f : testTexel(level, face, x, row, c);
                        b.put(&f, 4);
                    }
        const std::size_t entry = levelIndexAt + std::size_t(level) * 24;
        for (int i = 0; i < 8; ++i) b.data[entry + std::size_t(i)] = std::uint8_t(std::uint64_t(at) >> (8 * i));
        const std::uint64_t length = b.data.size() - at;
        for (int i = 0; i < 8; ++i) {
            b.data[entry + 8 + std::size_t(i)] = std::uint8_t(length >> (8 * i));
            b.data[entry + 16 + std::size_t(i)] = std::uint8_t(length >> (8 * i));
        }
    }
    return b.data;
}

} // namespace iblab::test
