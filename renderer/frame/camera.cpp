#include "frame/camera.hpp"

#include <algorithm>

#include <glm/gtc/matrix_transform.hpp>

namespace iblab {

glm::vec3 cameraForward(const CameraSettings& camera)
{
    const float yaw = glm::radians(camera.yawDegrees);
    // Clamped short of the poles, where lookAt's up vector would be parallel to forward.
    const float pitch = glm::radians(std::clamp(camera.pitchDegrees, -89.5f, 89.5f));
    return {std::sin(yaw) * std::cos(pitch), std::sin(pitch), -std::cos(yaw) * std::cos(pitch)};
}

glm::vec3 cameraPosition(const CameraSettings& camera) { return camera.target - cameraForward(camera) * camera.distance; }

glm::mat4 cameraView(const CameraSettings& camera)
{
    return glm::lookAt(cameraPosition(camera), camera.target, glm::vec3(0.0f, 1.0f, 0.0f));
}

ClipPlanes clipPlanesFor(const CameraSettings& camera, glm::vec3 centre, float radius)
{
    // 2% slack on either side keeps the sphere's own surface from being clipped by rounding.
    // The depth buffer is 32-bit float; a far / near ratio up to 1e4 keeps depth steps
    // far below any scene's detail, and the near plane never reaches the camera.
    constexpr float kMaxRatio = 1e4f;
    radius = std::max(radius, 1e-6f);
    const float toCentre = glm::length(cameraPosition(camera) - centre);
    const float farPlane = 1.02f * (toCentre + radius);
    const float nearPlane = std::max(0.98f * (toCentre - radius), farPlane / kMaxRatio);
    return {nearPlane, farPlane};
}

glm::mat4 cameraProjection(const CameraSettings& camera, float aspect, ClipPlanes planes)
{
    const float fov = glm::radians(std::clamp(camera.fovDegrees, 1.0f, 170.0f));
    return glm::perspective(fov, aspect, planes.nearPlane, planes.farPlane);
}

glm::vec2 clipToPixel(const glm::vec4& clip, int width, int height)
{
    return (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(width, height);
}

void frameBox(CameraSettings& camera, glm::vec3 centre, glm::vec3 halfExtents, float aspect)
{
    // The box's half extent along the camera's right, up and forward axes (the support of
    // an axis-aligned box along a direction is the dot product with |direction|). It fits
    // when, at the distance of its near face, both half extents are within the half field
    // of view; 8% margin keeps silhouettes off the frame's edge.
    const glm::vec3 forward = cameraForward(camera);
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0.0f, 1.0f, 0.0f)));
    const glm::vec3 up = glm::cross(right, forward);
    const float halfRight = glm::dot(glm::abs(right), halfExtents);
    const float halfUp = glm::dot(glm::abs(up), halfExtents);
    const float halfDepth = glm::dot(glm::abs(forward), halfExtents);
    const float tanVertical = std::tan(0.5f * glm::radians(std::clamp(camera.fovDegrees, 1.0f, 170.0f)));
    const float tanHorizontal = tanVertical * aspect;
    camera.target = centre;
    camera.distance = 1.08f * std::max(halfRight / tanHorizontal, halfUp / tanVertical) + halfDepth;
}

void frameSphere(CameraSettings& camera, glm::vec3 centre, float radius, float aspect)
{
    // The sphere's angular radius, asin(r / d), is within the half field of view of the
    // narrower axis; 15% margin leaves air around the model as a viewer does.
    constexpr float kMargin = 1.15f;
    const float tanVertical = std::tan(0.5f * glm::radians(std::clamp(camera.fovDegrees, 1.0f, 170.0f)));
    const float halfAngle = std::atan(std::min(tanVertical, tanVertical * aspect));
    camera.target = centre;
    camera.distance = kMargin * std::max(radius, 1e-6f) / std::sin(halfAngle);
}

void frameScene(CameraSettings& camera, glm::vec3 centre, glm::vec3 halfExtents, bool model, float aspect)
{
    if (model) frameSphere(camera, centre, glm::length(halfExtents), aspect);
    else frameBox(camera, centre, halfExtents, aspect);
}

void homeView(CameraSettings& camera, bool model)
{
    const CameraSettings defaults;
    camera.yawDegrees = model ? -35.0f : defaults.yawDegrees;
    camera.pitchDegrees = model ? -25.0f : defaults.pitchDegrees;
    camera.fovDegrees = defaults.fovDegrees;
}

void panCamera(CameraSettings& camera, glm::vec2 dragPixels, float viewHeight)
{
    const glm::vec3 forward = cameraForward(camera);
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0.0f, 1.0f, 0.0f)));
    const glm::vec3 up = glm::cross(right, forward);
    // World units per pixel in the plane through the target, facing the camera.
    const float unitsPerPixel = 2.0f * camera.distance * std::tan(0.5f * glm::radians(camera.fovDegrees)) / std::max(viewHeight, 1.0f);
    camera.target += unitsPerPixel * (-dragPixels.x * right + dragPixels.y * up);
}

void setAxisView(CameraSettings& camera, CameraAxisView view)
{
    // Pitch stops short of 90 degrees, where the orbit's up vector would be undefined.
    switch (view) {
    case CameraAxisView::Front: camera.yawDegrees = 0.0f; camera.pitchDegrees = 0.0f; break;
    case CameraAxisView::Side: camera.yawDegrees = -90.0f; camera.pitchDegrees = 0.0f; break;
    case CameraAxisView::Top: camera.yawDegrees = 0.0f; camera.pitchDegrees = -89.0f; break;
    }
}

} // namespace iblab
