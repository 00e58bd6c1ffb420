#include "gui_app.hpp"

#include <chrono>
#include <filesystem>
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
        if (!glfwInit()) throw std::runtime_error("no window system: glfwInit failed (is DISPLAY set?)");
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
        if (!handle) throw std::runtime_error("cannot create a window with an OpenGL 4.5 core context");
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
    LabSession session(renderer);
    ui::PanelState panels;
    panels.catalog = session.catalog();
    panels.environmentStatus = session.loadEnvironment(settings.environment.source, settings);
    if (panels.environmentStatus.isError) {
        // The requested environment failed: fall back to the bundled default so there is a sky.
        std::fprintf(stderr, "iblab: %s\n", panels.environmentStatus.text.c_str());
        session.loadEnvironment(defaultEnvironmentSpec(), settings);
    }

    ui::FrameStats stats;
    stats.renderer = gl::describeCurrentContext();
    bool firstFrame = true;
    int framesShown = 0;
    auto previousFrame = Clock::now();
    while (!glfwWindowShouldClose(window.handle)) {
        glfwPollEvents();
        int fbWidth = 0, fbHeight = 0;
        glfwGetFramebufferSize(window.handle, &fbWidth, &fbHeight);
        if (fbWidth <= 0 || fbHeight <= 0) { // minimised
            glfwWaitEvents();
            continue;
        }
        for (const std::string& error : renderer.reloadShaders()) std::fprintf(stderr, "iblab: %s\n", error.c_str());

        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        ui::UiRequests requests;
        ui::drawControlWindow(settings, panels, stats, requests);
        if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape)) && !ImGui::GetIO().WantTextInput) glfwSetWindowShouldClose(window.handle, 1);
        if (ImGui::IsKeyPressed(GLFW_KEY_F12)) requests.captureTo = std::string(panels.capture.path);
        ImGui::Render();

        for (const std::string& dropped : std::exchange(g_droppedFiles, {})) {
            const std::string extension = std::filesystem::path(dropped).extension().string();
            if (extension == ".exr" || extension == ".hdr" || extension == ".EXR" || extension == ".HDR")
                requests.loadEnvironment = dropped;
            else
                panels.environmentStatus = {dropped + ": not an environment (drop an .exr or .hdr file)", true};
        }
        if (requests.loadEnvironment) panels.environmentStatus = session.loadEnvironment(*requests.loadEnvironment, settings);

        const auto renderStart = Clock::now();
        renderer.renderFrame(settings, fbWidth, fbHeight);
        glFinish(); // so that the reported pass time is the GPU's, not the submission's
        stats.renderMs = std::chrono::duration<double, std::milli>(Clock::now() - renderStart).count();
        stats.width = fbWidth;
        stats.height = fbHeight;
        if (requests.captureTo) panels.captureStatus = session.capture(*requests.captureTo, settings);

        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glViewport(0, 0, fbWidth, fbHeight);
        renderer.presentToDefaultFramebuffer(fbWidth, fbHeight);
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
