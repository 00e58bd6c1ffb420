#pragma once
// Mouse input on the 3D view rather than on a control: the camera's orbit, pan, zoom and
// framing, and the split view's divider.
#include <imgui.h>

#include "frame/settings.hpp"
#include "ui/panels.hpp"

namespace iblab::app {

// Left drag orbits; right or middle drag, or Shift + left drag, pans; the wheel zooms
// (multiplicatively, so it feels the same at any distance); a double-click frames the scene.
struct CameraInput {
    void update(CameraSettings& camera, const ImGuiIO& io, float viewHeight, ui::UiRequests& requests);
};

// The split view's divider follows the mouse when grabbed within a few pixels of it; while
// it is held, the drag does not orbit the camera.
struct SplitDividerInput {
    bool held = false;
    // Returns true while the divider is being dragged.
    bool update(ViewSettings& view, const ImGuiIO& io, int viewX, int viewWidth);
};

} // namespace iblab::app
