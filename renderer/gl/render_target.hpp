#pragma once
#include <epoxy/gl.h>

#include "gl/handles.hpp"

namespace iblab::gl {

// A single-level colour texture with its framebuffer, reallocated only when the format
// or size changes (window resizes happen every frame while dragging a corner).
class RenderTarget {
public:
    void ensure(GLenum internalFormat, int width, int height);
    GLuint texture() const { return texture_.id(); }
    GLuint framebuffer() const { return framebuffer_.id(); }
    int width() const { return width_; }
    int height() const { return height_; }

private:
    Texture texture_;
    Framebuffer framebuffer_;
    GLenum format_ = 0;
    int width_ = 0;
    int height_ = 0;
};

} // namespace iblab::gl
