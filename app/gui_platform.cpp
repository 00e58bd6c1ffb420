#include "gui_platform.hpp"

#include <array>
#include <cstdio>
#include <cstdlib>
#include <utility>
#include <algorithm>

#include <epoxy/gl.h>
// GLFW after epoxy: epoxy provides the GL declarations GLFW would otherwise pull in.
#include <GLFW/glfw3.h>
#include <imgui.h>

#include "gl/headless_context.hpp"
#include "gl/render_target.hpp"

namespace iblab::app {

WindowPixels GuiPlatform::readPixels() const
{
    WindowPixels pixels{width(), height(), {}};
    pixels.rgba.resize(std::size_t(pixels.width) * std::size_t(pixels.height) * 4);
    std::vector<std::uint8_t> bottomUp(pixels.rgba.size());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer());
    if (framebuffer() == 0) glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, pixels.width, pixels.height, GL_RGBA, GL_UNSIGNED_BYTE, bottomUp.data());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    const std::size_t row = std::size_t(pixels.width) * 4;
    for (int y = 0; y < pixels.height; ++y)
        std::copy_n(bottomUp.begin() + std::ptrdiff_t(std::size_t(pixels.height - 1 - y) * row), row,
                    pixels.rgba.begin() + std::ptrdiff_t(std::size_t(y) * row));
    return pixels;
}

