#include "gl/render_target.hpp"

#include <stdexcept>
#include <string>

namespace iblab::gl {

void RenderTarget::ensure(GLenum internalFormat, int width, int height, bool withDepth)
{
    if (texture_ && format_ == internalFormat && width_ == width && height_ == height && withDepth_ == withDepth) return;
    if (width <= 0 || height <= 0)
        throw std::invalid_argument("render target size must be positive, got " + std::to_string(width) + "x" + std::to_string(height));
    Texture texture = createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(texture.id(), 1, internalFormat, width, height);
    glTextureParameteri(texture.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(texture.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    Framebuffer framebuffer = createFramebuffer();
    glNamedFramebufferTexture(framebuffer.id(), GL_COLOR_ATTACHMENT0, texture.id(), 0);
    Renderbuffer depth;
    if (withDepth) {
        depth = createRenderbuffer();
        glNamedRenderbufferStorage(depth.id(), GL_DEPTH_COMPONENT32F, width, height);
        glNamedFramebufferRenderbuffer(framebuffer.id(), GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth.id());
    }
    const GLenum status = glCheckNamedFramebufferStatus(framebuffer.id(), GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("render target " + std::to_string(width) + "x" + std::to_string(height) + " is incomplete (status 0x" +
                                 std::to_string(status) + ")");
    texture_ = std::move(texture);
    framebuffer_ = std::move(framebuffer);
    depth_ = std::move(depth);
    withDepth_ = withDepth;
    format_ = internalFormat;
    width_ = width;
    height_ = height;
}

} // namespace iblab::gl
