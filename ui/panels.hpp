#pragma once
// Dear ImGui panels. Each edits a plain settings struct and records what the user asked
// for in UiRequests; the app acts on the requests and the renderer reads the structs.
// Nothing here issues GL calls.
#include <optional>
#include <string>
#include <vector>

#include "settings.hpp"

namespace iblab::ui {

struct EnvironmentCatalog {
    std::vector<std::string> gallery;  // bundled files
    std::vector<std::string> builtins; // "builtin:white", ...
};

struct StatusLine {
    std::string text;
    bool isError = false;
};

struct FrameStats {
    double frameMs = 0.0;  // wall clock of the whole frame, CPU side
    double renderMs = 0.0; // our passes, measured with glFinish when profiling is on
    int width = 0;
    int height = 0;
    std::string renderer; // GL renderer string
};

struct UiRequests {
    std::optional<std::string> loadEnvironment; // a path or builtin:NAME
    std::optional<std::string> captureTo;       // a .png or .exr path
};

struct CaptureSettings {
    char path[512] = "iblab-capture.png";
};

struct PanelState {
    EnvironmentCatalog catalog;
    StatusLine environmentStatus;
    StatusLine captureStatus;
    CaptureSettings capture;
    char environmentPath[512] = "";
    bool showPanels = true;
};

void drawEnvironmentPanel(EnvironmentSettings& settings, PanelState& state, UiRequests& requests);
void drawToneMapPanel(ToneMapSettings& settings);
void drawCameraPanel(CameraSettings& settings);
void drawCapturePanel(PanelState& state, UiRequests& requests);
void drawStatsOverlay(const FrameStats& stats);

// The full control window with all of the above, docked at the left.
void drawControlWindow(FrameSettings& settings, PanelState& state, const FrameStats& stats, UiRequests& requests);

} // namespace iblab::ui
