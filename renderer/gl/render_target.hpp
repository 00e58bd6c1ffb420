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

} // namespace iblab::gl
