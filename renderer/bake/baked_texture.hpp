#pragma once
// A baked GL texture with what it takes to describe it (target, format, size, levels), and
// the CPU images it reads back into and uploads from. Internal layer: includes GL handles.
#include <array>
#include <cstddef>
#include <memory>
#include <vector>

#include <epoxy/gl.h>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "gl/handles.hpp"

namespace iblab::bake {

struct BakedTexture {
    gl::Texture texture;
    GLenum target = 0;         // GL_TEXTURE_CUBE_MAP or GL_TEXTURE_2D
    GLenum internalFormat = 0; // GL_RGBA16F or GL_RGBA32F
    int size = 0;              // edge of level 0 (a cube face, or the square LUT)
    int levels = 0;

    explicit operator bool() const { return bool(texture); }
    GLuint id() const { return texture.id(); }
    int levelSize(int level) const { return size >> level > 0 ? size >> level : 1; }
    // GPU memory of all levels and faces, from the format and the sizes.
    std::size_t bytes() const;
};

std::size_t bytesPerTexel(GLenum internalFormat);
// The GLSL image format qualifier of a baked texture's format (a shader's FORMAT define).
inline const char* imageFormatName(GLenum internalFormat) { return internalFormat == GL_RGBA16F ? "rgba16f" : "rgba32f"; }

// Immutable storage for a cube map / 2D texture, linear filtering (trilinear when levels > 1)
// and clamped edges.
BakedTexture createCubeTexture(GLenum internalFormat, int faceSize, int levels);
BakedTexture create2DTexture(GLenum internalFormat, int size);

// One level of a cube map in CPU memory: RGBA float, faces in GL order, each face row-major
// with row 0 = the first row GL stores (face-local t = 0).
struct CubeImage {
    int size = 0;
    std::vector<glm::vec4> texels; // [(face * size + row) * size + x]

    CubeImage() = default;
    explicit CubeImage(int faceSize) : size(faceSize), texels(std::size_t(6) * std::size_t(faceSize) * std::size_t(faceSize)) {}
    std::size_t index(int face, int x, int row) const
    {
        return (std::size_t(face) * std::size_t(size) + std::size_t(row)) * std::size_t(size) + std::size_t(x);
    }
    glm::vec4& at(int face, int x, int row) { return texels[index(face, x, row)]; }
    const glm::vec4& at(int face, int x, int row) const { return texels[index(face, x, row)]; }
    glm::vec3 rgb(int face, int x, int row) const { return glm::vec3(at(face, x, row)); }
    // The direction through the centre of texel (x, row) of a face (conventions.glsl).
    glm::vec3 texelDirection(int face, int x, int row) const;
    // The texel whose footprint contains direction d (nearest texel, no filtering).
    glm::vec3 nearest(glm::vec3 direction) const;
};

// A square 2D image (the LUT), RGBA float, row 0 = the first row GL stores.
struct Image2D {
    int size = 0;
    std::vector<glm::vec4> texels; // [row * size + x]
    const glm::vec4& at(int x, int row) const { return texels[std::size_t(row) * std::size_t(size) + std::size_t(x)]; }
};

// One level of a cube map as the texture stores it: RGBA, half floats (RGBA16F) or floats
// (RGBA32F), in CubeImage's order. The cache's files are written from it with no
// conversion (a float read-back of a half texture, converted back to half for the file,
// cost more than the rest of the write).
struct StoredCubeLevel {
    int size = 0;
    GLenum internalFormat = 0;
    std::unique_ptr<std::byte[]> bytes; // 6 size^2 texels of bytesPerTexel(internalFormat)
    std::size_t byteCount() const { return std::size_t(6) * std::size_t(size) * std::size_t(size) * bytesPerTexel(internalFormat); }
};

// Read-backs make earlier shader image stores visible first (glMemoryBarrier).
CubeImage readCubeLevel(const BakedTexture& texture, int level);
StoredCubeLevel readStoredCubeLevel(const BakedTexture& texture, int level);
Image2D read2D(const BakedTexture& texture);
void uploadCubeLevel(const BakedTexture& texture, int level, const CubeImage& image);
// In the texture's own format (the stored level's): a copy, no conversion.
void uploadStoredCubeLevel(const BakedTexture& texture, int level, const StoredCubeLevel& stored);
void upload2D(const BakedTexture& texture, const Image2D& image);
// Rows [firstRow, firstRow + rowCount) of faces [firstFace, firstFace + faceCount) of a
// level of `from` into the same texels of a level of `to`, of the same size and format.
void copyCubeRows(const BakedTexture& from, int fromLevel, const BakedTexture& to, int toLevel, int firstFace, int faceCount,
                  int firstRow, int rowCount);

} // namespace iblab::bake
