#pragma once
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "frame/settings.hpp"

namespace iblab {

// The orbit camera's unit forward vector: -Z at yaw = pitch = 0, towards +X for positive
// yaw, up for positive pitch.
glm::vec3 cameraForward(const CameraSettings& camera);
glm::mat4 cameraView(const CameraSettings& camera);
glm::vec3 cameraPosition(const CameraSettings& camera);
glm::mat4 cameraProjection(const CameraSettings& camera, float aspect);
// Where a clip-space point lands in a width x height frame, in pixels (y up).
glm::vec2 clipToPixel(const glm::vec4& clip, int width, int height);

// Aims the camera at the centre of a bounding box and backs off until the box fills the
// view with a margin, keeping yaw, pitch and field of view (double-click, a new scene,
// --distance 0).
void frameBox(CameraSettings& camera, glm::vec3 centre, glm::vec3 halfExtents, float aspect);

// Moves the target (and the camera with it) in the view plane by a drag of dragPixels
// (x right, y down) across a view viewHeight pixels tall, so that what lies at the target's
// depth follows the cursor.
void panCamera(CameraSettings& camera, glm::vec2 dragPixels, float viewHeight);

// The axis views: front looks down -Z, side down -X (from +X), top down -Y; the target and
// distance stay.
enum class CameraAxisView { Front, Side, Top };
void setAxisView(CameraSettings& camera, CameraAxisView view);

} // namespace iblab
