#pragma once
// What the KTX writers take: a 2D texture or a cube map, RGBA floats per level, and the
// key/value pairs of the file. No GL: the bake layer fills it from its read-backs.
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "io/ktx_format.hpp"

namespace iblab::ktx {

struct KtxTexture {
    int size = 0;  // edge of level 0 (square faces only: cube maps and the square LUT)
    int faces = 1; // 1 (2D) or 6 (cube map, faces in GL order +X, -X, +Y, -Y, +Z, -Z)
    // levels[m]: faces x levelSize(m)^2 texels of 4 floats (RGBA), face after face, each
    // face row after row, row 0 first (the first row GL or Vulkan stores: t = 0).
    std::vector<std::vector<float>> levels;
    PixelType pixelType = PixelType::Half;
    // In the order given (KTX 2.0 sorts them by key itself, section 3.11).
    std::vector<std::pair<std::string, std::string>> keyValues;

    int levelSize(int level) const { return size >> level > 0 ? size >> level : 1; }
    std::size_t bytesPerTexel() const { return pixelType == PixelType::Half ? 8 : 16; }
    // Whether a half-float file of it clips a texel (any value above the largest finite half,
    // 65504, where ktx_writer.cpp clips).
    bool clipsToHalf() const;
    // Throws std::invalid_argument naming the problem for sizes, faces or data that disagree.
    void validate() const;
};

} // namespace iblab::ktx
