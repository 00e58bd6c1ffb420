#include "gl/render_target.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

namespace iblab::gl {

namespace {

void requirePositiveSize(int width, int height)
{
    if (width <= 0 || height <= 0)
        throw std::invalid_argument("render target size must be positive, got " + std::to_string(width) + "x" + std::to_string(height));
}

void requireComplete(const Framebuffer& framebuffer, int width, int height)
{
    const GLenum status = glCheckNamedFramebufferStatus(framebuffer.id(), GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("render target " + std::to_string(width) + "x" + std::to_string(height) + " is incomplete (status 0x" +
                                 std::to_string(status) + ")");
}

// The most samples a renderbuffer of this format may have (GL lists the counts it supports
// in descending order); GL_MAX_SAMPLES bounds every format but some formats allow fewer.
int maxRenderbufferSamples(GLenum format)
{
    GLint count = 0;
    glGetInternalformativ(GL_RENDERBUFFER, format, GL_NUM_SAMPLE_COUNTS, 1, &count);
    if (count <= 0) return 1;
    std::vector<GLint> samples(static_cast<std::size_t>(count));
    glGetInternalformativ(GL_RENDERBUFFER, format, GL_SAMPLES, count, samples.data());
    return std::max(samples.front(), 1);
}

} // namespace

void RenderTarget::ensure(GLenum internalFormat, int width, int height, bool withDepth)
{
    if (texture_ && format_ == internalFormat && width_ == width && height_ == height && withDepth_ == withDepth) return;
    requirePositiveSize(width, height);
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
    requireComplete(framebuffer, width, height);
    texture_ = std::move(texture);
    framebuffer_ = std::move(framebuffer);
    depth_ = std::move(depth);
    withDepth_ = withDepth;
    format_ = internalFormat;
    width_ = width;
    height_ = height;
}

void MultisampleTarget::ensure(GLenum colourFormat, int width, int height, int samples)
{
    if (framebuffer_ && format_ == colourFormat && width_ == width && height_ == height && requested_ == samples) return;
    requirePositiveSize(width, height);
    constexpr GLenum kDepthFormat = GL_DEPTH_COMPONENT32F;
    const int allocated = std::clamp(samples, 1, std::min(maxRenderbufferSamples(colourFormat), maxRenderbufferSamples(kDepthFormat)));
    Renderbuffer colour = createRenderbuffer();
    glNamedRenderbufferStorageMultisample(colour.id(), allocated, colourFormat, width, height);
    // The depth buffer must have as many samples as the colour buffer, or the framebuffer
    // is incomplete: ask for what GL gave the colour.
    GLint colourSamples = 0;
    glGetNamedRenderbufferParameteriv(colour.id(), GL_RENDERBUFFER_SAMPLES, &colourSamples);
    Renderbuffer depth = createRenderbuffer();
    glNamedRenderbufferStorageMultisample(depth.id(), colourSamples, kDepthFormat, width, height);
    Framebuffer framebuffer = createFramebuffer();
    glNamedFramebufferRenderbuffer(framebuffer.id(), GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour.id());
    glNamedFramebufferRenderbuffer(framebuffer.id(), GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth.id());
    requireComplete(framebuffer, width, height);
    framebuffer_ = std::move(framebuffer);
    colour_ = std::move(colour);
    depth_ = std::move(depth);
    format_ = colourFormat;
    requested_ = samples;
    samples_ = std::max(int(colourSamples), 1);
    width_ = width;
    height_ = height;
}

void MultisampleTarget::resolveInto(const RenderTarget& target) const
{
    if (target.width() != width_ || target.height() != height_)
        throw std::invalid_argument("MSAA resolve into a target of another size: " + std::to_string(target.width()) + "x" +
                                    std::to_string(target.height()) + " from " + std::to_string(width_) + "x" + std::to_string(height_));
    // The blit honours the scissor test: a frame that ended scissored would resolve a part.
    glDisable(GL_SCISSOR_TEST);
    glBlitNamedFramebuffer(framebuffer_.id(), target.framebuffer(), 0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

} // namespace iblab::gl
