#pragma once
// The GUI's input, as events in the order they happened: GLFW's callbacks push them for a
// real window, a script (gui_script.hpp) pushes them for tests, and both reach Dear ImGui
// through the same queue. Dear ImGui 1.86 reads input as per-frame state (io.MouseDown,
// io.KeysDown), so a key tapped or a button clicked within one slow frame (250-600 ms
// under a software rasteriser) would be seen neither down nor up; the queue hands events
// over a frame at a time and holds back any event that would undo one already given this
// frame, as Dear ImGui 1.87's own input queue does ("trickling").
#include <deque>
#include <string>
#include <vector>

struct ImGuiIO;

namespace iblab::app {

struct InputEvent {
    enum class Type {
        CursorMoved,  // x, y in window pixels, y down
        CursorLeft,   // the cursor left the window
        MouseButton,  // button (0 left, 1 right, 2 middle), pressed
        Scroll,       // x, y: wheel steps
        Key,          // key (GLFW_KEY_*), pressed
        Text,         // codepoint
        Focus,        // pressed = focused
        Drop,         // paths
        CloseRequest, // the window's close button (or the window manager)
        Resize,       // x, y: the new window size
    };
    Type type = Type::CursorMoved;
    double x = 0.0, y = 0.0;
    int code = 0;       // button or key
    bool pressed = false;
    unsigned codepoint = 0;
    std::vector<std::string> paths = {};
};

// What one frame's input asks of the app beyond Dear ImGui.
struct FrameRequests {
    std::vector<std::string> dropped;
    bool closeRequested = false;
    bool userActed = false; // a button or key pressed, text typed, the wheel turned, a file dropped
    bool resized = false;
    int width = 0, height = 0;
};

class InputQueue {
public:
    void push(InputEvent event) { events_.push_back(std::move(event)); }
    bool empty() const { return events_.empty(); }
    std::size_t size() const { return events_.size(); }

    // Applies the events of one frame to io (mouse, wheel, keys, modifiers, text, focus)
    // and returns the rest; stops before an event that would merge with one already applied
    // (a second change of the same button or key, a move after a button change, text after
    // a key change or a key change after text, a modifier's change after another key's
    // press), which then waits for the next frame.
    FrameRequests applyFrame(ImGuiIO& io);

private:
    std::deque<InputEvent> events_;
};

// io.KeyMap for GLFW key codes (the codes every event carries, window or script).
void mapGlfwKeys(ImGuiIO& io);

} // namespace iblab::app
