#pragma once
// The moment irradiance's groups (moment_texel.glsl's MomentTexel, irradiance_moments.comp)
// summed over the map's own texels rather than over the environment cube's. The cube is the
// map resampled, which keeps a small source's radiance but not its flux: a 0.5 degree sun was
// 0.97 of its flux in a 256 cube at 45 degrees of elevation, 1.24 at the zenith and 0.87 at
// 89 degrees (the clamped bilinear read at the pole, and a sun smaller than a cube texel
// caught between texel centres), and the diffuse of every shading method with it. Each texel
// of the map goes to the group its centre's direction falls in, with its exact solid angle: a
// group's flux and moments are the map's, wherever in the group its light is.
#include <vector>

#include <glm/vec4.hpp>

#include "ibl/image.hpp"

namespace iblab::bake {

// 6 groupsPerEdge^2 groups, kMomentTexelVec4s (6) vec4 each, in irradiance_moments.comp's
// order ((face * groupsPerEdge + row) * groupsPerEdge + column); the map's rows are summed in
// eight bands, on threads, and the bands added in order, so the result does not depend on the
// thread count.
std::vector<glm::vec4> equirectMomentTexels(const ImageRGB32F& map, int groupsPerEdge);

} // namespace iblab::bake
