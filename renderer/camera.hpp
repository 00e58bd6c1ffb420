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

// Aims the camera at the centre of a bounding box and backs off until the box fills the
// view with a margin, keeping yaw, pitch and field of view (double-click, a new scene,
// --distance 0).
void frameBox(CameraSettings& camera, glm::vec3 centre, glm::vec3 halfExtents, float aspect);

} // namespace iblab
