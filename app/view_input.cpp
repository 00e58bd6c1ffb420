#include "view_input.hpp"

#include <algorithm>
#include <cmath>

#include "frame/camera.hpp"
#include "frame/split_view.hpp"

namespace iblab::app {

void CameraInput::update(CameraSettings& camera, const ImGuiIO& io, float viewHeight, ui::UiRequests& requests)
{
    if (ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left)) requests.frameScene = true;
    const bool panning = ImGui::IsMouseDragging(ImGuiMouseButton_Right, 1.0f) || ImGui::IsMouseDragging(ImGuiMouseButton_Middle, 1.0f) ||
                         (io.KeyShift && ImGui::IsMouseDragging(ImGuiMouseButton_Left, 1.0f));
    if (panning) {
        panCamera(camera, glm::vec2(io.MouseDelta.x, io.MouseDelta.y), viewHeight);
    } else if (ImGui::IsMouseDragging(ImGuiMouseButton_Left, 1.0f)) {
        camera.yawDegrees -= io.MouseDelta.x * 0.3f;
        camera.pitchDegrees = std::clamp(camera.pitchDegrees + io.MouseDelta.y * 0.3f, -89.0f, 89.0f);
        camera.yawDegrees = std::remainder(camera.yawDegrees, 360.0f);
    }
    // Within the distance's range (frame/settings.cpp): a model in millimetres or in
    // kilometres zooms as far as one in metres.
    if (io.MouseWheel != 0.0f) camera.distance = std::clamp(camera.distance * std::pow(0.9f, io.MouseWheel), 1e-5f, 1e6f);
}

bool SplitDividerInput::update(ViewSettings& view, const ImGuiIO& io, int viewX, int viewWidth)
{
    if (!view.split || viewWidth <= 0) return held = false;
    constexpr float kGrabPixels = 6.0f;
    const float column = float(viewX + splitColumn(view, viewWidth));
    const bool near = std::abs(io.MousePos.x - column) <= kGrabPixels && io.MousePos.x >= float(viewX);
    if (near || held) ImGui::SetMouseCursor(ImGuiMouseCursor_ResizeEW);
    if (near && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) held = true;
    if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) held = false;
    if (held) view.splitPosition = std::clamp((io.MousePos.x - float(viewX)) / float(viewWidth), 0.0f, 1.0f);
    return held;
}

} // namespace iblab::app
