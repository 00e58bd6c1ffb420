#pragma once
#include <string>

namespace iblab::gl {
// "llvmpipe (LLVM 15.0.6, 256 bits), OpenGL 4.5 (Core Profile) Mesa 22.3.6"; needs a current context.
std::string describeCurrentContext();
// Throws ContextError naming the first missing requirement (version, extension, limit).
void requireCurrentContextFeatures();
}
