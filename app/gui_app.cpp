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

#include "asset_paths.hpp"
#include "bake_export.hpp"
#include "command_support.hpp"
#include "frame/camera.hpp"
#include "frame/conventions.hpp"
#include "io/atomic_file.hpp"
#include "io/builtin_environments.hpp"
#include "io/environment.hpp"
#include "io/error.hpp"
#include "gl/context_info.hpp"
#include "gl/debug_output.hpp"
#include "gl/pass_timer.hpp"
#include "gui_files.hpp"
#include "gui_script.hpp"
#include "gui_app_impl.hpp"
#include "frame_capture.hpp"
#include "lab_session.hpp"
#include "ui/help_window.hpp"
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
constexpr auto kReferenceBudgetPerFrame = std::chrono::milliseconds(20);
// Background loading and baking get this much per frame: the UI stays near interactive
// rates on a software renderer.
constexpr auto kBackgroundBudgetPerFrame = std::chrono::milliseconds(30);
// A scripted frame advances ImGui's clock by this much, whatever the frame took.
constexpr float kScriptedFrameSeconds = 1.0f / 30.0f;

#ifdef NDEBUG
constexpr bool kDebugContext = false;
#else
constexpr bool kDebugContext = true;
#endif

} // namespace

ImGuiSetup::ImGuiSetup(GuiPlatform& platform)
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

ImGuiSetup::~ImGuiSetup()
{
    ImGui_ImplOpenGL3_Shutdown();
    ImGui::DestroyContext(context);
}

namespace {

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
void showEnvironmentStatus(ui::StatusLine& line, const StatusReport& report)
{
    ui::StatusLine status = toStatusLine(report);
    if (status.isError && !line.text.empty()) {
        // After another error, its notes are already the kept environment's.
        if (!line.isError) status.notes.push_back("still showing " + line.text);
        status.notes.insert(status.notes.end(), line.notes.begin(), line.notes.end());
    }
    line = std::move(status);
}

// A dropped file's path goes into its panel's path field, as if typed there, so that the field
// names what is loading and Load reloads it (where the path fits the field).
template <std::size_t N>
void showDroppedPath(char (&field)[N], const std::string& path)
{
    if (path.size() < N) std::snprintf(field, N, "%s", path.c_str());
}

void handleDrop(const std::string& path, ui::UiRequests& requests, ui::PanelState& panels)
{
    const std::string extension = lowerExtension(path);
    if (extension == ".gltf" || extension == ".glb") {
        requests.loadModel = path;
        showDroppedPath(panels.modelPath, path);
    } else if (extension == ".json") {
        // Not into the preset's field: Save would then overwrite the dropped file.
        requests.loadPreset = path;
    } else if (isEnvironmentImagePath(path) || isImportedBakeSpec(path)) {
        requests.loadEnvironment = path;
        showDroppedPath(panels.environmentPath, path);
    } else
        showEnvironmentStatus(panels.environmentStatus,
                              StatusReport{path + ": cannot open this kind of file (drop an environment, " + kEnvironmentImageKinds +
                                               "; another tool's bake, .ktx, .ktx2 or its directory; a model, .gltf or .glb; or a .json preset)",
                                           true});
}

bool keyPressed(int glfwKey) { return ImGui::IsKeyPressed(glfwKey, /*repeat=*/false); }

} // namespace

GuiApp::Impl::Impl(GuiPlatform& p, const GuiOptions& o)
    : platform(p), options(o), imgui(p), renderer(shaderDirectory()), settings(o.settings), session(renderer, initialBake(o)), model(renderer)
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
    panels.catalog = environmentCatalog();
    rememberFrom(options.remembered);
    // The environment loads on a worker thread and bakes in slices: the window is up at once.
    session.requestEnvironment(settings.environment.source);
    if (settings.camera.distance <= 0.0f) {
        const bool orientationGiven = settings.camera.yawDegrees != CameraSettings{}.yawDegrees || settings.camera.pitchDegrees != CameraSettings{}.pitchDegrees;
        startFraming = orientationGiven ? StartFraming::WhenBaked : StartFraming::WhenBakedFromHome;
        settings.camera.distance = 3.5f;
    }
    if (settings.scene.kind == SceneKind::Model) loadModel(settings.scene.modelPath);
    stats.renderer = gl::describeCurrentContext();
    savedSettings = settings;
}

