#pragma once
// Where the GUI runs: a GLFW window (a user's desktop, or Xvfb in the GUI tests), or an
// offscreen framebuffer in a headless EGL context (the same GUI frame with no display at
// all, for CI and scripts). Both feed one InputQueue and draw into one framebuffer; the app
// above them is the same code.
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "gui_input.hpp"

namespace iblab::app {

// No window could be opened (no window system, or no 4.5 core context for a window): the
// caller may render headless instead.
struct WindowUnavailable : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct WindowPixels {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba; // top row first, as the window shows it
};

enum class PlatformKind { Window, Offscreen };
// "window" or "offscreen": the name scripts and logs print.
inline const char* platformKindName(PlatformKind kind) { return kind == PlatformKind::Window ? "window" : "offscreen"; }

class GuiPlatform {
public:
    virtual ~GuiPlatform() = default;
    // Moves what happened since the last call into the queue, waiting up to `waitSeconds`
    // for something to happen (0: do not wait).
    virtual void collectEvents(InputQueue& queue, double waitSeconds) = 0;
    virtual int width() const = 0;
    virtual int height() const = 0;
    virtual void resize(int width, int height) = 0;
    // The GL framebuffer the frame is drawn into (0 for a window's back buffer).
    virtual unsigned framebuffer() const = 0;
    virtual void present() = 0;
    // The mouse cursor shape Dear ImGui asks for (ImGuiMouseCursor).
    virtual void setCursor(int imguiCursor) = 0;
    virtual std::string clipboard() const = 0;
    virtual void setClipboard(const std::string& text) = 0;
    virtual PlatformKind kind() const = 0;
    // The drawn frame, read back before present().
    WindowPixels readPixels() const;
};

// A 4.5 core window of width x height (KHR_debug context when `debug`). Throws
// WindowUnavailable when there is no window system or no such context.
std::unique_ptr<GuiPlatform> makeWindowPlatform(int width, int height, bool debug);
// A headless EGL context and an RGBA8 framebuffer of width x height.
std::unique_ptr<GuiPlatform> makeOffscreenPlatform(int width, int height, bool debug);

// True when a window system is reachable (glfwInit succeeds).
bool displayAvailable();

} // namespace iblab::app
