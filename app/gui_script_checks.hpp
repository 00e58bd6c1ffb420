#pragma once
// What a GUI script's checks compare and measure, apart from the app that is driven: the
// state's JSON values against expectations (with float tolerance, and "contains" for
// strings and lists), and window pixels (a region's mean level, the mean difference from
// a snapshot). A failed check, or a step that cannot do what it says, throws StepFailed,
// which the runner (gui_script_runner.cpp) reports as FILE:LINE: step: reason.
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "gui_platform.hpp"

namespace iblab::app {

struct StepFailed : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Window pixels x0 <= x < x1, y0 <= y < y1, y down as the window's.
struct Region {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

// What `snapshot` keeps for expect-changed and expect-unchanged.
struct Snapshot {
    Region region;
    WindowPixels pixels;
};

// The mean of (R + G + B) / 3 over the region (clipped to the pixels); StepFailed when empty.
double meanLevel(const WindowPixels& pixels, Region region);

// The mean absolute channel difference over the snapshot's region; 255 when the window
// size has changed since.
double meanDifference(const Snapshot& before, const WindowPixels& now);

// actual OP expected, OP one of == != < <= > >= ~ (within 1%) contains. Numbers compare
// with a relative tolerance of 1e-5 (settings travel as float); other values by equality
// or containment. On false, `why` says what was found.
bool compareValues(const nlohmann::json& actual, const std::string& op, const nlohmann::json& expected, std::string& why);

// The state's value at the JSON pointer `pointerText` compared with `valueText` parsed as
// JSON (a bare word is a string: grid, splitsum).
bool checkState(const nlohmann::json& state, const std::string& pointerText, const std::string& op,
                const std::string& valueText, std::string& why);

} // namespace iblab::app
