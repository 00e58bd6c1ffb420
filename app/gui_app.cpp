#include "gui_app.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <epoxy/gl.h>
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_opengl3.h>
#include <imgui_internal.h>

#include "bake_export.hpp"
#include "asset_paths.hpp"
#include "command_support.hpp"
#include "frame/camera.hpp"
#include "frame/conventions.hpp"
#include "io/atomic_file.hpp"
#include "io/builtin_environments.hpp"
#include "io/error.hpp"
#include "gl/context_info.hpp"
#include "gl/debug_output.hpp"
#include "gl/pass_timer.hpp"
#include "gui_files.hpp"
#include "gui_script.hpp"
#include "lab_session.hpp"
#include "ui/panels.hpp"
#include "frame/renderer.hpp"
#include "frame/split_view.hpp"
#include "study_run.hpp"
#include "view_overlays.hpp"
#include "ui/widgets.hpp"

namespace iblab::app {
namespace {

using Clock = std::chrono::steady_clock;

// The error view's reference gets this much GPU time per frame while the view is idle.
constexpr auto kReferenceBudgetPerFrame = std::chrono::milliseconds(30);
// Background loading and baking get this much per frame: the UI stays near interactive
// rates on a software renderer.
constexpr auto kBackgroundBudgetPerFrame = std::chrono::milliseconds(30);
// Progressive refinement stops here: 64 rotated sample sets of any N are plenty to judge.
constexpr int kMaxAccumulatedFrames = 64;
// A scripted frame advances ImGui's clock by this much, whatever the frame took.
constexpr float kScriptedFrameSeconds = 1.0f / 30.0f;

#ifdef NDEBUG
constexpr bool kDebugContext = false;
#else
constexpr bool kDebugContext = true;
#endif

// The ImGui context with our platform layer (gui_input.hpp) in place of imgui_impl_glfw,
// and the OpenGL3 renderer backend.
struct ImGuiSetup {
    ImGuiContext* context = nullptr;
    explicit ImGuiSetup(GuiPlatform& platform)
    {
        IMGUI_CHECKVERSION();
        context = ImGui::CreateContext();
        ImGuiIO& io = ImGui::GetIO();
        io.IniFilename = nullptr; // no imgui.ini littering the working directory
        io.BackendPlatformName = "iblab";
        io.BackendFlags |= ImGuiBackendFlags_HasMouseCursors;
        mapGlfwKeys(io);
        io.ClipboardUserData = &platform;
        io.GetClipboardTextFn = [](void* user) {
            static std::string text; // ImGui copies it before the next call
            text = static_cast<GuiPlatform*>(user)->clipboard();
            return text.c_str();
        };
        io.SetClipboardTextFn = [](void* user, const char* text) { static_cast<GuiPlatform*>(user)->setClipboard(text); };
        ImGui::StyleColorsDark();
        ImGui_ImplOpenGL3_Init("#version 450");
    }
    ~ImGuiSetup()
    {
        ImGui_ImplOpenGL3_Shutdown();
        ImGui::DestroyContext(context);
    }
};

std::string lowerExtension(const std::string& path)
{
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return extension;
}

constexpr const char* kNoModelStatus =
    "no model loaded: type a .gltf / .glb path and press Load model, or drop the file on the window (the sphere stands in meanwhile)";

// A failed load keeps the environment on screen, so the error line keeps that environment's
// own line and notes under it: they are still true of what is shown.
void showEnvironmentStatus(ui::StatusLine& line, ui::StatusLine status)
{
    if (status.isError && !line.text.empty()) {
        // After another error, its notes are already the kept environment's.
        if (!line.isError) status.notes.push_back("still showing " + line.text);
        status.notes.insert(status.notes.end(), line.notes.begin(), line.notes.end());
    }
    line = std::move(status);
}

void handleDrop(const std::string& path, ui::UiRequests& requests, ui::PanelState& panels)
{
    const std::string extension = lowerExtension(path);
    if (extension == ".exr" || extension == ".hdr")
        requests.loadEnvironment = path;
    else if (extension == ".gltf" || extension == ".glb")
        requests.loadModel = path;
    else if (extension == ".json")
        requests.loadPreset = path;
    else
        showEnvironmentStatus(panels.environmentStatus,
                              {path + ": cannot open this kind of file (drop .exr, .hdr, .gltf, .glb or a .json preset)", true});
}

// Left drag orbits; right or middle drag, or Shift + left drag, pans; the wheel zooms
// (multiplicatively, so it feels the same at any distance); a double-click frames the scene.
struct CameraInput {
    void update(CameraSettings& camera, const ImGuiIO& io, float viewHeight, ui::UiRequests& requests)
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
        if (io.MouseWheel != 0.0f) camera.distance = std::clamp(camera.distance * std::pow(0.9f, io.MouseWheel), 0.05f, 500.0f);
    }
};

// The split view's divider follows the mouse when grabbed within a few pixels of it; while
// it is held, the drag does not orbit the camera.
struct SplitDividerInput {
    bool held = false;
    // Returns true while the divider is being dragged.
    bool update(ViewSettings& view, const ImGuiIO& io, int viewX, int viewWidth)
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
};

bool keyPressed(int glfwKey) { return ImGui::IsKeyPressed(glfwKey, /*repeat=*/false); }

// What the image on screen was rendered from: when it is unchanged, nothing is left to
// render but refinement. The renderer's content revision covers what settings do not
// (a bake that finished, a model or environment that arrived).
struct RenderedState {
    FrameSettings settings;
    int width = 0, height = 0;
    std::uint64_t contentRevision = 0;
    bool referenceComplete = false;   // of the error view
    float referenceMethodProgress = 0.0f; // a side drawn with the reference method shows each step
    // A frame drawn during a drag, scroll or edit renders fewer pixels; once the input stops,
    // the same settings want the full resolution again (else the blurred frame stayed, and the
    // error view kept the shaded preview it draws at another size than its reference).
    float resolutionScale = 1.0f;
    bool operator==(const RenderedState&) const = default;
};

nlohmann::json statusJson(const ui::StatusLine& status) { return {{"text", status.text}, {"error", status.isError}, {"notes", status.notes}}; }

nlohmann::json switchJson(const std::optional<LabSession::SwitchTiming>& timing)
{
    if (!timing) return nullptr;
    return {{"environment", timing->environment}, {"load_ms", timing->loadMs}, {"bake_ms", timing->bakeMs},
            {"first_frame_ms", timing->firstFrameMs}, {"from_cache", timing->fromCache}};
}

// Points the Study chart draws: with a positive error and cost (the axes are logarithmic).
std::size_t plottedPoints(const std::vector<ui::ParetoChart>& charts)
{
    std::size_t count = 0;
    for (const ui::ParetoChart& chart : charts)
        for (const ui::ChartSeries& series : chart.series)
            for (const ui::ChartPoint& point : series.points) count += point.x > 0.0 && point.y > 0.0 && std::isfinite(point.y);
    return count;
}

} // namespace

