#include "bake/baked_texture.hpp"

#include <algorithm>
#include <cmath>

#include "ibl/conventions.hpp"

namespace iblab::bake {

std::size_t bytesPerTexel(GLenum internalFormat)
{
    switch (internalFormat) {
    case GL_RGBA16F: return 8;
    case GL_RGBA32F: return 16;
    case GL_RGB32F: return 12;
    case GL_RGB16F: return 6;
    default: return 0;
    }
}

std::size_t BakedTexture::bytes() const
{
    if (!texture)
        return 0;
    const std::size_t faces = target == GL_TEXTURE_CUBE_MAP ? 6 : 1;
    std::size_t total = 0;
    for (int level = 0; level < levels; ++level) {
        const std::size_t s = std::size_t(levelSize(level));
        total += faces * s * s * bytesPerTexel(internalFormat);
    }
    return total;
}

BakedTexture createCubeTexture(GLenum internalFormat, int faceSize, int levels)
{
    BakedTexture t{gl::createTexture(GL_TEXTURE_CUBE_MAP), GL_TEXTURE_CUBE_MAP, internalFormat, faceSize, levels};
    glTextureStorage2D(t.id(), levels, internalFormat, faceSize, faceSize);
    glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
    glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(t.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t.id(), GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t.id(), GL_TEXTURE_MAX_LEVEL, levels - 1);
    return t;
}

BakedTexture create2DTexture(GLenum internalFormat, int size)
{
    BakedTexture t{gl::createTexture(GL_TEXTURE_2D), GL_TEXTURE_2D, internalFormat, size, 1};
    glTextureStorage2D(t.id(), 1, internalFormat, size, size);
    glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(t.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return t;
}

glm::vec3 CubeImage::texelDirection(int face, int x, int row) const
{
    return cubeFaceUvToDirection(face, glm::vec2((float(x) + 0.5f) / float(size), (float(row) + 0.5f) / float(size)));
}

glm::vec3 CubeImage::nearest(glm::vec3 direction) const
{
    const glm::vec3 fst = directionToCubeFaceUv(direction);
    const int x = std::clamp(int(std::floor(fst.y * float(size))), 0, size - 1);
    const int row = std::clamp(int(std::floor(fst.z * float(size))), 0, size - 1);
    return rgb(int(fst.x), x, row);
}

namespace {
void makeShaderWritesVisible()
{
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}
} // namespace

CubeImage readCubeLevel(const BakedTexture& texture, int level)
{
    makeShaderWritesVisible();
    CubeImage image(texture.levelSize(level));
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    // A cube map reads back as six layers in face order (GL 4.5, 8.11.4).
    glGetTextureImage(texture.id(), level, GL_RGBA, GL_FLOAT, GLsizei(image.texels.size() * sizeof(glm::vec4)),
                      image.texels.data());
    return image;
}

StoredCubeLevel readStoredCubeLevel(const BakedTexture& texture, int level)
{
    makeShaderWritesVisible();
    StoredCubeLevel stored{texture.levelSize(level), texture.internalFormat, nullptr};
    stored.bytes = std::make_unique_for_overwrite<std::byte[]>(stored.byteCount());
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(texture.id(), level, GL_RGBA, texture.internalFormat == GL_RGBA16F ? GL_HALF_FLOAT : GL_FLOAT,
                      GLsizei(stored.byteCount()), stored.bytes.get());
    return stored;
}

Image2D read2D(const BakedTexture& texture)
{
    makeShaderWritesVisible();
    Image2D image{texture.size, std::vector<glm::vec4>(std::size_t(texture.size) * std::size_t(texture.size))};
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(texture.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(image.texels.size() * sizeof(glm::vec4)), image.texels.data());
    return image;
}

void uploadCubeLevel(const BakedTexture& texture, int level, const CubeImage& image)
{
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureSubImage3D(texture.id(), level, 0, 0, 0, image.size, image.size, 6, GL_RGBA, GL_FLOAT, image.texels.data());
}

void uploadStoredCubeLevel(const BakedTexture& texture, int level, const StoredCubeLevel& stored)
{
    if (stored.internalFormat != texture.internalFormat || stored.size != texture.levelSize(level))
        throw std::invalid_argument("uploadStoredCubeLevel: a level of another format or size");
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureSubImage3D(texture.id(), level, 0, 0, 0, stored.size, stored.size, 6, GL_RGBA,
                        stored.internalFormat == GL_RGBA16F ? GL_HALF_FLOAT : GL_FLOAT, stored.bytes.get());
}

void upload2D(const BakedTexture& texture, const Image2D& image)
{
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureSubImage2D(texture.id(), 0, 0, 0, image.size, image.size, GL_RGBA, GL_FLOAT, image.texels.data());
}

void copyCubeRows(const BakedTexture& from, int fromLevel, const BakedTexture& to, int toLevel, int firstFace, int faceCount,
                  int firstRow, int rowCount)
{
    glCopyImageSubData(from.id(), GL_TEXTURE_CUBE_MAP, fromLevel, 0, firstRow, firstFace, to.id(), GL_TEXTURE_CUBE_MAP, toLevel, 0,
                       firstRow, firstFace, to.levelSize(toLevel), rowCount, faceCount);
}

} // namespace iblab::bake
