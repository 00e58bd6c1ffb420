#pragma once
// The GUI: a docked control panel beside the 3D view, on a window or offscreen
// (gui_platform.hpp). GuiApp is the lab's state and one frame of it; runGui is init, the
// frame loop and shutdown. Scripts (gui_script.hpp) drive the same GuiApp through its input
// queue and read state() to check what a user would see.
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "gui_platform.hpp"
#include "gui_prefs.hpp"
#include "frame/settings.hpp"

namespace iblab::ui {
class ItemRegistry;
}

namespace iblab::app {

struct GuiOptions {
    FrameSettings settings;
    std::string convention; // conventions.hpp; empty: the default bake and the settings as given
    int width = 1280;
    int height = 720;
    int quitAfterFrames = 0; // > 0: close after that many frames (scripted start-up timing)
    std::string script;      // a GUI script (gui_script.hpp): run it, then exit with its verdict
    bool offscreen = false;  // no window: the GUI frame in a headless EGL context
    std::string coverageOut; // with a script: write the controls it showed and used (JSON)
    bool windowSizeGiven = false; // --window-size: it wins over the remembered size
    // What the last session left (gui_prefs.hpp); nullopt on the first run.
    std::optional<GuiPrefs> remembered;
};

class GuiApp {
public:
    GuiApp(GuiPlatform& platform, const GuiOptions& options);
    ~GuiApp();
    GuiApp(const GuiApp&) = delete;
    GuiApp& operator=(const GuiApp&) = delete;

    // One frame: input, background work (loading, baking, the study), the panels, the 3D
    // view when it changed, presentation. Waits for input first when idle(), unless scripted.
    void frame();
    // A script advances ImGui's clock by a fixed step per frame (double-clicks and key
    // repeat then do not depend on how long a software-rendered frame takes), and the
    // loop never sleeps waiting for input.
    void setScripted(bool scripted);

    bool quitRequested() const;
    // Nothing left to do until the next input: no load, bake, refinement, reference or
    // study running, no queued input.
    bool idle() const;
    InputQueue& input();
    GuiPlatform& platform();
    // What a script can check: settings, panels, session, renderer, the UI's popups, in
    // JSON (the keys are listed in docs/gui-scripts.md).
    nlohmann::json state() const;
    // The window as drawn by the last frame (read back during it; see requestPixels).
    const WindowPixels& lastPixels() const;
    // The next frame keeps a copy of what it drew, for lastPixels().
    void requestPixels();
    const ui::ItemRegistry& items() const;
    // What to remember for the next session: open sections, paths, the window's size.
    GuiPrefs prefs() const;
    int glErrorCount() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// Runs the GUI until it is closed (or its script ends); returns the exit status. Throws
// WindowUnavailable when no window can be made.
int runGui(const GuiOptions& options);

} // namespace iblab::app
