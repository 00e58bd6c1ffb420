#include "gui_app.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>
#include <cstdio>
#include <stdexcept>

#include <epoxy/gl.h>
// GLFW after epoxy: epoxy provides the GL declarations GLFW would otherwise pull in.
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include "asset_paths.hpp"
#include "bench/auto_quality.hpp"
#include "bench_chart.hpp"
#include "camera.hpp"
#include "conventions.hpp"
#include "view_overlays.hpp"
#include "environment/atomic_file.hpp"
#include "environment/error.hpp"
#include "gl/context_info.hpp"
#include "gl/debug_output.hpp"
#include "lab_session.hpp"
#include "panels.hpp"
#include "renderer.hpp"

namespace iblab::app {
namespace {

struct GlfwLibrary {
    GlfwLibrary()
    {
        glfwSetErrorCallback([](int code, const char* description) { std::fprintf(stderr, "iblab: GLFW error %d: %s\n", code, description); });
        if (!glfwInit()) throw WindowUnavailable("no window system: glfwInit failed (is DISPLAY set?)");
    }
    ~GlfwLibrary() { glfwTerminate(); }
};

struct Window {
    GLFWwindow* handle = nullptr;
    Window(int width, int height, bool debug)
    {
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
        glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
        glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
        glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, debug ? GLFW_TRUE : GLFW_FALSE);
        handle = glfwCreateWindow(width, height, "iblab", nullptr, nullptr);
        if (!handle) throw WindowUnavailable("cannot create a window with an OpenGL 4.5 core context");
        glfwMakeContextCurrent(handle);
        glfwSwapInterval(1);
    }
    ~Window() { glfwDestroyWindow(handle); }
};

struct ImGuiLayer {
    explicit ImGuiLayer(GLFWwindow* window)
    {
        IMGUI_CHECKVERSION();
        ImGui::CreateContext();
        ImGui::GetIO().IniFilename = nullptr; // no imgui.ini littering the working directory
        ImGui::StyleColorsDark();
        ImGui_ImplGlfw_InitForOpenGL(window, true);
        ImGui_ImplOpenGL3_Init("#version 450");
    }
    ~ImGuiLayer()
    {
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
    }
};

// Files dropped onto the window, collected by GLFW's callback and handled once per frame.
std::vector<std::string> g_droppedFiles;

void onDrop(GLFWwindow*, int count, const char** paths)
{
    for (int i = 0; i < count; ++i) g_droppedFiles.emplace_back(paths[i]);
}

void handleDrop(const std::string& path, ui::UiRequests& requests, ui::PanelState& panels)
{
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (extension == ".exr" || extension == ".hdr")
        requests.loadEnvironment = path;
    else if (extension == ".gltf" || extension == ".glb")
        requests.loadModel = path;
    else if (extension == ".json")
        requests.loadPreset = path;
    else
        panels.environmentStatus = {path + ": cannot open this kind of file (drop .exr, .hdr, .gltf, .glb or a .json preset)", true};
}

ui::StatusLine savePreset(const std::string& path, const FrameSettings& settings)
{
    try {
        writeTextFileAtomic(path, toJsonText(settings) + "\n");
        return {"saved " + path, false};
    } catch (const Error& e) {
        return {e.what(), true};
    }
}

// A preset replaces every setting; its environment and model load like a user's choice.
ui::StatusLine loadPreset(const std::string& path, FrameSettings& settings, LabSession& session)
{
    FrameSettings loaded;
    try {
        loaded = frameSettingsFromJsonText(readTextFile(path));
    } catch (const Error& e) {
        return {e.what(), true};
    } catch (const std::exception& e) {
        return {path + ": " + e.what(), true};
    }
    const std::string environment = loaded.environment.source;
    loaded.environment.source = settings.environment.source; // until the new one has loaded
    settings = loaded;
    if (!environment.empty()) session.requestEnvironment(environment);
    if (settings.scene.kind == SceneKind::Model && !settings.scene.modelPath.empty()) {
        const ui::StatusLine model = session.loadModel(settings.scene.modelPath, settings);
        if (model.isError) return model;
    }
    return {"loaded " + path, false};
}

// Left drag orbits, the wheel zooms (multiplicatively, so it feels the same at any
// distance), a double-click frames the scene.
struct OrbitInput {
    void update(CameraSettings& camera, const ImGuiIO& io, ui::UiRequests& requests)
    {
        if (ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left)) requests.frameScene = true;
        if (ImGui::IsMouseDragging(ImGuiMouseButton_Left, 1.0f)) {
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

// The error view's reference gets this much GPU time per frame while the view is idle.
constexpr auto kReferenceBudgetPerFrame = std::chrono::milliseconds(30);

// Progressive refinement stops here: 64 rotated sample sets of any N are plenty to judge.
constexpr int kMaxAccumulatedFrames = 64;

#ifdef NDEBUG
constexpr bool kDebugContext = false;
#else
constexpr bool kDebugContext = true;
#endif

} // namespace

bool displayAvailable()
{
    if (!std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY")) return false;
    glfwSetErrorCallback(nullptr);
    if (!glfwInit()) return false;
    glfwTerminate();
    return true;
}

// The Study panel's sweep: a quick bench on the current environment and scene, a slice per
// frame. It runs on a renderer of its own, so the view keeps its environment and bake.
class StudyRun {
public:
    void start(const LabSession& session, const FrameSettings& settings, ui::StudyState& study) { begin(session, settings, study, false); }

    // The auto quality mode: its candidates for this scene and environment, and the presets
    // beside them, measured like the sweep; the choice is made when the last one is in.
    void startAutoQuality(const LabSession& session, const FrameSettings& settings, ui::StudyState& study) { begin(session, settings, study, true); }

    void stop(ui::StudyState& study)
    {
        job_.reset();
        study.running = false;
        study.autoQuality.running = false;
        study.status = {"stopped", false};
    }

    // One slice of the sweep; the chart follows the points measured so far.
    void advance(ui::StudyState& study, std::chrono::steady_clock::duration budget)
    {
        if (!job_) return;
        try {
            const bool more = job_->runFor(budget);
            study.progress = job_->progress();
            study.activity = job_->currentActivity();
            if (job_->report().points.size() != pointsCharted_) {
                pointsCharted_ = job_->report().points.size();
                study.charts = study.autoQuality.running ? benchCharts(job_->report(), ChartError::DisplayP99, targetSteps_) : benchCharts(job_->report());
            }
            if (!more) {
                study.running = false;
                study.status = {std::to_string(pointsCharted_) + " settings measured in " + std::to_string(int(job_->report().seconds)) + " s", false};
                if (study.autoQuality.running) finishAutoQuality(study);
                job_.reset();
            }
        } catch (const std::exception& e) {
            study.running = false;
            study.autoQuality.running = false;
            study.status = {e.what(), true};
            job_.reset();
        }
        if (!job_) pointsCharted_ = 0;
    }

    // The chosen bake and sampling on top of the session's: its environment cube and LUT stay.
    void applyAutoQuality(LabSession& session, FrameSettings& settings, ui::PanelState& panels) const
    {
        if (!choice_ || !choice_->found) return;
        session.setBakeSettings(bench::appliedBakeSettings(*choice_, session.bakeSettings()));
        settings.sampling = bench::appliedSampling(*choice_, settings.sampling);
        panels.bakeStatus = {"auto quality: baking " + bench::describeSettings(choice_->chosen.setting), false};
    }

    bool running() const { return bool(job_); }

private:
    void begin(const LabSession& session, const FrameSettings& settings, ui::StudyState& study, bool autoQuality)
    {
        if (!session.environment()) {
            study.status = {"no environment loaded yet", true};
            return;
        }
        if (settings.scene.kind == SceneKind::None) {
            study.status = {"the scene has no surfaces to measure: pick sphere, grid or a model", true};
            return;
        }
        try {
            if (!renderer_) renderer_ = std::make_unique<Renderer>(shaderDirectory());
            bench::BenchOptions options = bench::defaultBenchOptions(/*quick=*/true, assetDirectory().string());
            const Environment& environment = *session.environment();
            options.environments = {{std::filesystem::path(environment.source).stem().string(), environment.source,
                                     std::make_shared<const Environment>(environment)}};
            options.frame = settings;
            options.width = options.height = 96; // the quick run's 48 is for tests; 96 still sweeps in seconds
            if (autoQuality) {
                candidates_ = bench::autoCandidates(/*quick=*/true, bench::sceneFacts(settings, environment.image));
                options.points = candidates_.points;
                for (bench::SweepPoint& preset : bench::presetPoints(/*quick=*/true)) options.points.push_back(std::move(preset));
                options.referenceWidth = candidates_.referenceWidth;
                targetSteps_ = study.autoQuality.targetSteps;
            }
            job_ = std::make_unique<bench::BenchJob>(*renderer_, options);
            ui::AutoQualityState kept = study.autoQuality;
            study = {true, 0.0f, "", {}, {}, true, kept};
            study.autoQuality.running = autoQuality;
            if (autoQuality) {
                study.autoQuality.haveChoice = false;
                choice_.reset();
            }
        } catch (const std::exception& e) {
            study.status = {e.what(), true};
        }
    }

    void finishAutoQuality(ui::StudyState& study)
    {
        bench::BenchReport report = job_->report();
        choice_ = bench::chooseAuto(report, targetSteps_, candidates_);
        bench::markChosen(report.points, *choice_);
        study.charts = benchCharts(report, ChartError::DisplayP99, targetSteps_);
        ui::AutoQualityState& shown = study.autoQuality;
        shown.running = false;
        shown.haveChoice = choice_->found;
        shown.meetsTarget = choice_->meetsTarget;
        shown.reasons = choice_->reasons;
        shown.presets.clear();
        if (!choice_->found) {
            study.status = {choice_->reasons.back(), true};
            return;
        }
        const auto numbers = [](const bench::BenchPoint& p) {
            char text[160];
            std::snprintf(text, sizeof text, "cost %.1f ms (bake %.1f + frame %.2f), display p99 %.2f steps, RMS %.2f", p.costMilliseconds,
                          p.bakeMilliseconds, p.frameMilliseconds, p.display.p99Steps, p.display.rmsSteps);
            return std::string(text);
        };
        shown.chosen = bench::describeSettings(choice_->chosen.setting);
        shown.numbers = numbers(choice_->chosen);
        for (const bench::BenchPoint& p : report.points)
            if (p.setting.family == "preset") shown.presets.push_back(p.setting.mark + " preset: " + numbers(p));
    }

    std::unique_ptr<Renderer> renderer_;
    std::unique_ptr<bench::BenchJob> job_;
    std::size_t pointsCharted_ = 0;
    bench::AutoCandidates candidates_;
    double targetSteps_ = bench::kDefaultAutoTargetSteps;
    std::optional<bench::AutoChoice> choice_;
};

int runGui(const GuiOptions& options)
{
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    GlfwLibrary glfw;
    Window window(options.width, options.height, kDebugContext);
    gl::requireCurrentContextFeatures();
    gl::DebugOutput debug;
    if (gl::currentContextHasDebugOutput()) {
        debug.onMessage = [](const gl::DebugMessage& m) { std::fprintf(stderr, "iblab: %s\n", m.text.c_str()); };
        debug.install();
    }
    ImGuiLayer imgui(window.handle);
    glfwSetDropCallback(window.handle, onDrop);

    FrameSettings settings = options.settings;
    Renderer renderer(shaderDirectory());
    bake::BakeSettings bakeSettings = bake::defaultPreset();
    ui::PanelState panels;
    if (const ConventionPreset* convention = findConvention(options.convention)) {
        bakeSettings = conventionBakeSettings(*convention);
        applyConvention(*convention, settings.sampling);
        panels.convention = convention->name;
    }
    LabSession session(renderer, bakeSettings);
    panels.catalog = session.catalog();
    // The environment loads on a worker thread and bakes in slices: the window is up at once.
    session.requestEnvironment(settings.environment.source);
    bool frameWhenReady = settings.camera.distance <= 0.0f;
    if (frameWhenReady) settings.camera.distance = 3.5f;
    if (settings.scene.kind == SceneKind::Model) panels.sceneStatus = session.loadModel(settings.scene.modelPath, settings);

    ui::FrameStats stats;
    stats.renderer = gl::describeCurrentContext();
    bool firstFrame = true;
    int framesShown = 0;
    auto previousFrame = Clock::now();
    OrbitInput orbit;
    SplitDividerInput divider;
    std::vector<SphereReading> furnaceReadings; // of the previous frame, printed over the spheres
    float previousScale = 1.0f;
    bool idle = false;
    std::string lastRenderedKey; // settings + size of the image on screen
    StudyRun study;
    while (!glfwWindowShouldClose(window.handle)) {
        // Idle and converged: sleep until input instead of re-rendering the same image.
        if (idle) glfwWaitEventsTimeout(0.25);
        else glfwPollEvents();
        int windowWidth = 0, windowHeight = 0;
        glfwGetFramebufferSize(window.handle, &windowWidth, &windowHeight);
        // The 3D view is the part of the window right of the docked panel.
        const int viewX = panels.showPanels ? std::min(int(panels.panelWidth), windowWidth - 16) : 0;
        const int fbWidth = windowWidth - viewX, fbHeight = windowHeight;
        if (fbWidth <= 0 || fbHeight <= 0) { // minimised
            glfwWaitEvents();
            continue;
        }
        const glm::vec2 viewOrigin(float(viewX), 0.0f);
        for (const std::string& error : renderer.reloadShaders()) std::fprintf(stderr, "iblab: %s\n", error.c_str());

        // Background work first, within a budget that keeps the UI near interactive rates
        // on a software renderer.
        const LabSession::Finished finished = session.pump(settings, std::chrono::milliseconds(30));
        if (finished.environment) panels.environmentStatus = *finished.environment;
        if (finished.bake) panels.bakeStatus = *finished.bake;
        panels.activity = {session.activity(), session.progress()};
        study.advance(panels.study, std::chrono::milliseconds(30));

        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        ui::UiRequests requests;
        ui::drawControlWindow(settings, panels, stats, requests);
        const ImVec2 mouse = ImGui::GetIO().MousePos;
        drawViewOverlays(renderer, settings, fbWidth, fbHeight, viewOrigin, furnaceReadings,
                         glm::vec2(mouse.x - float(viewX), float(fbHeight) - mouse.y));
        const ImGuiIO& io = ImGui::GetIO();
        if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape)) && !io.WantTextInput) glfwSetWindowShouldClose(window.handle, 1);
        if (ImGui::IsKeyPressed(GLFW_KEY_F12)) requests.captureTo = std::string(panels.capture.path);
        if (!io.WantCaptureMouse && !divider.update(settings.view, io, viewX, fbWidth)) orbit.update(settings.camera, io, requests);
        ImGui::Render();

