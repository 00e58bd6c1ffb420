#pragma once
#include <stdexcept>
#include <string>

#include "settings.hpp"

namespace iblab::app {

struct GuiOptions {
    FrameSettings settings;
    std::string convention; // conventions.hpp; empty: the default bake and the settings as given
    int width = 1280;
    int height = 720;
    int quitAfterFrames = 0; // > 0: close after that many frames (scripted start-up timing)
};

// No window could be opened (no window system, or no 4.5 core context for a window): the
// caller may render headless instead.
struct WindowUnavailable : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// True when a window system is reachable (glfwInit succeeds).
bool displayAvailable();
// Runs the window until closed. Throws std::runtime_error when no window can be made.
int runGui(const GuiOptions& options);

} // namespace iblab::app
