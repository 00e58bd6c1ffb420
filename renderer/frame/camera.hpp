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
// The near and far planes of the projection. The default suits a scene of unit size seen
// from a few units away; clipPlanesFor fits them to any scene.
struct ClipPlanes {
    float nearPlane = 0.01f;
    float farPlane = 100.0f;
};
// Planes that hold a scene inside the sphere (centre, radius) whatever its units and
// wherever the camera is: far just beyond the sphere's far side, near just before its near
// side, or a fixed fraction of far when the camera is inside it.
ClipPlanes clipPlanesFor(const CameraSettings& camera, glm::vec3 centre, float radius);
glm::mat4 cameraProjection(const CameraSettings& camera, float aspect, ClipPlanes planes = {});
// Where a clip-space point lands in a width x height frame, in pixels (y up).
glm::vec2 clipToPixel(const glm::vec4& clip, int width, int height);

// Aims the camera at the centre of a bounding box and backs off until the box fills the
// view with a margin, keeping yaw, pitch and field of view (double-click, a new scene,
// --distance 0).
void frameBox(CameraSettings& camera, glm::vec3 centre, glm::vec3 halfExtents, float aspect);
// Aims the camera at the centre of a sphere and backs off until the whole sphere fits the
// narrower field of view with a margin, keeping yaw, pitch and field of view: the framing
// of a model, which stays whole in view from any orbit angle.
void frameSphere(CameraSettings& camera, glm::vec3 centre, float radius, float aspect);
// Frames a scene: a loaded model by its bounding sphere, the lab's layouts (sphere, grid,
// strips), which are read from the front, tightly by their box.
void frameScene(CameraSettings& camera, glm::vec3 centre, glm::vec3 halfExtents, bool model, float aspect);
// The orientation a scene is first shown from (a new scene, Reset, a start that frames):
// a model from a three-quarter view above and to its right, where its depth shows; the
// lab's layouts from the front. The field of view returns to its default.
void homeView(CameraSettings& camera, bool model);

// Moves the target (and the camera with it) in the view plane by a drag of dragPixels
// (x right, y down) across a view viewHeight pixels tall, so that what lies at the target's
// depth follows the cursor.
void panCamera(CameraSettings& camera, glm::vec2 dragPixels, float viewHeight);

// The axis views: front looks down -Z, side down -X (from +X), top down -Y; the target and
// distance stay.
enum class CameraAxisView { Front, Side, Top };
void setAxisView(CameraSettings& camera, CameraAxisView view);

} // namespace iblab
