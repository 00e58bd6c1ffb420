#include "gl/texture_upload.hpp"

#include <algorithm>
#include <cmath>

namespace iblab::gl {

Texture createMipmappedTexture2D(const Texture2DUpload& upload)
{
    const int levels = 1 + int(std::floor(std::log2(double(std::max(upload.width, upload.height)))));
    Texture texture = createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(texture.id(), levels, upload.internalFormat, upload.width, upload.height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, upload.unpackAlignment);
    glTextureSubImage2D(texture.id(), 0, 0, 0, upload.width, upload.height, upload.format, upload.type, upload.pixels);
    glGenerateTextureMipmap(texture.id());
    glTextureParameteri(texture.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(texture.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_S, GLint(upload.wrapS));
    glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_T, GLint(upload.wrapT));
    return texture;
}

} // namespace iblab::gl
