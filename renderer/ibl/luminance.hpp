#pragma once
// Rec. 709 / sRGB luminance of linear RGB: what the bake's bright-texel split and the shading
// lights rank texels by.
#include <glm/vec3.hpp>

namespace iblab {

inline float luminance(glm::vec3 c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

} // namespace iblab
