// The GUI script language: lines split into tokens (double quotes group, backslash escapes,
// '#' starts a comment, ${NAME} expands an environment variable), each command checked
// against its number of arguments and key chords against the key names, so that a script
// with a typo fails before a single frame runs. The commands, their arguments and what each
// does are one table in the runner (gui_script_runner.cpp); docs/gui-scripts.md describes them.
#include "gui_script.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <map>
#include <sstream>
#include <stdexcept>

#include <GLFW/glfw3.h>

namespace iblab::app {
namespace {

// ${NAME} becomes the environment variable's value, so that a script can name files
// wherever a test or a user keeps them (${IBLAB_ASSET_DIR}/models/...). An unset variable is
// an error rather than an empty string that would make a wrong path.
std::string expandVariables(const std::string& token, int lineNumber)
{
    std::string out;
    for (std::size_t i = 0; i < token.size(); ++i) {
        if (token.compare(i, 2, "${") != 0) {
            out += token[i];
            continue;
        }
        const std::size_t end = token.find('}', i);
        if (end == std::string::npos) throw std::runtime_error("line " + std::to_string(lineNumber) + ": unterminated ${");
        const std::string name = token.substr(i + 2, end - i - 2);
        const char* value = std::getenv(name.c_str());
        if (!value) throw std::runtime_error("line " + std::to_string(lineNumber) + ": environment variable " + name + " is not set");
        out += value;
        i = end;
    }
    return out;
}

std::vector<std::string> tokenize(const std::string& line, int lineNumber)
{
    std::vector<std::string> tokens;
    std::size_t i = 0;
    while (i < line.size()) {
        if (std::isspace(static_cast<unsigned char>(line[i]))) {
            ++i;
            continue;
        }
        if (line[i] == '#') break;
        std::string token;
        if (line[i] == '"') {
            ++i;
            bool closed = false;
            while (i < line.size()) {
                if (line[i] == '\\' && i + 1 < line.size()) {
                    token += line[i + 1];
                    i += 2;
                } else if (line[i] == '"') {
                    closed = true;
                    ++i;
                    break;
                } else {
                    token += line[i++];
                }
            }
            if (!closed) throw std::runtime_error("line " + std::to_string(lineNumber) + ": unterminated quote");
        } else {
            while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) token += line[i++];
        }
        tokens.push_back(expandVariables(token, lineNumber));
    }
    return tokens;
}

std::string lower(std::string text)
{
    std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return text;
}

const std::map<std::string, int>& keyNames()
{
    static const std::map<std::string, int> names = [] {
        std::map<std::string, int> n = {
            {"escape", GLFW_KEY_ESCAPE},   {"esc", GLFW_KEY_ESCAPE},        {"enter", GLFW_KEY_ENTER},     {"return", GLFW_KEY_ENTER},
            {"tab", GLFW_KEY_TAB},         {"space", GLFW_KEY_SPACE},       {"backspace", GLFW_KEY_BACKSPACE}, {"delete", GLFW_KEY_DELETE},
            {"insert", GLFW_KEY_INSERT},   {"left", GLFW_KEY_LEFT},         {"right", GLFW_KEY_RIGHT},     {"up", GLFW_KEY_UP},
            {"down", GLFW_KEY_DOWN},       {"home", GLFW_KEY_HOME},         {"end", GLFW_KEY_END},         {"pageup", GLFW_KEY_PAGE_UP},
            {"pagedown", GLFW_KEY_PAGE_DOWN}, {"minus", GLFW_KEY_MINUS},    {"equal", GLFW_KEY_EQUAL},     {"plus", GLFW_KEY_KP_ADD},
            {"kp_add", GLFW_KEY_KP_ADD},   {"kp_subtract", GLFW_KEY_KP_SUBTRACT}, {"kp_enter", GLFW_KEY_KP_ENTER},
            {"ctrl", GLFW_KEY_LEFT_CONTROL}, {"shift", GLFW_KEY_LEFT_SHIFT}, {"alt", GLFW_KEY_LEFT_ALT},   {"super", GLFW_KEY_LEFT_SUPER},
        };
        for (char c = 'a'; c <= 'z'; ++c) n[std::string(1, c)] = GLFW_KEY_A + (c - 'a');
        for (char c = '0'; c <= '9'; ++c) {
            n[std::string(1, c)] = GLFW_KEY_0 + (c - '0');
            n["kp_" + std::string(1, c)] = GLFW_KEY_KP_0 + (c - '0');
        }
        for (int f = 1; f <= 12; ++f) n["f" + std::to_string(f)] = GLFW_KEY_F1 + f - 1;
        return n;
    }();
    return names;
}

} // namespace

std::optional<KeyChord> parseKeyChord(const std::string& text)
{
    KeyChord chord;
    std::stringstream parts(text);
    std::vector<std::string> names;
    for (std::string part; std::getline(parts, part, '+');) names.push_back(lower(part));
    if (names.empty()) return std::nullopt;
    // "ctrl++" leaves an empty last part: the key is '+' itself.
    if (!text.empty() && text.back() == '+' && (names.empty() || names.back().empty())) names.back() = "plus";
    for (std::size_t i = 0; i < names.size(); ++i) {
        const auto found = keyNames().find(names[i]);
        if (found == keyNames().end()) return std::nullopt;
        if (i + 1 < names.size()) chord.modifiers.push_back(found->second);
        else chord.key = found->second;
    }
    return chord;
}

std::vector<ScriptStep> parseGuiScript(const std::string& text)
{
    std::vector<ScriptStep> steps;
    std::istringstream in(text);
    int lineNumber = 0;
    for (std::string line; std::getline(in, line);) {
        ++lineNumber;
        std::vector<std::string> tokens = tokenize(line, lineNumber);
        if (tokens.empty()) continue;
        const std::string command = tokens.front();
        const std::optional<ScriptCommandShape> shape = scriptCommandShape(command);
        if (!shape) throw std::runtime_error("line " + std::to_string(lineNumber) + ": unknown command \"" + command + "\"");
        const int args = int(tokens.size()) - 1;
        if (args < shape->minArgs || args > shape->maxArgs)
            throw std::runtime_error("line " + std::to_string(lineNumber) + ": " + command + " takes " + std::to_string(shape->minArgs) +
                                     (shape->maxArgs != shape->minArgs ? " to " + std::to_string(shape->maxArgs) : "") +
                                     " arguments, got " + std::to_string(args));
        if (command == "key" || command == "key-down" || command == "key-up")
            for (std::size_t i = 1; i < tokens.size(); ++i)
                if (!parseKeyChord(tokens[i])) throw std::runtime_error("line " + std::to_string(lineNumber) + ": unknown key \"" + tokens[i] + "\"");
        if (command == "key-events")
            for (std::size_t i = 1; i < tokens.size(); ++i)
                if ((tokens[i][0] != '+' && tokens[i][0] != '-') || !parseKeyChord(tokens[i].substr(1)))
                    throw std::runtime_error("line " + std::to_string(lineNumber) + ": \"" + tokens[i] + "\" is not +KEY (a press) or -KEY (a release)");
        steps.push_back({lineNumber, command, std::vector<std::string>(tokens.begin() + 1, tokens.end()), line});
    }
    return steps;
}

} // namespace iblab::app
