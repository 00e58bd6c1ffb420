#pragma once
// Opens a scope in which a shared .glsl file compiles as C++: glm provides the GLSL
// vocabulary (vec3, mat3, clamp, atan(y, x), ...), and IBL_FN makes its functions inline.
// Usage, in namespace iblab::shared only:
//   #include "ibl/glsl_shared.hpp"
//   namespace iblab::shared { #include "common/tonemap.glsl" }
#include <glm/glm.hpp>

#ifndef IBL_FN
#define IBL_FN inline
#endif

namespace iblab::shared {
using namespace glm;
}
