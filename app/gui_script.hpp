#pragma once
// GUI scripts: real input (mouse, wheel, keys, text, dropped files, the close button)
// injected frame by frame into the GUI's input queue, where GLFW's callbacks put a user's
// input, with checks on the state (settings, panels, popups) and on the pixels drawn. The
// language is described in docs/gui-scripts.md; `iblab --script FILE` runs one, in a window
// when there is a display and offscreen otherwise (or with --offscreen). The parser is
// gui_script_parser.cpp, the runner gui_script_runner.cpp, and what the checks compare and
// measure gui_script_checks.hpp.
#include <optional>
#include <string>
#include <vector>

namespace iblab::app {

class GuiApp;

struct ScriptStep {
    int line = 0;
    std::string command;
    std::vector<std::string> args; // quotes removed
    std::string text;              // the line as written, for messages
};

// How many arguments a command takes, nullopt for a name that is no command: the runner's
// table of commands (gui_script_runner.cpp), which the parser checks scripts against.
struct ScriptCommandShape {
    int minArgs = 0, maxArgs = 0;
};
std::optional<ScriptCommandShape> scriptCommandShape(const std::string& command);

// Splits a script into steps. Throws std::runtime_error naming the line of a malformed one
// (an unknown command, an unterminated quote, a wrong number of arguments).
std::vector<ScriptStep> parseGuiScript(const std::string& text);

// A key chord such as "ctrl+shift+s", "Escape", "F12", "KP_Add": the GLFW key code and the
// modifier keys (GLFW codes of their left-hand keys) to hold around it.
struct KeyChord {
    int key = 0;
    std::vector<int> modifiers;
};
std::optional<KeyChord> parseKeyChord(const std::string& text);

// Runs the script at path against app; returns 0 when every step and check passed, 1 at the
// first failure (printed as "FILE:LINE: step: reason"), 2 when the script cannot be read or
// parsed. coverageOut, if not empty, receives the controls shown and used (JSON).
int runGuiScript(GuiApp& app, const std::string& path, const std::string& coverageOut);

} // namespace iblab::app
