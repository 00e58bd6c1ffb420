#pragma once
// GuiApp's state, shared by its translation units: gui_app.cpp (start, input, the frame),
// gui_app_state.cpp (state() for scripts). Private to the app.
#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include <imgui.h>

#include "frame/renderer.hpp"
#include "frame_scheduler.hpp"
#include "gl/debug_output.hpp"
#include "gui_app.hpp"
#include "gui_input.hpp"
#include "lab_session.hpp"
#include "study_run.hpp"
#include "ui/panels.hpp"
#include "view_input.hpp"

namespace iblab::app {

// The ImGui context with our platform layer (gui_input.hpp) in place of imgui_impl_glfw,
// and the OpenGL3 renderer backend.
struct ImGuiSetup {
    ImGuiContext* context = nullptr;
    explicit ImGuiSetup(GuiPlatform& platform);
    ~ImGuiSetup();
    ImGuiSetup(const ImGuiSetup&) = delete;
    ImGuiSetup& operator=(const ImGuiSetup&) = delete;
};

// The part of the window right of the docked panel.
struct ViewArea {
    int x = 0, width = 0, height = 0;
};

struct GuiApp::Impl {
    using Clock = std::chrono::steady_clock;

    GuiPlatform& platform;
    GuiOptions options;
    gl::DebugOutput debug;
    ImGuiSetup imgui;
    Renderer renderer;
    FrameSettings settings;
    FrameSettings savedSettings; // as last saved or loaded: quitting asks before losing changes
    ui::PanelState panels;
    LabSession session;
    ui::FrameStats stats;
    ViewScheduler view; // what the 3D view renders each frame (frame_scheduler.hpp)
    InputQueue input;
    StudyRun study;
    CameraInput cameraInput;
    SplitDividerInput divider;
    // A screenshot of a frame that shows a reference waits until the reference is complete.
    std::optional<ui::CaptureRequest> pendingCapture;
    std::vector<SphereReading> furnaceReadings; // of the previous frame, printed over the spheres
    Clock::time_point start = Clock::now();
    Clock::time_point previousFrame = Clock::now();
    bool frameWhenReady = false;
    bool startsAtDefaultOrientation = true; // no --yaw or --pitch: a model starts from its home view
    bool isIdle = false;
    bool heldForLoad = false; // the last frame drew nothing new: a map decodes, nothing else runs
    bool sleepWhenIdle = false;
    bool scripted = false;
    bool quit = false;
    bool pixelsRequested = false;
    WindowPixels pixels;
    int framesShown = 0;
    long long viewImages = 0; // new images of the view put on screen
    // The environment status line as the panel drew it this frame, and as it was drawn beside
    // the first image of the environment on screen (scripts check they agree).
    std::string drawnEnvironmentStatus;
    struct FirstImage {
        std::string environment, status;
    } firstImageOfEnvironment;

    Impl(GuiPlatform& p, const GuiOptions& o);
    static bake::BakeSettings initialBake(const GuiOptions& o);

    bool unsavedChanges() const { return !(settings == savedSettings); }
    void rememberFrom(const std::optional<GuiPrefs>& remembered);
    void requestQuit();
    void handleShortcuts(const ImGuiIO& io, ui::UiRequests& requests);
    void capture(const ui::CaptureRequest& request);
    void actOn(ui::UiRequests& requests, int viewWidth, int viewHeight);
    void frameCamera(ui::UiRequests& requests, int viewWidth, int viewHeight);

    void frame();
    ViewArea viewArea() const;
    void pumpBackground();
    ui::UiRequests drawUi(const FrameRequests& frameInput, const ViewArea& area);
    void renderView(const ViewArea& area, bool interacting);
    void present(int windowWidth, int windowHeight, int viewX);
};

} // namespace iblab::app
