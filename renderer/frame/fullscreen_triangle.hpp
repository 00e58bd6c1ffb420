#pragma once
// One triangle over the whole viewport, for the full-screen passes (fullscreen.vert makes
// its corners from gl_VertexID, so it needs an empty vertex array and no buffer).
#include <epoxy/gl.h>

#include "gl/handles.hpp"

namespace iblab {

class FullscreenTriangle {
public:
    void draw() const
    {
        glBindVertexArray(vertexArray_.id());
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }

private:
    gl::VertexArray vertexArray_ = gl::createVertexArray();
};

} // namespace iblab
