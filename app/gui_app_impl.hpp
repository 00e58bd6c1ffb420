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
#include "loaded_model.hpp"
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

// How the loop goes on after a frame, as that frame found things.
enum class LoopPace {
    Working,     // something computes or refines: the next frame comes at once
    HeldForLoad, // the frame drew nothing new while a map may decode: the next one waits for
                 // the decode, a 60 Hz frame at most, rather than taking its CPU
    Idle,        // nothing to compute until the next input (what scripts wait for); frames go
                 // on for a hovered control's tooltip or a text field's caret
    IdleAsleep,  // idle, and nothing hovered or typed into: the loop sleeps until input
};

// The camera's framing at the start (no --distance): once the first bake is in, since the
// scene's bounds come with it.
enum class StartFraming {
    Done,              // framed, or --distance given
    WhenBaked,         // keeping the --yaw / --pitch given
    WhenBakedFromHome, // from the scene's home view (a model's front), as no --yaw or --pitch was given
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
    LoadedModel model;
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
    std::optional<Clock::time_point> presented; // the last frame's present, for the session's switch timing
    StartFraming startFraming = StartFraming::Done;
    LoopPace pace = LoopPace::Working;
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
    void loadModel(const std::string& path);
    void actOn(ui::UiRequests& requests, int viewWidth, int viewHeight);
    void frameCamera(ui::UiRequests& requests, int viewWidth, int viewHeight);

    void frame();
    ViewArea viewArea() const;
    void pumpBackground(bool inputArrived);
    ui::UiRequests drawUi(const FrameRequests& frameInput, const ViewArea& area);
    void renderView(const ViewArea& area, bool interacting);
    void present(int windowWidth, int windowHeight, int viewX);
};

} // namespace iblab::app
