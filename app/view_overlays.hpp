#pragma once
// Text drawn over the 3D view (grid axis labels, furnace readings, debug-view labels and
// the texel readout), the same in the window and in headless PNGs.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "frame/renderer.hpp"

struct ImGuiContext;

namespace iblab::app {

// Adds the overlays of the current view to ImGui's background draw list (between NewFrame
// and Render). viewOrigin: the view's top-left in ImGui coordinates; mouseInView: the
// cursor in view pixels, y up, for the readout.
void drawViewOverlays(const Renderer& renderer, const FrameSettings& settings, int width, int height, glm::vec2 viewOrigin,
                      const std::vector<SphereReading>& furnaceReadings, std::optional<glm::vec2> mouseInView);

// Dear ImGui with no window: draws overlays into the renderer's display image, for PNGs
// written headless. Needs the GL context current for its whole life.
class OffscreenOverlay {
public:
    OffscreenOverlay();
    ~OffscreenOverlay();
    OffscreenOverlay(const OffscreenOverlay&) = delete;
    OffscreenOverlay& operator=(const OffscreenOverlay&) = delete;

    // Draws the view's overlays over the last frame's display image, and the caption's
    // lines (if any) at its top-left on a dark backdrop.
    void drawOver(Renderer& renderer, const FrameSettings& settings, int width, int height, const std::vector<std::string>& caption = {});
    // One ImGui frame of width x height: `build` adds to the draw lists (between NewFrame and
    // Render), `bindTarget` binds the framebuffer it is rendered into.
    void drawFrame(int width, int height, const std::function<void()>& build, const std::function<void()>& bindTarget);

private:
    ::ImGuiContext* context_ = nullptr;
};

} // namespace iblab::app
