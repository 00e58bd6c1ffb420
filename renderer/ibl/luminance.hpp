#pragma once
// Rec. 709 / sRGB luminance of linear RGB: what the bake's bright-texel split and the shading
// lights rank texels by, the loader's negative-light check weighs and the GUI's probes show.
// The shaders' copy is assets/shaders/common/luminance.glsl (held equal by
// bake_shared_glsl_gltest's LuminanceAgreesWithCore).
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace iblab {

inline constexpr glm::dvec3 kLuminanceWeights{0.2126, 0.7152, 0.0722};

inline float luminance(glm::vec3 c) { return glm::dot(c, glm::vec3(kLuminanceWeights)); }
inline double luminance(glm::dvec3 c) { return glm::dot(c, kLuminanceWeights); }
// Three floats in a row (an RGB texel of ImageRGB32F).
inline float luminance(const float* rgb) { return luminance(glm::vec3(rgb[0], rgb[1], rgb[2])); }

} // namespace iblab
