#include "gui_input.hpp"

#include <cfloat>
#include <set>

#include <GLFW/glfw3.h>
#include <imgui.h>

namespace iblab::app {

void mapGlfwKeys(ImGuiIO& io)
{
    io.KeyMap[ImGuiKey_Tab] = GLFW_KEY_TAB;
    io.KeyMap[ImGuiKey_LeftArrow] = GLFW_KEY_LEFT;
    io.KeyMap[ImGuiKey_RightArrow] = GLFW_KEY_RIGHT;
    io.KeyMap[ImGuiKey_UpArrow] = GLFW_KEY_UP;
    io.KeyMap[ImGuiKey_DownArrow] = GLFW_KEY_DOWN;
    io.KeyMap[ImGuiKey_PageUp] = GLFW_KEY_PAGE_UP;
    io.KeyMap[ImGuiKey_PageDown] = GLFW_KEY_PAGE_DOWN;
    io.KeyMap[ImGuiKey_Home] = GLFW_KEY_HOME;
    io.KeyMap[ImGuiKey_End] = GLFW_KEY_END;
    io.KeyMap[ImGuiKey_Insert] = GLFW_KEY_INSERT;
    io.KeyMap[ImGuiKey_Delete] = GLFW_KEY_DELETE;
    io.KeyMap[ImGuiKey_Backspace] = GLFW_KEY_BACKSPACE;
    io.KeyMap[ImGuiKey_Space] = GLFW_KEY_SPACE;
    io.KeyMap[ImGuiKey_Enter] = GLFW_KEY_ENTER;
    io.KeyMap[ImGuiKey_Escape] = GLFW_KEY_ESCAPE;
    io.KeyMap[ImGuiKey_KeyPadEnter] = GLFW_KEY_KP_ENTER;
    io.KeyMap[ImGuiKey_A] = GLFW_KEY_A;
    io.KeyMap[ImGuiKey_C] = GLFW_KEY_C;
    io.KeyMap[ImGuiKey_V] = GLFW_KEY_V;
    io.KeyMap[ImGuiKey_X] = GLFW_KEY_X;
    io.KeyMap[ImGuiKey_Y] = GLFW_KEY_Y;
    io.KeyMap[ImGuiKey_Z] = GLFW_KEY_Z;
}

namespace {

bool isModifier(int glfwKey)
{
    return glfwKey == GLFW_KEY_LEFT_CONTROL || glfwKey == GLFW_KEY_RIGHT_CONTROL || glfwKey == GLFW_KEY_LEFT_SHIFT || glfwKey == GLFW_KEY_RIGHT_SHIFT ||
           glfwKey == GLFW_KEY_LEFT_ALT || glfwKey == GLFW_KEY_RIGHT_ALT || glfwKey == GLFW_KEY_LEFT_SUPER || glfwKey == GLFW_KEY_RIGHT_SUPER;
}

} // namespace

FrameRequests InputQueue::applyFrame(ImGuiIO& io)
{
    FrameRequests requests;
    std::set<int> buttonsChanged, keysChanged;
    bool textGiven = false;
    bool keyPressedThisFrame = false; // a key other than a modifier
    while (!events_.empty()) {
        const InputEvent& e = events_.front();
        switch (e.type) {
        case InputEvent::Type::CursorMoved:
            if (!buttonsChanged.empty()) return requests; // a click lands where it was made
            io.MousePos = ImVec2(float(e.x), float(e.y));
            break;
        case InputEvent::Type::CursorLeft:
            if (!buttonsChanged.empty()) return requests;
            io.MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
            break;
        case InputEvent::Type::MouseButton:
            if (e.code < 0 || e.code >= int(IM_ARRAYSIZE(io.MouseDown))) break;
            if (!buttonsChanged.insert(e.code).second) return requests;
            io.MouseDown[e.code] = e.pressed;
            requests.userActed = requests.userActed || e.pressed;
            break;
        case InputEvent::Type::Scroll:
            io.MouseWheelH += float(e.x);
            io.MouseWheel += float(e.y);
            requests.userActed = true;
            break;
        case InputEvent::Type::Key:
            if (e.code < 0 || e.code >= int(IM_ARRAYSIZE(io.KeysDown))) break;
            // ImGui reads the modifiers once a frame: Ctrl released in the frame S went down
            // (a fast Ctrl+S, released Ctrl first) made S a plain S, and the shortcut was lost.
            if (isModifier(e.code) && keyPressedThisFrame) return requests;
            if (textGiven || !keysChanged.insert(e.code).second) return requests;
            io.KeysDown[e.code] = e.pressed;
            keyPressedThisFrame = keyPressedThisFrame || (e.pressed && !isModifier(e.code));
            requests.userActed = requests.userActed || e.pressed;
            io.KeyCtrl = io.KeysDown[GLFW_KEY_LEFT_CONTROL] || io.KeysDown[GLFW_KEY_RIGHT_CONTROL];
            io.KeyShift = io.KeysDown[GLFW_KEY_LEFT_SHIFT] || io.KeysDown[GLFW_KEY_RIGHT_SHIFT];
            io.KeyAlt = io.KeysDown[GLFW_KEY_LEFT_ALT] || io.KeysDown[GLFW_KEY_RIGHT_ALT];
            io.KeySuper = io.KeysDown[GLFW_KEY_LEFT_SUPER] || io.KeysDown[GLFW_KEY_RIGHT_SUPER];
            break;
        case InputEvent::Type::Text:
            if (!keysChanged.empty()) return requests;
            io.AddInputCharacter(e.codepoint);
            textGiven = true;
            requests.userActed = true;
            break;
        case InputEvent::Type::Focus: io.AddFocusEvent(e.pressed); break;
        case InputEvent::Type::Drop:
            requests.dropped.insert(requests.dropped.end(), e.paths.begin(), e.paths.end());
            requests.userActed = true;
            break;
        case InputEvent::Type::CloseRequest: requests.closeRequested = true; break;
        case InputEvent::Type::Resize:
            requests.resized = true;
            requests.width = int(e.x);
            requests.height = int(e.y);
            break;
        }
        events_.pop_front();
    }
    return requests;
}

} // namespace iblab::app