        for (const std::string& dropped : std::exchange(g_droppedFiles, {})) handleDrop(dropped, requests, panels);
        if (requests.loadEnvironment) session.requestEnvironment(*requests.loadEnvironment);
        if (requests.loadModel) {
            panels.sceneStatus = session.loadModel(*requests.loadModel, settings);
            requests.frameScene = !panels.sceneStatus.isError;
        }
        if (requests.loadPreset) panels.presetStatus = loadPreset(*requests.loadPreset, settings, session);
        if (requests.savePreset) panels.presetStatus = savePreset(*requests.savePreset, settings);
        if (requests.exportModel) panels.sceneStatus = session.exportModel(*requests.exportModel, settings);
        if (requests.applyConvention)
            if (const ConventionPreset* convention = findConvention(*requests.applyConvention)) {
                session.setBakeSettings(conventionBakeSettings(*convention));
                applyConvention(*convention, settings.sampling);
                panels.convention = convention->name;
                panels.bakeStatus = {"convention " + std::string(convention->title) + ": baking its preset \"" + std::string(convention->bakePreset) + "\"", false};
            }
        if (requests.startStudy) study.start(session, settings, panels.study);
        if (requests.stopStudy) study.stop(panels.study);
        if (requests.startAutoQuality) study.startAutoQuality(session, settings, panels.study);
        if (requests.applyAutoQuality) study.applyAutoQuality(session, settings, panels);
        if (requests.sceneChanged || requests.frameScene || (frameWhenReady && renderer.hasBake())) {
            const SceneInfo scene = renderer.sceneInfo(settings);
            frameBox(settings.camera, scene.centre, scene.halfExtents, float(fbWidth) / float(fbHeight));
            frameWhenReady = false;
        }

