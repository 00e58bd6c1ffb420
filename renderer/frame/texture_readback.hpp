#pragma once
// Reads a whole single-level texture back into plain pixels (glGetTextureImage).
#include <epoxy/gl.h>

#include "frame/readback.hpp"

namespace iblab {

FrameReadback readFloatTexture(GLuint texture, int width, int height);  // RGBA float
DisplayReadback readByteTexture(GLuint texture, int width, int height); // RGBA 8-bit

} // namespace iblab
