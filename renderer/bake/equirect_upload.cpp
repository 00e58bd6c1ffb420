// The equirect's texture, the environment cube pass's source: BakePasses' upload, in one call
// or in parts that a job spreads over steps (a 4096-wide map's level 0 is 100 MB, whose upload
// on llvmpipe took up to 350 ms in one step, the fresh texture's pages faulted in as it went).
#include "bake/bake_passes.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <vector>

#include <glm/vec4.hpp>

#include "ibl/conventions.hpp"

namespace iblab::bake {
namespace {

// Levels of a full mip chain down to 1 texel on the longer side.
int fullMipLevels(int width, int height) { return std::bit_width(unsigned(std::max({width, height, 1}))); }

// `levels` mips of the image, 0 for its full chain.
int equirectLevels(const ImageRGB32F& image, int levels)
{
    const int full = fullMipLevels(image.width, image.height);
    return levels > 0 ? std::min(levels, full) : full;
}

} // namespace

int BakePasses::equirectLevelsForCube(int width, int height, int faceSize)
{
    const int full = fullMipLevels(width, height);
    const double maxLod = std::log2(2.0 * double(height) / (kPi * double(faceSize)));
    return std::clamp(1 + int(std::lround(maxLod)), 1, full);
}

gl::Texture BakePasses::createEquirect(const ImageRGB32F& image, int levels)
{
    levels = equirectLevels(image, levels);
    gl::Texture texture = gl::createTexture(GL_TEXTURE_2D);
    // One level: RGB32F, the image's own layout, so that the upload is one copy (the default
    // bake's 1024x512 map: 9 ms against 14 for the padded RGBA upload, minimum of 8 runs each;
    // the same texels are sampled). More: RGBA32F, since the mips are built by image
    // load/store, which RGB formats lack.
    glTextureStorage2D(texture.id(), levels, levels == 1 ? GL_RGB32F : GL_RGBA32F, image.width, image.height);
    // One level: plain bilinear, the same texels as trilinear clamped to level 0, without the
    // per-lane level selection llvmpipe compiles for a mip filter (the environment cube pass
    // took 0.8-0.95x the time in three interleaved runs of measure-bake.sh phases).
    glTextureParameteri(texture.id(), GL_TEXTURE_MIN_FILTER, levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
    glTextureParameteri(texture.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return texture;
}

void BakePasses::uploadEquirectRows(const gl::Texture& texture, const ImageRGB32F& image, int levels, int firstRow, int rowCount)
{
    levels = equirectLevels(image, levels);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    const float* rows = image.texels.data() + std::size_t(firstRow) * std::size_t(image.width) * 3;
    if (levels == 1) {
        glTextureSubImage2D(texture.id(), 0, 0, firstRow, image.width, rowCount, GL_RGB, GL_FLOAT, rows);
        return;
    }
    // Padded to RGBA here: the upload is then a copy, where Mesa's RGB -> RGBA conversion
    // path costs about as much as the rest of the upload and mip chain together. A band of
    // rows at a time, through one buffer that stays in cache, not a padded copy of the whole
    // image (whose fresh pages alone cost milliseconds to fault in).
    const int bandRows = std::max(1, (256 * 1024) / int(sizeof(glm::vec4)) / std::max(image.width, 1));
    std::vector<glm::vec4> rgba(std::size_t(bandRows) * std::size_t(image.width));
    for (int row = firstRow; row < firstRow + rowCount; row += bandRows) {
        const int count = std::min(bandRows, firstRow + rowCount - row);
        const float* source = image.texels.data() + std::size_t(row) * std::size_t(image.width) * 3;
        for (std::size_t i = 0; i < std::size_t(count) * std::size_t(image.width); ++i)
            rgba[i] = glm::vec4(source[3 * i], source[3 * i + 1], source[3 * i + 2], 1.0f);
        glTextureSubImage2D(texture.id(), 0, 0, row, image.width, count, GL_RGBA, GL_FLOAT, rgba.data());
    }
}

void BakePasses::finishEquirect(const gl::Texture& texture, const ImageRGB32F& image, int levels)
{
    downsampleChain(texture.id(), GL_TEXTURE_2D, GL_RGBA32F, image.width, image.height, equirectLevels(image, levels));
}

gl::Texture BakePasses::uploadEquirect(const ImageRGB32F& image, int levels)
{
    gl::Texture texture = createEquirect(image, levels);
    uploadEquirectRows(texture, image, levels, 0, image.height);
    finishEquirect(texture, image, levels);
    return texture;
}

} // namespace iblab::bake