struct GuiApp::Impl {
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
    gl::PassTimer renderTimer; // the frame's passes, without stalling a real GPU
    InputQueue input;
    StudyRun study;
    CameraInput cameraInput;
    SplitDividerInput divider;
    std::optional<RenderedState> rendered;
    // A screenshot of a frame that shows a reference waits until the reference is complete.
    std::optional<ui::CaptureRequest> pendingCapture;
    std::vector<SphereReading> furnaceReadings; // of the previous frame, printed over the spheres
    Clock::time_point start = Clock::now();
    Clock::time_point previousFrame = Clock::now();
    bool frameWhenReady = false;
    bool isIdle = false;
    bool heldForLoad = false; // the last frame drew nothing new: a map decodes, nothing else runs
    bool sleepWhenIdle = false;
    bool scripted = false;
    bool quit = false;
    bool pixelsRequested = false;
    WindowPixels pixels;
    int framesShown = 0;

    Impl(GuiPlatform& p, const GuiOptions& o)
        : platform(p), options(o), imgui(p), renderer(shaderDirectory()), settings(o.settings), session(renderer, initialBake(o))
    {
        if (gl::currentContextHasDebugOutput()) {
            echoOnStderr(debug);
            debug.install();
        }
        if (const ConventionPreset* convention = findConvention(options.convention)) {
            applyConvention(*convention, settings.sampling);
            panels.convention = convention->name;
        } else if (const ConventionPreset* own = findConvention("iblab")) {
            // The start is iblab's own convention, unless the command line changed its choices.
            SamplingSettings asOwn = settings.sampling;
            applyConvention(*own, asOwn);
            if (asOwn == settings.sampling) panels.convention = own->name;
        }
        panels.catalog = session.catalog();
        std::snprintf(panels.capture.directory, sizeof panels.capture.directory, "%s", std::filesystem::current_path().string().c_str());
        // The environment loads on a worker thread and bakes in slices: the window is up at once.
        session.requestEnvironment(settings.environment.source);
        frameWhenReady = settings.camera.distance <= 0.0f;
        if (frameWhenReady) settings.camera.distance = 3.5f;
        if (settings.scene.kind == SceneKind::Model) panels.sceneStatus = session.loadModel(settings.scene.modelPath, settings);
        stats.renderer = gl::describeCurrentContext();
        savedSettings = settings;
    }