bake::BakeSettings GuiApp::Impl::initialBake(const GuiOptions& o)
{
    const ConventionPreset* convention = findConvention(o.convention);
    return convention ? conventionBakeSettings(*convention) : bake::defaultPreset();
}

// The last session's sections and paths; captures, presets and exports otherwise go to the
// user's pictures and documents folders rather than wherever the lab was started.
void GuiApp::Impl::rememberFrom(const std::optional<GuiPrefs>& remembered)
{
    const GuiPrefs prefs = remembered.value_or(GuiPrefs{});
    panels.firstRunHint = !prefs.hintDismissed;
    for (const auto& [label, open] : prefs.sections) ui::sectionStates()[label] = open;
    const auto copy = [](char* field, std::size_t size, const std::string& value) {
        if (!value.empty()) std::snprintf(field, size, "%s", value.c_str());
    };
    copy(panels.capture.directory, sizeof panels.capture.directory,
         prefs.captureFolder.empty() ? userDirectory("PICTURES").string() : prefs.captureFolder);
    copy(panels.presetPath, sizeof panels.presetPath,
         prefs.presetPath.empty() ? (userDirectory("DOCUMENTS") / panels.presetPath).string() : prefs.presetPath);
    copy(panels.environmentPath, sizeof panels.environmentPath, prefs.environmentPath);
    copy(panels.modelPath, sizeof panels.modelPath, prefs.modelPath);
    copy(panels.exportPath, sizeof panels.exportPath,
         prefs.exportPath.empty() ? (userDirectory("DOCUMENTS") / panels.exportPath).string() : prefs.exportPath);
    copy(panels.bakeExportPath, sizeof panels.bakeExportPath,
         prefs.bakeExportPath.empty() ? (userDirectory("DOCUMENTS") / panels.bakeExportPath).string() : prefs.bakeExportPath);
}

void GuiApp::Impl::requestQuit()
{
    if (unsavedChanges()) panels.quitDialog.open = true;
    else quit = true;
}

