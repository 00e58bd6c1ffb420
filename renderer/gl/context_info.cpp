#include "gl/context_info.hpp"

#include <epoxy/gl.h>

#include "gl/context_error.hpp"

namespace iblab::gl {

std::string describeCurrentContext()
{
    auto str = [](GLenum name) {
        const auto* s = reinterpret_cast<const char*>(glGetString(name));
        return std::string(s ? s : "?");
    };
    return str(GL_RENDERER) + ", OpenGL " + str(GL_VERSION);
}

void requireCurrentContextFeatures()
{
    const int version = epoxy_gl_version();
    if (version < 45)
        throw ContextError("OpenGL 4.5 is required, the driver gives " + std::to_string(version / 10) + "." +
                           std::to_string(version % 10) + " (" + describeCurrentContext() + ")");
    // Seamless filtering across cube faces is core since 3.2; checked for drivers that lie.
    GLint maxCubeSize = 0;
    glGetIntegerv(GL_MAX_CUBE_MAP_TEXTURE_SIZE, &maxCubeSize);
    if (maxCubeSize < 1024)
        throw ContextError("the GL driver's cube maps are limited to " + std::to_string(maxCubeSize) + " texels, iblab needs 1024");
}

} // namespace iblab::gl
