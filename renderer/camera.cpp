#include "camera.hpp"

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

glm::mat4 cameraProjection(const CameraSettings& camera, float aspect)
{
    const float fov = glm::radians(std::clamp(camera.fovDegrees, 1.0f, 170.0f));
    return glm::perspective(fov, aspect, 0.01f, 100.0f);
}

} // namespace iblab