    static bake::BakeSettings initialBake(const GuiOptions& o)
    {
        const ConventionPreset* convention = findConvention(o.convention);
        return convention ? conventionBakeSettings(*convention) : bake::defaultPreset();
    }

    bool unsavedChanges() const { return !(settings == savedSettings); }

    void requestQuit()
    {
        if (unsavedChanges()) panels.quitDialog.open = true;
        else quit = true;
    }

    // Keys that act on the lab, not on a control. None fires while a text field has the
    // keyboard; Esc only closes what is open and never quits (tuning is lost that way too
    // easily): quitting is the window's close button or Ctrl+Q, which ask first when the
    // settings changed since the last save.
    void handleShortcuts(const ImGuiIO& io, ui::UiRequests& requests)
    {
        if (io.WantTextInput) return;
        if (keyPressed(GLFW_KEY_ESCAPE)) {
            if (panels.quitDialog.open) panels.quitDialog.open = false;
            else if (ImGui::IsPopupOpen(nullptr, ImGuiPopupFlags_AnyPopup)) ImGui::ClosePopupsExceptModals();
        }
        if (io.KeyCtrl && keyPressed(GLFW_KEY_Q)) requestQuit();
        if (io.KeyCtrl && keyPressed(GLFW_KEY_S)) requests.savePreset = std::string(panels.presetPath);
        if (keyPressed(GLFW_KEY_F12)) requests.capture = ui::CaptureRequest{};
        if (io.KeyCtrl || io.KeyAlt) return;
        const bool plus = keyPressed(GLFW_KEY_KP_ADD) || keyPressed(GLFW_KEY_EQUAL);
        const bool minus = keyPressed(GLFW_KEY_KP_SUBTRACT) || keyPressed(GLFW_KEY_MINUS);
        if (plus || minus) settings.sampling.samples = std::clamp(settings.sampling.samples + (plus ? 1 : -1), 1, kMaxSampleCount);
        if (keyPressed(GLFW_KEY_HOME) || keyPressed(GLFW_KEY_R)) requests.resetCamera = true;
        if (keyPressed(GLFW_KEY_1) || keyPressed(GLFW_KEY_KP_1)) requests.axisView = CameraAxisView::Front;
        if (keyPressed(GLFW_KEY_3) || keyPressed(GLFW_KEY_KP_3)) requests.axisView = CameraAxisView::Side;
        if (keyPressed(GLFW_KEY_7) || keyPressed(GLFW_KEY_KP_7)) requests.axisView = CameraAxisView::Top;
        if (keyPressed(GLFW_KEY_F)) requests.frameScene = true;
    }

    void capture(const ui::CaptureRequest& request)
    {
        const std::string extension = request.file.empty() ? ".png" : lowerExtension(request.file);
        const std::filesystem::path path = captureName(panels.capture.directory, request.file, settings.environment.source, extension);
        panels.captureStatus = session.capture(path.string(), settings);
    }

