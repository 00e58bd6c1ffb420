#pragma once
#include <epoxy/gl.h>

#include "gl/handles.hpp"

namespace iblab::gl {

// A single-level colour texture with its framebuffer, reallocated only when the format
// or size changes (window resizes happen every frame while dragging a corner).
class RenderTarget {
public:
    // withDepth adds a 32-bit float depth renderbuffer (the mesh passes need one).
    void ensure(GLenum internalFormat, int width, int height, bool withDepth = false);
    GLuint texture() const { return texture_.id(); }
    GLuint framebuffer() const { return framebuffer_.id(); }
    int width() const { return width_; }
    int height() const { return height_; }

private:
    Texture texture_;
    Framebuffer framebuffer_;
    Renderbuffer depth_;
    GLenum format_ = 0;
    bool withDepth_ = false;
    int width_ = 0;
    int height_ = 0;
};

// A multisampled colour + depth framebuffer, drawn into and then resolved into a
// RenderTarget: renderbuffers, because nothing samples it. Reallocated only when the
// format, size or sample count changes.
class MultisampleTarget {
public:
    // samples above what the driver supports for these formats are clamped to it; GL may
    // allocate more than asked (the next count it supports), which samples() reports.
    void ensure(GLenum colourFormat, int width, int height, int samples);
    // Averages each pixel's samples into target's texture, which must have this size.
    void resolveInto(const RenderTarget& target) const;
    GLuint framebuffer() const { return framebuffer_.id(); }
    int samples() const { return samples_; }

private:
    Framebuffer framebuffer_;
    Renderbuffer colour_;
    Renderbuffer depth_;
    GLenum format_ = 0;
    int requested_ = 0;
    int samples_ = 0;
    int width_ = 0;
    int height_ = 0;
};

} // namespace iblab::gl
