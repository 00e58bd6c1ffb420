#pragma once
#include <chrono>
#include <string>

#include "frame/settings.hpp"

namespace iblab::app {

struct RenderJob {
    FrameSettings settings;
    std::string convention; // conventions.hpp; empty: the default bake and the settings as given
    int width = 1280;
    int height = 720;
    std::string output;   // .png or .exr
    int timingRepeats = 0; // > 0: re-render that many times and report the median frame time
    bool json = false;     // print a JSON report on stdout instead of a line of text
    bool glDebug = false;  // a KHR_debug context even in release builds; GL errors fail the job
};

// Renders one frame with no window (EGL) and writes it. Returns the exit status; prints
// a one-line reason on stderr when it fails.
int runHeadlessRender(const RenderJob& job, std::chrono::steady_clock::time_point processStart);

} // namespace iblab::app