    void actOn(ui::UiRequests& requests, int viewWidth, int viewHeight)
    {
        if (requests.loadEnvironment) session.requestEnvironment(*requests.loadEnvironment);
        if (requests.loadModel) {
            panels.sceneStatus = session.loadModel(*requests.loadModel, settings);
            if (!panels.sceneStatus.isError) {
                // A model shows its own materials first; the sliders take over on request.
                settings.material.overrideModel = false;
                requests.frameScene = true;
            }
        }
        if (requests.loadPreset) {
            panels.presetStatus = loadPreset(*requests.loadPreset, settings, session);
            if (!panels.presetStatus.isError) savedSettings = settings;
        }
        if (requests.savePreset) {
            panels.presetStatus = savePreset(*requests.savePreset, settings);
            if (!panels.presetStatus.isError) savedSettings = settings;
        }
        if (requests.exportModel) panels.sceneStatus = session.exportModel(*requests.exportModel, settings);
        if (requests.exportBake) panels.bakeStatus = exportCurrentBake(session, renderer.shaders(), *requests.exportBake, panels.bakeExportPath);
        if (requests.applyConvention)
            if (const ConventionPreset* convention = findConvention(*requests.applyConvention)) {
                session.setBakeSettings(conventionBakeSettings(*convention));
                applyConvention(*convention, settings.sampling);
                panels.convention = convention->name;
                panels.bakeStatus = {"convention " + std::string(convention->title) + ": baking its preset \"" + std::string(convention->bakePreset) + "\"",
                                     false};
            }
        if (requests.startStudy) study.start(session, settings, panels.study);
        if (requests.stopStudy) study.stop(panels.study);
        if (requests.startAutoQuality) study.startAutoQuality(session, settings, panels.study);
        if (requests.applyAutoQuality) study.applyAutoQuality(session, settings, panels);
        if (requests.axisView) setAxisView(settings.camera, *requests.axisView);
        if (requests.resetCamera) {
            const CameraSettings defaults;
            settings.camera.yawDegrees = defaults.yawDegrees;
            settings.camera.pitchDegrees = defaults.pitchDegrees;
            settings.camera.fovDegrees = defaults.fovDegrees;
            requests.frameScene = true;
        }
        // The renderer draws the sphere for a model scene without a model: say why, until
        // another scene is chosen.
        if (requests.sceneChanged && settings.scene.kind == SceneKind::Model && settings.scene.modelPath.empty())
            panels.sceneStatus = {kNoModelStatus};
        else if (requests.sceneChanged && panels.sceneStatus.text == kNoModelStatus)
            panels.sceneStatus = {};
        if (requests.sceneChanged || requests.frameScene || (frameWhenReady && renderer.hasBake())) {
            const bool startFraming = frameWhenReady && !requests.sceneChanged && !requests.frameScene;
            const auto cameraBefore = settings.camera;
            const SceneInfo scene = renderer.sceneInfo(settings);
            frameBox(settings.camera, scene.centre, scene.halfExtents, float(viewWidth) / float(viewHeight));
            // The start's own framing (once the first bake is in) is not an edit of the
            // user's: what counts as saved moves with it, so that quitting does not ask.
            if (startFraming && savedSettings.camera == cameraBefore) savedSettings.camera = settings.camera;
            frameWhenReady = false;
        }
        if (requests.quit) {
            if (*requests.quit == ui::QuitChoice::SaveAndQuit) {
                panels.presetStatus = savePreset(panels.presetPath, settings);
                quit = !panels.presetStatus.isError; // a failed save keeps the app and says why
                if (quit) savedSettings = settings;
            } else if (*requests.quit == ui::QuitChoice::Quit) {
                quit = true;
            }
            panels.quitDialog.open = false;
        }
    }

    void frame();
};

