#pragma once
#include <epoxy/gl.h>

#include "gl/handles.hpp"

namespace iblab::gl {

struct Texture2DUpload {
    GLenum internalFormat = GL_RGBA8;
    int width = 0;
    int height = 0;
    GLenum format = GL_RGBA;     // of `pixels`
    GLenum type = GL_UNSIGNED_BYTE;
    const void* pixels = nullptr; // row 0 becomes GL row 0 (t = 0)
    int unpackAlignment = 1;
    GLenum wrapS = GL_REPEAT;
    GLenum wrapT = GL_REPEAT;
};

// Immutable storage with a full mip chain, trilinear filtering: environments and model
// textures are both minified at a distance.
Texture createMipmappedTexture2D(const Texture2DUpload& upload);

} // namespace iblab::gl
