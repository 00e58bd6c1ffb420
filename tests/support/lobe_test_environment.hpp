#pragma once
// An outdoor-like map of the specular-lobe tests' own (no bundled map, which the lobe's fit
// saw): a sky brightening towards the zenith, a warm sun 25 degrees up, a dark ground and a
// bright vertical strip (a window) on one side, so that a lobe's position and width both
// matter. Shared by the CPU study's tests and the GPU frame's.
#include <cmath>

#include <glm/glm.hpp>

#include "ibl/equirect.hpp"

namespace iblab::testing {

inline ImageRGB32F lobeTestEnvironment(int width)
{
    const glm::dvec3 sun = glm::normalize(glm::dvec3(0.5, 0.42, -0.75));
    return paintEquirect(width, width / 2, [&](glm::dvec3 d) {
        glm::dvec3 L = d.y > 0.0 ? glm::dvec3(0.3, 0.45, 0.8) * (0.4 + 0.6 * d.y) : glm::dvec3(0.06, 0.05, 0.04);
        if (glm::dot(d, sun) > std::cos(glm::radians(6.0))) L += glm::dvec3(40.0, 32.0, 22.0);
        if (d.x < -0.8 && std::abs(d.y) < 0.4) L += glm::dvec3(3.0);
        return glm::vec3(L);
    });
}

} // namespace iblab::testing