        if (settings.view.mode == ViewMode::Furnace) session.ensureFurnaceBake();
        // Responsive on a software renderer: while the user drags something, expensive
        // frames render fewer pixels (aiming at ~30 fps); when idle, the sampled method
        // refines progressively instead of re-rendering the same noisy image.
        const bool interacting = ImGui::IsAnyItemActive() || ImGui::IsMouseDragging(ImGuiMouseButton_Left) || io.MouseWheel != 0.0f;
        Renderer::Options renderOptions;
        if (interacting && !requests.captureTo && stats.renderMs > 33.0)
            renderOptions.resolutionScale = std::clamp(float(std::sqrt(33.0 / stats.renderMs * double(previousScale * previousScale))), 0.25f, 1.0f);
        renderOptions.accumulate = !interacting;
        previousScale = renderOptions.resolutionScale;
        // The error view's reference, one budgeted slice of work per idle frame (a drag
        // would restart it every frame; it resumes when the drag ends).
        const bool errorView = settings.view.mode == ViewMode::Error;
        if (errorView)
            panels.compare.reference = interacting || session.busy() ? renderer.referenceStatus(settings, fbWidth, fbHeight)
                                                                     : renderer.advanceReference(settings, fbWidth, fbHeight, kReferenceBudgetPerFrame);
        // A finished image needs no more frames: split-sum is deterministic, the sampled
        // method stops refining after kMaxAccumulatedFrames, and the error view waits for
        // its reference (whose completion changes the image, hence its place in the key).
        const bool referencePending = errorView && !panels.compare.reference.complete;
        const std::string renderKey = toJsonText(settings, -1) + std::to_string(fbWidth) + "x" + std::to_string(fbHeight) +
                                      (errorView && panels.compare.reference.complete ? " with reference" : "");
        const bool converged = renderKey == lastRenderedKey && !interacting && !session.busy() && !requests.captureTo &&
                               renderer.accumulatedFrames() >= (renderer.lastFrameWasSampled() ? kMaxAccumulatedFrames : 1);
        idle = converged && !referencePending && !study.running() && !ImGui::IsAnyItemHovered() && !io.WantTextInput;
        lastRenderedKey = renderKey;
        const auto renderStart = Clock::now();
        if (!converged) renderer.renderFrame(settings, fbWidth, fbHeight, renderOptions);
        stats.resolutionScale = renderOptions.resolutionScale;
        stats.accumulatedFrames = renderer.accumulatedFrames();
        glFinish(); // so that the reported pass time is the GPU's, not the submission's
        if (!converged) stats.renderMs = std::chrono::duration<double, std::milli>(Clock::now() - renderStart).count();
        stats.width = fbWidth;
        stats.height = fbHeight;
        furnaceReadings = settings.view.mode == ViewMode::Furnace ? renderer.measureSpheres(settings) : std::vector<SphereReading>{};
        if (!converged) panels.compare.error = errorView ? renderer.measureError(settings) : ErrorReport{};
        if (requests.captureTo) panels.captureStatus = session.capture(*requests.captureTo, settings);

        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glViewport(0, 0, windowWidth, windowHeight);
        glClearColor(0.06f, 0.06f, 0.07f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        renderer.presentToDefaultFramebuffer(viewX, 0, windowWidth, windowHeight);
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        glfwSwapBuffers(window.handle);

        const auto now = Clock::now();
        stats.frameMs = std::chrono::duration<double, std::milli>(now - previousFrame).count();
        previousFrame = now;
        if (firstFrame) {
            std::printf("iblab: first frame %.0f ms after start (%s)\n", std::chrono::duration<double, std::milli>(now - start).count(),
                        stats.renderer.c_str());
            std::fflush(stdout);
            firstFrame = false;
        }
        if (options.quitAfterFrames > 0 && ++framesShown >= options.quitAfterFrames) break;
    }
    return 0;
}

} // namespace iblab::app