// Keys that act on the lab, not on a control. None fires while a text field has the
// keyboard; Esc only closes what is open and never quits (tuning is lost that way too
// easily): quitting is the window's close button or Ctrl+Q, which ask first when the
// settings changed since the last save.
void GuiApp::Impl::handleShortcuts(const ImGuiIO& io, ui::UiRequests& requests)
{
    if (io.WantTextInput) return;
    if (keyPressed(GLFW_KEY_ESCAPE)) {
        if (panels.quitDialog.open) panels.quitDialog.open = false;
        else if (ImGui::IsPopupOpen(nullptr, ImGuiPopupFlags_AnyPopup)) ImGui::ClosePopupsExceptModals();
        else if (panels.helpOpen) panels.helpOpen = false;
    }
    if (keyPressed(GLFW_KEY_F1)) panels.helpOpen = !panels.helpOpen;
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

void GuiApp::Impl::capture(const ui::CaptureRequest& request)
{
    const std::string extension = request.file.empty() ? ".png" : lowerExtension(request.file);
    const std::filesystem::path path = captureName(panels.capture.directory, request.file, settings.environment.source, extension);
    panels.captureStatus = toStatusLine(writeCapture(renderer, path.string(), settings, session.bakeSettings()));
}

// A loaded model becomes the scene (the session never writes the settings); a failed load
// keeps the scene and the model it had.
void GuiApp::Impl::loadModel(const std::string& path)
{
    panels.sceneStatus = toStatusLine(model.load(path, settings.scene.kind == SceneKind::Model));
    if (panels.sceneStatus.isError) return;
    settings.scene.kind = SceneKind::Model;
    settings.scene.modelPath = path;
}

void GuiApp::Impl::actOn(ui::UiRequests& requests, int viewWidth, int viewHeight)
{
    if (requests.countingSetup) {
        requests.loadEnvironment = applyCountingSetup(settings);
        requests.frameScene = true;
    }
    if (requests.loadEnvironment) session.requestEnvironment(*requests.loadEnvironment);
    if (requests.loadModel) {
        loadModel(*requests.loadModel);
        if (!panels.sceneStatus.isError) {
            // A model shows its own materials first; the sliders take over on request.
            settings.material.overrideModel = false;
            requests.frameScene = true;
        }
    }
    if (requests.loadPreset)
        panels.presetStatus = loadPreset(*requests.loadPreset, settings, savedSettings, session, model, panels.convention);
    if (requests.savePreset) {
        panels.presetStatus = savePreset(*requests.savePreset, settings, session.bakeSettings());
        if (!panels.presetStatus.isError) savedSettings = settings;
    }
    if (requests.exportModel) panels.sceneStatus = toStatusLine(model.exportWithPanelMaterial(*requests.exportModel, settings));
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
    frameCamera(requests, viewWidth, viewHeight);
    if (requests.quit) {
        if (*requests.quit == ui::QuitChoice::SaveAndQuit) {
            panels.presetStatus = savePreset(panels.presetPath, settings, session.bakeSettings());
            quit = !panels.presetStatus.isError; // a failed save keeps the app and says why
            if (quit) savedSettings = settings;
        } else if (*requests.quit == ui::QuitChoice::Quit) {
            quit = true;
        }
        panels.quitDialog.open = false;
    }
}


// The scene's framing: on request, on a scene switch, and once the first bake is in.
void GuiApp::Impl::frameCamera(ui::UiRequests& requests, int viewWidth, int viewHeight)
{
    // A new scene, a new model and Reset show the scene from its home view; Frame, F and
    // a double-click keep the orientation the user chose.
    const bool home = requests.resetCamera || requests.sceneChanged || (requests.loadModel && !panels.sceneStatus.isError);
    if (home) requests.frameScene = true;
    // The model's line belongs to the model scene: another scene clears it, and coming back
    // to the model shows it again (the sphere kept the model's line). Without a model the
    // renderer draws the sphere: say why.
    if (requests.sceneChanged && settings.scene.kind == SceneKind::Model)
        panels.sceneStatus = settings.scene.modelPath.empty() || model.line().empty() ? ui::StatusLine{kNoModelStatus} : ui::StatusLine{model.line()};
    else if (requests.sceneChanged)
        panels.sceneStatus = {};
    const bool framingDue = startFraming != StartFraming::Done && renderer.hasBake();
    if (requests.sceneChanged || requests.frameScene || framingDue) {
        const bool atStart = framingDue && !requests.sceneChanged && !requests.frameScene;
        const auto cameraBefore = settings.camera;
        const SceneInfo scene = renderer.sceneInfo(settings);
        const bool isModel = settings.scene.kind == SceneKind::Model;
        if (home || (atStart && startFraming == StartFraming::WhenBakedFromHome)) homeView(settings.camera, isModel);
        frameScene(settings.camera, scene.centre, scene.halfExtents, isModel, float(viewWidth) / float(viewHeight));
        // The start's own framing (once the first bake is in) is not an edit of the
        // user's: what counts as saved moves with it, so that quitting does not ask.
        if (atStart && savedSettings.camera == cameraBefore) savedSettings.camera = settings.camera;
        startFraming = StartFraming::Done;
    }
}

ViewArea GuiApp::Impl::viewArea() const
{
    const int windowWidth = platform.width();
    const int x = panels.showPanels ? std::min(int(panels.panelWidth), windowWidth - 16) : 0;
    return {x, windowWidth - x, platform.height()};
}

// Loading, baking and the study, each a budgeted slice of work per frame: the frame's one
// call into the session, which also hears when the last frame was presented.
void GuiApp::Impl::pumpBackground(bool inputArrived)
{
    // While a map decodes and nothing else is to be done, wait for it, a 60 Hz frame at most,
    // rather than drawing held frames: on two cores each drawn frame took CPU from the decode
    // (the GUI's switch from the disk cache loaded sunset.exr in 161 ms, the bake command in
    // 52). Input that came with this frame is not kept waiting.
    const bool waitForDecode = pace == LoopPace::HeldForLoad && !inputArrived;
    const LabSession::FrameReport report =
        session.update({.budget = kBackgroundBudgetPerFrame,
                        .presented = std::exchange(presented, std::nullopt),
                        .waitForDecode = waitForDecode ? std::chrono::milliseconds(16) : Clock::duration::zero()});
    const LabSession::Finished& finished = report.finished;
    if (finished.environment) showEnvironmentStatus(panels.environmentStatus, *finished.environment);
    if (finished.bake) panels.bakeStatus = toStatusLine(*finished.bake);
    if (finished.environmentShown) settings.environment.source = *finished.environmentShown;
    panels.activity = {report.activity, report.progress};
    study.advance(panels.study, kBackgroundBudgetPerFrame);
}

// The panels, the dialogs, the overlays on the view and the mouse on the view; returns what
// they asked for.
ui::UiRequests GuiApp::Impl::drawUi(const FrameRequests& frameInput, const ViewArea& area)
{
    ImGuiIO& io = ImGui::GetIO();
    const auto now = Clock::now();
    io.DisplaySize = ImVec2(float(platform.width()), float(platform.height()));
    io.DeltaTime = scripted ? kScriptedFrameSeconds : std::max(std::chrono::duration<float>(now - previousFrame).count(), 1e-4f);
    ImGui_ImplOpenGL3_NewFrame();
    ImGui::NewFrame();
    ui::itemRegistry().beginFrame();
    ui::UiRequests requests;
    for (const std::string& dropped : frameInput.dropped) handleDrop(dropped, requests, panels);
    handleShortcuts(io, requests);
    panels.unsavedChanges = unsavedChanges();
    drawnEnvironmentStatus = panels.environmentStatus.text;
    ui::drawControlWindow(settings, panels, stats, requests);
    ui::drawQuitDialog(panels, requests);
    ui::drawHelpWindow(panels.helpOpen);
    const ImVec2 mouse = io.MousePos;
    drawViewOverlays(renderer, settings, area.width, area.height, glm::vec2(float(area.x), 0.0f), furnaceReadings,
                     glm::vec2(mouse.x - float(area.x), float(area.height) - mouse.y));
    if (!io.WantCaptureMouse && !divider.update(settings.view, io, area.x, area.width))
        cameraInput.update(settings.camera, io, float(area.height), requests);
    ImGui::Render();
    ui::itemRegistry().endFrame();
    platform.setCursor(ImGui::GetMouseCursor());
    // A value typed into a slider stays inside the setting's range, which the command line
    // and presets check: ImGui keeps a Ctrl+click value as typed, -5 for a roughness.
    clampToRanges(frameSettingsFields(), settings);
    // A distance of 0 (typed, or from a preset) is the range's special value, "frame the
    // scene", as --distance 0 is; taken literally it put the camera at the sphere's centre.
    if (settings.camera.distance == 0.0f) requests.frameScene = true;
    return requests;
}

// The reference's slice, the view's frame (frame_scheduler.hpp decides what it draws), the
// measurements of what it drew, and a screenshot once the view shows what it asked for.
void GuiApp::Impl::renderView(const ViewArea& area, bool interacting)
{
    const bool inputPending = !input.empty();
    // The reference (of the error view, or of a side drawn with the reference method), one
    // budgeted slice of work per frame with nothing else to do first (a drag would restart
    // it every frame; it resumes when the drag ends, and waits while input is queued).
    const bool errorView = settings.view.mode == ViewMode::Error;
    const bool referenceShown = showsReference(settings);
    panels.compare.reference = !referenceShown ? ReferenceStatus{}
                               : interacting || inputPending || session.busy()
                                   ? renderer.referenceStatus(settings, area.width, area.height)
                                   : renderer.advanceReference(settings, area.width, area.height, kReferenceBudgetPerFrame);
    const bool referencePending = referenceShown && !panels.compare.reference.complete;
    ViewFrameInput in;
    in.content = {settings, area.width, area.height, renderer.contentRevision(), errorView && panels.compare.reference.complete,
                  referenceMethodSide(settings) ? panels.compare.reference.progress : 0.0f};
    in.interacting = interacting;
    in.inputPending = inputPending;
    // While another environment loads and bakes, the view keeps its last image (the previous
    // environment, lit by its own bake) rather than drawing each frame again: the new one
    // shows sooner, and never with the old one's lighting.
    in.hold = session.holdsLastImage();
    const ViewWork work = view.render(renderer, in, Clock::now());
    if (view.newImage()) {
        ++viewImages;
        if (firstImageOfEnvironment.environment != settings.environment.source)
            firstImageOfEnvironment = {settings.environment.source, drawnEnvironmentStatus};
        if (errorView) panels.compare.error = renderer.measureError(settings);
        stats.resolutionScale = view.shownScale(); // of the frame on screen
    }
    stats.renderMs = view.fullFrameMs();
    stats.accumulatedFrames = renderer.accumulatedFrames();
    stats.width = area.width;
    stats.height = area.height;
    furnaceReadings = settings.view.mode == ViewMode::Furnace ? renderer.measureSpheres(settings) : std::vector<SphereReading>{};
    if (pendingCapture && referencePending)
        panels.captureStatus = {"the screenshot waits for the reference (" + std::to_string(int(100.0f * panels.compare.reference.progress)) + "%)"};
    else if (pendingCapture && view.showsFinal(renderer, in.content))
        capture(*std::exchange(pendingCapture, std::nullopt));
    else if (pendingCapture)
        panels.captureStatus = {"the screenshot waits for the full-resolution frame (" + std::to_string(int(100.0f * renderer.sliceProgress())) + "%)"};
    // Idle: nothing left to compute until the next input (what scripts wait for). The loop
    // also keeps drawing while a control is hovered (its tooltip) or a field has the
    // keyboard (the caret), and only sleeps when neither.
    ViewFrameInput settled = in;
    settled.inputPending = false;
    const bool viewDone = view.plan(renderer, settled) == ViewWork::None;
    // A switch's first frame is reported at the next frame's update: not idle before, so that
    // its timing is there for whoever waits for idle.
    const bool idle = viewDone && !in.hold && !session.busy() && !session.awaitsFrame() && !referencePending && !study.running() &&
                      input.empty() && !pendingCapture;
    if (idle) pace = !ImGui::IsAnyItemHovered() && !ImGui::GetIO().WantTextInput ? LoopPace::IdleAsleep : LoopPace::Idle;
    else pace = work == ViewWork::None && !study.running() && !referencePending ? LoopPace::HeldForLoad : LoopPace::Working;
}

void GuiApp::Impl::present(int windowWidth, int windowHeight, int viewX)
{
    glBindFramebuffer(GL_FRAMEBUFFER, platform.framebuffer());
    glViewport(0, 0, windowWidth, windowHeight);
    glClearColor(0.06f, 0.06f, 0.07f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    renderer.presentTo(platform.framebuffer(), viewX, 0, windowWidth, windowHeight);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (std::exchange(pixelsRequested, false)) pixels = platform.readPixels();
    platform.present();
    presented = Clock::now();
}

void GuiApp::Impl::frame()
{
    platform.collectEvents(input, pace == LoopPace::IdleAsleep && !scripted ? 0.25 : 0.0);
    const bool inputArrived = !input.empty();
    ImGuiIO& io = ImGui::GetIO();
    const FrameRequests frameInput = input.applyFrame(io);
    if (frameInput.resized && platform.kind() == PlatformKind::Offscreen) platform.resize(frameInput.width, frameInput.height);
    if (frameInput.closeRequested) requestQuit();
    // The first-run hint has done its job once the user does something; gui.json remembers.
    if (frameInput.userActed) panels.firstRunHint = false;

    const ViewArea area = viewArea();
    if (area.width <= 0 || area.height <= 0) { // minimised
        platform.collectEvents(input, 0.25);
        return;
    }
    panels.viewRect = {float(area.x), 0.0f, float(platform.width()), float(platform.height())};
    for (const std::string& error : renderer.reloadShaders()) std::fprintf(stderr, "iblab: %s\n", error.c_str());
    pumpBackground(inputArrived);
    ui::UiRequests requests = drawUi(frameInput, area);

    // A switch to a recent environment asked for here is shown by the next frame's pump,
    // before its panel is drawn: shown now, its first image went out beside the panel drawn
    // above, which still had the old environment's status line.
    actOn(requests, area.width, area.height);
    // On the frame that turns to the furnace view (or after a re-bake, which drops it).
    if (settings.view.mode == ViewMode::Furnace && !renderer.hasFurnaceBake()) session.ensureFurnaceBake();
    if (requests.capture) pendingCapture = requests.capture;

    // A drag, a held control or the wheel: the view previews what changes and refines nothing.
    const bool interacting = ImGui::IsAnyItemActive() || ImGui::IsMouseDragging(ImGuiMouseButton_Left) ||
                             ImGui::IsMouseDragging(ImGuiMouseButton_Right) || ImGui::IsMouseDragging(ImGuiMouseButton_Middle) ||
                             io.MouseWheel != 0.0f;
    renderView(area, interacting);
    present(platform.width(), platform.height(), area.x);

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
bool GuiApp::idle() const { return impl_->pace == LoopPace::Idle || impl_->pace == LoopPace::IdleAsleep; }
InputQueue& GuiApp::input() { return impl_->input; }
GuiPlatform& GuiApp::platform() { return impl_->platform; }
const WindowPixels& GuiApp::lastPixels() const { return impl_->pixels; }
void GuiApp::requestPixels() { impl_->pixelsRequested = true; }
const ui::ItemRegistry& GuiApp::items() const { return ui::itemRegistry(); }
int GuiApp::glErrorCount() const { return impl_->debug.errorCount(); }

GuiPrefs GuiApp::prefs() const
{
    const ui::PanelState& p = impl_->panels;
    GuiPrefs prefs{ui::sectionStates(), p.environmentPath, p.modelPath, p.presetPath, p.exportPath, p.capture.directory, impl_->platform.width(),
                   impl_->platform.height()};
    prefs.bakeExportPath = p.bakeExportPath;
    prefs.hintDismissed = !p.firstRunHint;
    return prefs;
}

int runGui(const GuiOptions& given)
{
    // The last session's window size, sections and paths; saved again on the way out.
    GuiOptions options = given;
    std::string warning;
    const std::filesystem::path prefsPath = guiPrefsPath();
    options.remembered = loadGuiPrefs(prefsPath, warning);
    if (!warning.empty()) std::fprintf(stderr, "iblab: %s\n", warning.c_str());
    if (options.remembered && !options.windowSizeGiven && options.remembered->width >= 320 && options.remembered->height >= 240) {
        options.width = std::min(options.remembered->width, 16384);
        options.height = std::min(options.remembered->height, 16384);
    }
    const bool offscreen = options.offscreen || (!options.script.empty() && !displayAvailable());
    std::unique_ptr<GuiPlatform> platform = offscreen ? makeOffscreenPlatform(options.width, options.height, kDebugContext || !options.script.empty())
                                                      : makeWindowPlatform(options.width, options.height, kDebugContext || !options.script.empty());
    gl::requireCurrentContextFeatures();
    GuiApp app(*platform, options);
    int status = 0;
    if (!options.script.empty()) status = runGuiScript(app, options.script, options.coverageOut);
    else
        while (!app.quitRequested()) app.frame();
    try {
        saveGuiPrefs(prefsPath, app.prefs());
    } catch (const Error& e) {
        std::fprintf(stderr, "iblab: the GUI's settings were not remembered: %s\n", e.what());
    }
    return status;
}

} // namespace iblab::app