void GuiApp::Impl::frame()
{
    // While a map decodes and nothing else is to be done, wait for it, a 60 Hz frame at most,
    // rather than drawing held frames: on two cores each drawn frame took CPU from the decode
    // (the GUI's switch from the disk cache loaded sunset.exr in 161 ms, the bake command in
    // 52). Input waits at most that frame.
    if (heldForLoad && input.empty()) session.waitForLoad(std::chrono::milliseconds(16));
    platform.collectEvents(input, isIdle && sleepWhenIdle && !scripted ? 0.25 : 0.0);
    ImGuiIO& io = ImGui::GetIO();
    const FrameRequests frameInput = input.applyFrame(io);
    if (frameInput.resized && platform.kind() == "offscreen") platform.resize(frameInput.width, frameInput.height);
    if (frameInput.closeRequested) requestQuit();

    const int windowWidth = platform.width(), windowHeight = platform.height();
    // The 3D view is the part of the window right of the docked panel.
    const int viewX = panels.showPanels ? std::min(int(panels.panelWidth), windowWidth - 16) : 0;
    const int viewWidth = windowWidth - viewX, viewHeight = windowHeight;
    if (viewWidth <= 0 || viewHeight <= 0) { // minimised
        platform.collectEvents(input, 0.25);
        return;
    }
    const glm::vec2 viewOrigin(float(viewX), 0.0f);
    panels.viewRect = {float(viewX), 0.0f, float(windowWidth), float(windowHeight)};
    for (const std::string& error : renderer.reloadShaders()) std::fprintf(stderr, "iblab: %s\n", error.c_str());

    const LabSession::Finished finished = session.pump(settings, kBackgroundBudgetPerFrame);
    if (finished.environment) showEnvironmentStatus(panels.environmentStatus, *finished.environment);
    if (finished.bake) panels.bakeStatus = *finished.bake;
    panels.activity = {session.activity(), session.progress()};
    study.advance(panels.study, kBackgroundBudgetPerFrame);

    const auto now = Clock::now();
    io.DisplaySize = ImVec2(float(windowWidth), float(windowHeight));
    io.DeltaTime = scripted ? kScriptedFrameSeconds : std::max(std::chrono::duration<float>(now - previousFrame).count(), 1e-4f);
    ImGui_ImplOpenGL3_NewFrame();
    ImGui::NewFrame();
    ui::itemRegistry().beginFrame();
    ui::UiRequests requests;
    for (const std::string& dropped : frameInput.dropped) handleDrop(dropped, requests, panels);
    handleShortcuts(io, requests);
    panels.unsavedChanges = unsavedChanges();
    ui::drawControlWindow(settings, panels, stats, requests);
    ui::drawQuitDialog(panels, requests);
    const ImVec2 mouse = io.MousePos;
    drawViewOverlays(renderer, settings, viewWidth, viewHeight, viewOrigin, furnaceReadings,
                     glm::vec2(mouse.x - float(viewX), float(viewHeight) - mouse.y));
    if (!io.WantCaptureMouse && !divider.update(settings.view, io, viewX, viewWidth)) cameraInput.update(settings.camera, io, float(viewHeight), requests);
    ImGui::Render();
    ui::itemRegistry().endFrame();
    platform.setCursor(ImGui::GetMouseCursor());
    // A value typed into a slider stays inside the setting's range, which the command line
    // and presets check: ImGui keeps a Ctrl+click value as typed, -5 for a roughness.
    clampToRanges(frameSettingsFields(), settings);
    // A distance of 0 (typed, or from a preset) is the range's special value, "frame the
    // scene", as --distance 0 is; taken literally it put the camera at the sphere's centre.
    if (settings.camera.distance == 0.0f) requests.frameScene = true;

    actOn(requests, viewWidth, viewHeight);
    const LabSession::Finished switched = session.showRequestedRecent(settings);
    if (switched.environment) showEnvironmentStatus(panels.environmentStatus, *switched.environment);
    if (switched.bake) panels.bakeStatus = *switched.bake;
    if (settings.view.mode == ViewMode::Furnace) session.ensureFurnaceBake();

    // Responsive on a software renderer: while the user drags something, expensive frames
    // render fewer pixels (aiming at ~30 fps); when idle, the sampled method refines
    // progressively instead of re-rendering the same noisy image.
    const bool interacting = ImGui::IsAnyItemActive() || ImGui::IsMouseDragging(ImGuiMouseButton_Left) ||
                             ImGui::IsMouseDragging(ImGuiMouseButton_Right) || ImGui::IsMouseDragging(ImGuiMouseButton_Middle) ||
                             io.MouseWheel != 0.0f;
    if (requests.capture) pendingCapture = requests.capture;
    const bool capturing = pendingCapture.has_value();
    Renderer::Options renderOptions;
    if (interacting && !capturing && stats.renderMs > 33.0)
        renderOptions.resolutionScale =
            std::clamp(float(std::sqrt(33.0 / stats.renderMs * double(stats.resolutionScale * stats.resolutionScale))), 0.25f, 1.0f);
    renderOptions.accumulate = !interacting;
    // The reference (of the error view, or of a side drawn with the reference method), one
    // budgeted slice of work per idle frame (a drag would restart it every frame; it resumes
    // when the drag ends).
    const bool errorView = settings.view.mode == ViewMode::Error;
    const bool referenceShown = showsReference(settings);
    panels.compare.reference = !referenceShown ? ReferenceStatus{}
                               : interacting || session.busy()
                                   ? renderer.referenceStatus(settings, viewWidth, viewHeight)
                                   : renderer.advanceReference(settings, viewWidth, viewHeight, kReferenceBudgetPerFrame);
    // A finished image needs no more frames: split-sum is deterministic, the sampled method
    // stops refining after kMaxAccumulatedFrames (or at once with a frozen sample set), the
    // error view waits for its reference, and the reference method shows each step of it.
    const bool referencePending = referenceShown && !panels.compare.reference.complete;
    const RenderedState current{settings, viewWidth, viewHeight, renderer.contentRevision(), errorView && panels.compare.reference.complete,
                                referenceMethodSide(settings) ? panels.compare.reference.progress : 0.0f, renderOptions.resolutionScale};
    const int framesToConverge = renderer.lastFrameWasSampled() && !keepsExactSampleCount(settings) ? kMaxAccumulatedFrames : 1;
    // The same image again: nothing it shows has changed (a load or bake that lands moves the
    // content revision, and a frame follows then), so a decode that runs meanwhile keeps
    // both cores rather than sharing them with copies of the last frame.
    const bool unchanged = rendered == current && !interacting && !capturing && renderer.accumulatedFrames() >= framesToConverge;
    const bool converged = unchanged && !session.busy();
    // While another environment loads and bakes, the view keeps its last image (the previous
    // environment, lit by its own bake) rather than drawing each frame again: the new one
    // shows sooner, and never with the old one's lighting.
    const bool holdFrame = session.switching() && renderer.hasBake();
    if (!unchanged && !holdFrame) {
        renderTimer.begin();
        renderer.renderFrame(settings, viewWidth, viewHeight, renderOptions);
        renderTimer.end();
        if (errorView) panels.compare.error = renderer.measureError(settings);
        stats.resolutionScale = renderOptions.resolutionScale; // of the frame on screen
        // Only a frame drawn: a held one is still the older state's (a load that then fails
        // changes no content, and the view stayed as it was before the request).
        rendered = current;
    }
    if (const std::optional<double> renderMs = renderTimer.latestMilliseconds()) stats.renderMs = *renderMs;
    stats.accumulatedFrames = renderer.accumulatedFrames();
    stats.width = viewWidth;
    stats.height = viewHeight;
    furnaceReadings = settings.view.mode == ViewMode::Furnace ? renderer.measureSpheres(settings) : std::vector<SphereReading>{};
    if (pendingCapture && referencePending)
        panels.captureStatus = {"the screenshot waits for the reference (" + std::to_string(int(100.0f * panels.compare.reference.progress)) + "%)"};
    else if (pendingCapture)
        capture(*std::exchange(pendingCapture, std::nullopt));
    // Idle: nothing left to compute until the next input (what scripts wait for). The loop
    // also keeps drawing while a control is hovered (its tooltip) or a field has the
    // keyboard (the caret), and only sleeps when neither.
    isIdle = converged && !referencePending && !study.running() && input.empty();
    heldForLoad = (holdFrame || unchanged) && !study.running() && !referencePending;
    sleepWhenIdle = !ImGui::IsAnyItemHovered() && !io.WantTextInput;

    glBindFramebuffer(GL_FRAMEBUFFER, platform.framebuffer());
    glViewport(0, 0, windowWidth, windowHeight);
    glClearColor(0.06f, 0.06f, 0.07f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    renderer.presentTo(platform.framebuffer(), viewX, 0, windowWidth, windowHeight);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (std::exchange(pixelsRequested, false)) pixels = platform.readPixels();
    platform.present();
    session.frameDrawn();

    const auto end = Clock::now();
    stats.frameMs = std::chrono::duration<double, std::milli>(end - previousFrame).count();
    previousFrame = end;
    if (framesShown++ == 0) {
        std::printf("iblab: first frame %.0f ms after start (%s)\n", std::chrono::duration<double, std::milli>(end - start).count(), stats.renderer.c_str());
        std::fflush(stdout);
    }
    if (options.quitAfterFrames > 0 && framesShown >= options.quitAfterFrames) quit = true;
}

GuiApp::GuiApp(GuiPlatform& platform, const GuiOptions& options) : impl_(std::make_unique<Impl>(platform, options)) {}
GuiApp::~GuiApp() = default;

void GuiApp::frame() { impl_->frame(); }
void GuiApp::setScripted(bool scripted) { impl_->scripted = scripted; }
bool GuiApp::quitRequested() const { return impl_->quit; }
bool GuiApp::idle() const { return impl_->isIdle; }
InputQueue& GuiApp::input() { return impl_->input; }
GuiPlatform& GuiApp::platform() { return impl_->platform; }
const WindowPixels& GuiApp::lastPixels() const { return impl_->pixels; }
void GuiApp::requestPixels() { impl_->pixelsRequested = true; }
const ui::ItemRegistry& GuiApp::items() const { return ui::itemRegistry(); }
int GuiApp::glErrorCount() const { return impl_->debug.errorCount(); }

nlohmann::json GuiApp::state() const
{
    const Impl& a = *impl_;
    const ui::PanelState& p = a.panels;
    nlohmann::json labels = nlohmann::json::array();
    for (const ScreenLabel& label : a.renderer.sceneLabels(a.settings, a.stats.width, a.stats.height))
        labels.push_back({{"text", label.text}, {"x", p.viewRect.x0 + label.pixel.x}, {"y", float(a.stats.height) - label.pixel.y}});
    nlohmann::json popups = nlohmann::json::array();
    for (const ImGuiPopupData& popup : ImGui::GetCurrentContext()->OpenPopupStack)
        popups.push_back(popup.Window ? popup.Window->Name : "");
    return {
        {"frame", a.framesShown},
        {"idle", a.isIdle},
        {"quit", a.quit},
        {"platform", a.platform.kind()},
        {"window", {{"width", a.platform.width()}, {"height", a.platform.height()}}},
        {"view", {{"x", p.viewRect.x0}, {"y", p.viewRect.y0}, {"width", p.viewRect.x1 - p.viewRect.x0}, {"height", p.viewRect.y1 - p.viewRect.y0}}},
        {"settings", nlohmann::json::parse(toJsonText(a.settings))},
        {"unsaved_changes", a.unsavedChanges()},
        {"panels",
         {{"shown", p.showPanels},
          {"width", p.panelWidth},
          {"environment_status", statusJson(p.environmentStatus)},
          {"bake_status", statusJson(p.bakeStatus)},
          {"scene_status", statusJson(p.sceneStatus)},
          {"capture_status", statusJson(p.captureStatus)},
          {"preset_status", statusJson(p.presetStatus)},
          {"activity", p.activity.text},
          {"convention", p.convention},
          {"quit_dialog", p.quitDialog.open},
          {"compare",
           {{"reference_current", p.compare.reference.current},
            {"reference_complete", p.compare.reference.complete},
            {"reference_progress", p.compare.reference.progress},
            {"error_valid", p.compare.error.valid},
            {"relative_rmse", p.compare.error.valid ? p.compare.error.left.relativeRmse : 0.0},
            {"pixels", p.compare.error.valid ? p.compare.error.left.pixels : 0}}},
          {"study",
           {{"running", p.study.running},
            {"status", statusJson(p.study.status)},
            {"charts", p.study.charts.size()},
            {"plotted_points", plottedPoints(p.study.charts)},
            {"chart_open", p.study.chartOpen},
            {"auto_quality", {{"running", p.study.autoQuality.running}, {"have_choice", p.study.autoQuality.haveChoice}, {"applied", p.study.autoQuality.applied}, {"chosen", p.study.autoQuality.chosen}}}}}}},
        {"session", {{"busy", a.session.busy()}, {"environment", a.session.environment() ? a.session.environment()->source : ""}, {"has_bake", a.renderer.hasBake()}, {"last_switch", switchJson(a.session.lastSwitch())}}},
        {"renderer",
         {{"accumulated_frames", a.renderer.accumulatedFrames()},
          {"content_revision", a.renderer.contentRevision()},
          {"sampled", a.renderer.lastFrameWasSampled()},
          {"render_ms", a.stats.renderMs},
          {"resolution_scale", a.stats.resolutionScale}}},
        {"ui",
         {{"popups", popups},
          {"want_text_input", ImGui::GetIO().WantTextInput},
          {"mouse", {ImGui::GetIO().MousePos.x, ImGui::GetIO().MousePos.y}}}},
        {"labels", labels},
    };
}

int runGui(const GuiOptions& options)
{
    const bool offscreen = options.offscreen || (!options.script.empty() && !displayAvailable());
    std::unique_ptr<GuiPlatform> platform = offscreen ? makeOffscreenPlatform(options.width, options.height, kDebugContext || !options.script.empty())
                                                      : makeWindowPlatform(options.width, options.height, kDebugContext || !options.script.empty());
    gl::requireCurrentContextFeatures();
    GuiApp app(*platform, options);
    if (!options.script.empty()) return runGuiScript(app, options.script, options.coverageOut);
    while (!app.quitRequested()) app.frame();
    return 0;
}

} // namespace iblab::app
