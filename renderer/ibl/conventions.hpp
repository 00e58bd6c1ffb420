#pragma once
// C++ view of assets/shaders/common/conventions.glsl: the very same source, so the GPU
// and the CPU cannot disagree on where a direction lands (tests/gl pins it anyway).
#include "ibl/glsl_shared.hpp"

namespace iblab::shared {
#include "common/conventions.glsl"
}

namespace iblab {
using shared::cubeFaceUvToDirection;
using shared::directionToCubeFaceUv;
using shared::directionToEquirectUv;
using shared::equirectUvToDirection;
using shared::rotateAboutY;
inline constexpr double kPi = 3.14159265358979323846;
}