bool displayAvailable()
{
    if (!std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY")) return false;
    glfwSetErrorCallback(nullptr);
    if (!glfwInit()) return false;
    glfwTerminate();
    return true;
}

namespace {

class WindowPlatform final : public GuiPlatform {
public:
    WindowPlatform(int width, int height, bool debug)
    {
        glfwSetErrorCallback([](int code, const char* description) { std::fprintf(stderr, "iblab: GLFW error %d: %s\n", code, description); });
        if (!glfwInit()) throw WindowUnavailable("no window system: glfwInit failed (is DISPLAY set?)");
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
        glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
        glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
        glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, debug ? GLFW_TRUE : GLFW_FALSE);
        window_ = glfwCreateWindow(width, height, "iblab", nullptr, nullptr);
        if (!window_) {
            glfwTerminate();
            throw WindowUnavailable("cannot create a window with an OpenGL 4.5 core context");
        }
        glfwMakeContextCurrent(window_);
        glfwSwapInterval(1);
        glfwSetWindowUserPointer(window_, this);
        installCallbacks();
        cursors_[ImGuiMouseCursor_Arrow] = glfwCreateStandardCursor(GLFW_ARROW_CURSOR);
        cursors_[ImGuiMouseCursor_TextInput] = glfwCreateStandardCursor(GLFW_IBEAM_CURSOR);
        cursors_[ImGuiMouseCursor_ResizeNS] = glfwCreateStandardCursor(GLFW_VRESIZE_CURSOR);
        cursors_[ImGuiMouseCursor_ResizeEW] = glfwCreateStandardCursor(GLFW_HRESIZE_CURSOR);
        cursors_[ImGuiMouseCursor_Hand] = glfwCreateStandardCursor(GLFW_HAND_CURSOR);
    }

    ~WindowPlatform() override
    {
        for (GLFWcursor* cursor : cursors_)
            if (cursor) glfwDestroyCursor(cursor);
        glfwDestroyWindow(window_);
        glfwTerminate();
    }

    void collectEvents(InputQueue& queue, double waitSeconds) override
    {
        for (InputEvent& event : std::exchange(late_, {})) queue.push(std::move(event));
        pending_ = &queue;
        if (waitSeconds > 0.0) glfwWaitEventsTimeout(waitSeconds);
        else glfwPollEvents();
        pending_ = nullptr;
    }

    int width() const override { return size(0); }
    int height() const override { return size(1); }
    void resize(int width, int height) override { glfwSetWindowSize(window_, width, height); }
    unsigned framebuffer() const override { return 0; }
    void present() override { glfwSwapBuffers(window_); }

    void setCursor(int imguiCursor) override
    {
        GLFWcursor* cursor = imguiCursor >= 0 && imguiCursor < int(cursors_.size()) ? cursors_[std::size_t(imguiCursor)] : nullptr;
        glfwSetCursor(window_, cursor ? cursor : cursors_[ImGuiMouseCursor_Arrow]);
    }

    std::string clipboard() const override
    {
        const char* text = glfwGetClipboardString(window_);
        return text ? text : "";
    }
    void setClipboard(const std::string& text) override { glfwSetClipboardString(window_, text.c_str()); }
    PlatformKind kind() const override { return PlatformKind::Window; }

private:
    int size(int axis) const
    {
        int w = 0, h = 0;
        glfwGetFramebufferSize(window_, &w, &h);
        return axis == 0 ? w : h;
    }

    static void push(GLFWwindow* window, InputEvent event)
    {
        auto* self = static_cast<WindowPlatform*>(glfwGetWindowUserPointer(window));
        // Callbacks outside collectEvents (GLFW calls some from other functions) queue too.
        if (self->pending_) self->pending_->push(std::move(event));
        else self->late_.push_back(std::move(event));
    }

    void installCallbacks()
    {
        using T = InputEvent::Type;
        glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double x, double y) { push(w, {.type = T::CursorMoved, .x = x, .y = y}); });
        glfwSetCursorEnterCallback(window_, [](GLFWwindow* w, int entered) {
            if (!entered) push(w, {.type = T::CursorLeft});
        });
        glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int button, int action, int) {
            push(w, {.type = T::MouseButton, .code = button, .pressed = action == GLFW_PRESS});
        });
        glfwSetScrollCallback(window_, [](GLFWwindow* w, double x, double y) { push(w, {.type = T::Scroll, .x = x, .y = y}); });
        glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int action, int) {
            if (action != GLFW_REPEAT) push(w, {.type = T::Key, .code = key, .pressed = action == GLFW_PRESS});
        });
        glfwSetCharCallback(window_, [](GLFWwindow* w, unsigned codepoint) { push(w, {.type = T::Text, .codepoint = codepoint}); });
        glfwSetWindowFocusCallback(window_, [](GLFWwindow* w, int focused) { push(w, {.type = T::Focus, .pressed = focused != 0}); });
        glfwSetDropCallback(window_, [](GLFWwindow* w, int count, const char** paths) {
            InputEvent event{.type = T::Drop};
            for (int i = 0; i < count; ++i) event.paths.emplace_back(paths[i]);
            push(w, std::move(event));
        });
        // The app decides whether closing loses work (it may ask first), so GLFW's own
        // close flag is taken back at once.
        glfwSetWindowCloseCallback(window_, [](GLFWwindow* w) {
            glfwSetWindowShouldClose(w, GLFW_FALSE);
            push(w, {.type = T::CloseRequest});
        });
        glfwSetFramebufferSizeCallback(window_, [](GLFWwindow* w, int width, int height) {
            push(w, {.type = T::Resize, .x = double(width), .y = double(height)});
        });
    }

    GLFWwindow* window_ = nullptr;
    // Events GLFW delivered outside collectEvents (window creation, resize requests).
    std::vector<InputEvent> late_;
    InputQueue* pending_ = nullptr;
    std::array<GLFWcursor*, ImGuiMouseCursor_COUNT> cursors_{};
};

class OffscreenPlatform final : public GuiPlatform {
public:
    OffscreenPlatform(int width, int height, bool debug) : context_(gl::HeadlessContextOptions{.debug = debug}) { resize(width, height); }

    void collectEvents(InputQueue&, double) override {}
    int width() const override { return target_.width(); }
    int height() const override { return target_.height(); }
    void resize(int width, int height) override { target_.ensure(GL_RGBA8, std::max(width, 1), std::max(height, 1)); }
    unsigned framebuffer() const override { return target_.framebuffer(); }
    void present() override { glFlush(); }
    void setCursor(int) override {}
    std::string clipboard() const override { return clipboard_; }
    void setClipboard(const std::string& text) override { clipboard_ = text; }
    PlatformKind kind() const override { return PlatformKind::Offscreen; }

private:
    gl::HeadlessContext context_;
    gl::RenderTarget target_;
    std::string clipboard_;
};

} // namespace

std::unique_ptr<GuiPlatform> makeWindowPlatform(int width, int height, bool debug)
{
    return std::make_unique<WindowPlatform>(width, height, debug);
}

std::unique_ptr<GuiPlatform> makeOffscreenPlatform(int width, int height, bool debug)
{
    return std::make_unique<OffscreenPlatform>(width, height, debug);
}

} // namespace iblab::app
