#pragma once
// What the GUI draws over the rendered view (ImGui draw lists, no GL): frame statistics,
// labels of debug tiles and scene axes, furnace readings, the error legend, the reference's
// progress and the split divider.
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "ui/panels.hpp"

namespace iblab::ui {

void drawStatsOverlay(const FrameStats& stats);

// A text the overlays drew over the view, with its rectangle in window pixels (y down).
struct OverlayText {
    std::string text;
    float x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};
// The overlays' texts since clearOverlayTexts(), which the view's overlays call first each
// frame: what scripts check (a label cut off at the view's edge, a number with no caption).
const std::vector<OverlayText>& overlayTexts();
void clearOverlayTexts();

// Labels of the debug view's tiles (rects y up, in framebuffer pixels), unit axes on each
// tile when `axes` (the LUTs), and the readout of the texel under the cursor.
void drawDebugOverlay(const std::vector<DebugTile>& tiles, bool axes, glm::vec2 viewOrigin, float viewHeight, const std::string& probeText);

// Text anchored in the scene (the grid's axes), projected by the renderer.
void drawSceneLabels(const std::vector<ScreenLabel>& labels, glm::vec2 viewOrigin, float viewHeight);

// The furnace view's numbers: reflected radiance (1 = all energy) over each sphere.
void drawSphereReadings(const std::vector<SphereReading>& readings, glm::vec2 viewOrigin, float viewHeight);

// The error view's colour bar with its numeric scale, at the bottom right of the view.
void drawErrorLegend(const ViewSettings& view, glm::vec2 viewOrigin, glm::vec2 viewSize);
// The reference's progress while the view waits for it (the error view) or builds it (the
// reference method), at the top of the view; `meanwhile` says what shows until then.
void drawReferenceProgress(const ReferenceStatus& status, const char* meanwhile, glm::vec2 viewOrigin, glm::vec2 viewSize);
// The split view's divider at pixel column `column` and what each side shows.
void drawSplitDivider(const FrameSettings& settings, int column, glm::vec2 viewOrigin, glm::vec2 viewSize);

} // namespace iblab::ui
