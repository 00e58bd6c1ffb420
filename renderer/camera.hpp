#pragma once
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "settings.hpp"

namespace iblab {

// The orbit camera's unit forward vector: -Z at yaw = pitch = 0, towards +X for positive
// yaw, up for positive pitch.
glm::vec3 cameraForward(const CameraSettings& camera);
glm::mat4 cameraView(const CameraSettings& camera);
glm::vec3 cameraPosition(const CameraSettings& camera);
glm::mat4 cameraProjection(const CameraSettings& camera, float aspect);

} // namespace iblab
