#include "frame/texture_readback.hpp"

namespace iblab {

FrameReadback readFloatTexture(GLuint texture, int width, int height)
{
    FrameReadback result{width, height, {}};
    result.rgba.resize(std::size_t(width) * std::size_t(height) * 4);
    glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, GLsizei(result.rgba.size() * sizeof(float)), result.rgba.data());
    return result;
}

DisplayReadback readByteTexture(GLuint texture, int width, int height)
{
    DisplayReadback result{width, height, {}};
    result.rgba.resize(std::size_t(width) * std::size_t(height) * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1); // rows of any width, tightly packed
    glGetTextureImage(texture, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(result.rgba.size()), result.rgba.data());
    return result;
}

} // namespace iblab
