#pragma once
// Seamless filtering across cube faces (GL 4.5 core, global state): without it a texel near a
// face edge is clamped to its own face, and the blurred mips show their seams. Turned on for
// a pass and restored after it.
#include <epoxy/gl.h>

namespace iblab::gl {

class SeamlessCubeScope {
public:
    SeamlessCubeScope() : wasEnabled_(glIsEnabled(GL_TEXTURE_CUBE_MAP_SEAMLESS) == GL_TRUE) { glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS); }
    ~SeamlessCubeScope()
    {
        if (!wasEnabled_)
            glDisable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    }
    SeamlessCubeScope(const SeamlessCubeScope&) = delete;
    SeamlessCubeScope& operator=(const SeamlessCubeScope&) = delete;

private:
    bool wasEnabled_;
};

} // namespace iblab::gl
