#pragma once
// The GUI script runner (internal to app/): each step becomes real input events pushed into
// the app's input queue (clicks aimed at controls found by path and scrolled into view first,
// drags over several frames, text as code points), frames are run until the queue drains,
// and the expect steps check the state and the pixels (gui_script_checks.hpp). Its commands
// are one table, commands(): name, arguments, action. Included by gui_script_runner.cpp only.
#include "gui_script.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <GLFW/glfw3.h>
#include <nlohmann/json.hpp>

#include "io/atomic_file.hpp"
#include "io/error.hpp"
#include "io/image_writer.hpp"
#include "gui_app.hpp"
#include "gui_script_checks.hpp"
#include "ui/widgets.hpp"

namespace iblab::app::script {

using Clock = std::chrono::steady_clock;

inline std::optional<double> number(const std::string& text)
{
    if (text.empty()) return std::nullopt;
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (end != text.c_str() + text.size() || !std::isfinite(value)) return std::nullopt;
    return value;
}

// As lower-casing both and finding one in the other would say (ASCII).
inline bool containsIgnoringCase(const std::string& text, const std::string& part)
{
    const auto sameLetter = [](char a, char b) {
        return std::tolower(static_cast<unsigned char>(a)) == std::tolower(static_cast<unsigned char>(b));
    };
    return part.empty() || std::search(text.begin(), text.end(), part.begin(), part.end(), sameLetter) != text.end();
}

class ScriptRunner {
public:
    ScriptRunner(GuiApp& app) : app_(app) {}

    // Every command: its name, how many arguments it takes and what it does. The parser checks
    // scripts against the same table (scriptCommandShape), and docs/gui-scripts.md describes
    // each command.
    struct Command {
        std::string_view name;
        int minArgs, maxArgs;
        void (ScriptRunner::*action)(const std::string& command, const std::vector<std::string>& args);
    };
    static const std::vector<Command>& commands()
    {
        static const std::vector<Command> table{
            {"window", 2, 2, &ScriptRunner::windowStep},
            {"frames", 1, 1, &ScriptRunner::framesStep},
            {"wait-idle", 0, 1, &ScriptRunner::waitIdleStep},
            {"wait-until", 3, 4, &ScriptRunner::waitUntilStep},
            {"move", 1, 2, &ScriptRunner::moveStep},
            {"click", 1, 3, &ScriptRunner::clickStep},
            {"double-click", 1, 2, &ScriptRunner::clickStep},
            {"press", 0, 1, &ScriptRunner::pressStep},
            {"release", 0, 1, &ScriptRunner::pressStep},
            {"drag", 3, 5, &ScriptRunner::dragStep},
            {"wheel", 1, 3, &ScriptRunner::wheelStep},
            {"key", 1, 16, &ScriptRunner::keyStep},
            {"key-down", 1, 1, &ScriptRunner::keyDownStep},
            {"key-up", 1, 1, &ScriptRunner::keyDownStep},
            {"key-events", 1, 32, &ScriptRunner::keyEventsStep},
            {"type", 1, 1, &ScriptRunner::typeStep},
            {"set", 2, 2, &ScriptRunner::setStep},
            {"select", 2, 2, &ScriptRunner::selectStep},
            {"open", 1, 1, &ScriptRunner::openStep},
            {"close-section", 1, 1, &ScriptRunner::openStep},
            {"drop", 1, 16, &ScriptRunner::dropStep},
            {"close", 0, 0, &ScriptRunner::closeStep},
            {"expect", 3, 3, &ScriptRunner::expectStep},
            {"expect-item", 1, 1, &ScriptRunner::expectItemStep},
            {"expect-no-item", 1, 1, &ScriptRunner::expectItemStep},
            {"expect-pixel", 5, 6, &ScriptRunner::expectPixelStep},
            {"expect-mean", 3, 7, &ScriptRunner::expectMeanStep},
            {"snapshot", 1, 6, &ScriptRunner::snapshotStep},
            {"expect-changed", 1, 2, &ScriptRunner::expectChangedStep},
            {"expect-unchanged", 1, 2, &ScriptRunner::expectChangedStep},
            {"screenshot", 1, 1, &ScriptRunner::screenshotStep},
            {"print", 1, 1, &ScriptRunner::printStep},
            {"list-items", 0, 1, &ScriptRunner::listItemsStep},
            {"timed-keys", 3, 3, &ScriptRunner::timedKeysStep},
            {"timed-click", 1, 3, &ScriptRunner::timedClickStep},
            {"expect-within", 4, 4, &ScriptRunner::expectWithinStep},
            {"remember", 1, 1, &ScriptRunner::rememberStep},
            {"expect-same", 1, 1, &ScriptRunner::rememberStep},
            {"sleep", 1, 1, &ScriptRunner::sleepStep},
        };
        return table;
    }

    void run(const ScriptStep& step)
    {
        for (const Command& command : commands())
            if (command.name == step.command) return (this->*command.action)(step.command, step.args);
        throw StepFailed("unknown command \"" + step.command + "\"");
    }

    int framesRun() const { return frames_; }

private:
    // The commands' actions (gui_script_runner.cpp), one per row of commands() or shared by
    // the two forms of one command (click and double-click).
    void windowStep(const std::string&, const std::vector<std::string>& a);
    void framesStep(const std::string&, const std::vector<std::string>& a);
    void waitIdleStep(const std::string&, const std::vector<std::string>& a);
    void waitUntilStep(const std::string&, const std::vector<std::string>& a);
    void moveStep(const std::string&, const std::vector<std::string>& a);
    void clickStep(const std::string& c, const std::vector<std::string>& a);
    void pressStep(const std::string& c, const std::vector<std::string>& a);
    void dragStep(const std::string&, const std::vector<std::string>& a);
    void wheelStep(const std::string&, const std::vector<std::string>& a);
    void keyStep(const std::string&, const std::vector<std::string>& a);
    void keyDownStep(const std::string& c, const std::vector<std::string>& a);
    void keyEventsStep(const std::string&, const std::vector<std::string>& a);
    void typeStep(const std::string&, const std::vector<std::string>& a);
    void setStep(const std::string&, const std::vector<std::string>& a);
    void selectStep(const std::string&, const std::vector<std::string>& a);
    void openStep(const std::string& c, const std::vector<std::string>& a);
    void dropStep(const std::string&, const std::vector<std::string>& a);
    void closeStep(const std::string&, const std::vector<std::string>&);
    void expectStep(const std::string&, const std::vector<std::string>& a);
    void expectItemStep(const std::string& c, const std::vector<std::string>& a);
    void expectPixelStep(const std::string&, const std::vector<std::string>& a);
    void expectMeanStep(const std::string&, const std::vector<std::string>& a);
    void snapshotStep(const std::string&, const std::vector<std::string>& a);
    void expectChangedStep(const std::string& c, const std::vector<std::string>& a);
    void screenshotStep(const std::string&, const std::vector<std::string>& a);
    void printStep(const std::string&, const std::vector<std::string>& a);
    void listItemsStep(const std::string&, const std::vector<std::string>& a);
    void timedKeysStep(const std::string&, const std::vector<std::string>& a);
    void timedClickStep(const std::string&, const std::vector<std::string>& a);
    void expectWithinStep(const std::string&, const std::vector<std::string>& a);
    void rememberStep(const std::string& c, const std::vector<std::string>& a);
    void sleepStep(const std::string&, const std::vector<std::string>& a);

    static double need(std::optional<double> value, const char* what)
    {
        if (!value) throw StepFailed(std::string("expected a number for ") + what);
        return *value;
    }

    static int mouseButton(const std::string& name)
    {
        if (name == "left") return 0;
        if (name == "right") return 1;
        if (name == "middle") return 2;
        throw StepFailed("unknown mouse button \"" + name + "\" (left, right, middle)");
    }

    void frames(int n)
    {
        for (int i = 0; i < n; ++i) {
            app_.frame();
            ++frames_;
        }
    }

    void push(InputEvent event) { app_.input().push(std::move(event)); }
    void moveTo(ImVec2 p) { push({.type = InputEvent::Type::CursorMoved, .x = p.x, .y = p.y}); }
    void key(int code, bool pressed) { push({.type = InputEvent::Type::Key, .code = code, .pressed = pressed}); }

    // A state value at a JSON pointer, or with "item:PATH" a control's rectangle.
    nlohmann::json rememberable(const std::string& what)
    {
        if (what.compare(0, 5, "item:") == 0) {
            const ui::TrackedItem& control = item(what.substr(5));
            return {control.min.x, control.min.y, control.max.x, control.max.y};
        }
        const nlohmann::json state = app_.state();
        const nlohmann::json::json_pointer pointer(what);
        return state.contains(pointer) ? state.at(pointer) : nlohmann::json();
    }

    // COUNT presses of a chord spread evenly over SECONDS of wall time, each pushed when it is
    // due, between frames, as a window's event loop polls them: a frame that takes long sees
    // what arrived meanwhile all at once. Returns after the last release, running no more frames.
    void timedKeys(const KeyChord& chord, int count, double seconds)
    {
        struct Due {
            Clock::time_point at;
            int code;
            bool pressed;
        };
        std::vector<Due> events;
        const auto start = Clock::now();
        const double interval = count > 1 ? seconds / double(count - 1) : 0.0;
        for (int n = 0; n < count; ++n) {
            const auto press = start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(interval * n));
            const auto release = press + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(0.5 * interval));
            for (int m : chord.modifiers) events.push_back({press, m, true});
            events.push_back({press, chord.key, true});
            events.push_back({release, chord.key, false});
            for (int m : chord.modifiers) events.push_back({release, m, false});
            lastArrival_ = press;
        }
        for (std::size_t next = 0; next < events.size();) {
            while (next < events.size() && events[next].at <= Clock::now()) {
                key(events[next].code, events[next].pressed);
                ++next;
            }
            if (next < events.size()) frames(1);
        }
    }

    // Runs frames until the state check passes, and fails when that took longer than `ms`
    // after the last input of a timed step arrived. Prints the time it took.
    void expectWithin(double ms, const std::string& pointer, const std::string& op, const std::string& value)
    {
        std::string why;
        const int giveUpMs = std::max(10000, int(5.0 * ms));
        const auto giveUp = lastArrival_ + std::chrono::milliseconds(giveUpMs);
        while (!checkState(app_.state(), pointer, op, value, why)) {
            if (Clock::now() > giveUp) throw StepFailed("still not " + pointer + " " + op + " " + value + " " + std::to_string(giveUpMs) + " ms after the input (last: " + why + ")");
            frames(1);
        }
        const double took = std::chrono::duration<double, std::milli>(Clock::now() - lastArrival_).count();
        std::printf("expect-within: %s %s %s %.0f ms after the input (limit %.0f ms)\n", pointer.c_str(), op.c_str(), value.c_str(), took, ms);
        std::fflush(stdout);
        if (took > ms) throw StepFailed(pointer + " " + op + " " + value + " took " + std::to_string(int(took)) + " ms, over " + std::to_string(int(ms)));
    }

    void typeText(const std::string& text)
    {
        // UTF-8 to code points, as GLFW's character callback delivers them.
        for (std::size_t i = 0; i < text.size();) {
            const unsigned char c = static_cast<unsigned char>(text[i]);
            unsigned codepoint = c;
            int extra = c >= 0xF0 ? 3 : c >= 0xE0 ? 2 : c >= 0xC0 ? 1 : 0;
            if (extra) codepoint = c & (0x3F >> extra);
            ++i;
            for (; extra > 0 && i < text.size(); --extra, ++i) codepoint = (codepoint << 6) | (static_cast<unsigned char>(text[i]) & 0x3F);
            push({.type = InputEvent::Type::Text, .codepoint = codepoint});
        }
    }

    // Frames until every queued event has been handed to the app, then `extra` more so that
    // what the input changed is drawn (a popup that opened is laid out on its second frame).
    void settle(int extra = 2)
    {
        for (int guard = 0; !app_.input().empty(); ++guard) {
            if (guard > 10000) throw StepFailed("the input queue does not drain");
            frames(1);
        }
        frames(extra);
    }

    template <typename Done, typename What>
    void waitFor(Done done, double seconds, What what)
    {
        const auto deadline = Clock::now() + std::chrono::duration<double>(seconds);
        while (!done()) {
            if (Clock::now() > deadline) throw StepFailed("timed out after " + std::to_string(int(seconds)) + " s waiting for " + what());
            frames(1);
        }
    }

    std::string nearby(const std::string& path) const
    {
        // The shown paths that share the last part of the missing one, to help fix a script.
        const std::string last = path.substr(path.rfind('/') == std::string::npos ? 0 : path.rfind('/') + 1);
        std::string list;
        for (const ui::TrackedItem& item : app_.items().items())
            if (containsIgnoringCase(item.path, last)) list += (list.empty() ? "" : ", ") + item.path;
        return list.empty() ? "" : " (shown: " + list + ")";
    }

    const ui::TrackedItem& item(const std::string& path) const
    {
        const ui::TrackedItem* found = app_.items().find(path);
        if (!found) throw StepFailed("no control \"" + path + "\" is shown" + nearby(path));
        return *found;
    }

    // A control to be clicked must be on screen: the panel is scrolled with the wheel, as a
    // user would, until the control's centre is inside the window.
    // It must also stay where it is: a status line that appears (a load finishing) moves
    // what is below it, and a click aimed at the last frame's layout would land elsewhere.
    const ui::TrackedItem& visibleItem(const std::string& path)
    {
        const float height = float(app_.platform().height());
        for (int attempt = 0; attempt < 200; ++attempt) {
            const ImVec2 before = item(path).min;
            frames(1);
            const ui::TrackedItem& control = item(path);
            if (control.min.x != before.x || control.min.y != before.y) continue;
            const float y = control.centre().y;
            if (y >= 4.0f && y <= height - 4.0f) return control;
            moveTo(ImVec2(std::max(4.0f, control.min.x), 0.5f * height));
            push({.type = InputEvent::Type::Scroll, .y = y < 4.0f ? 1.0 : -1.0});
            settle(1);
        }
        throw StepFailed("\"" + path + "\" stays out of view however the panel is scrolled");
    }

    // "X Y" (window pixels) or an item path; advances i past what it read.
    ImVec2 target(const std::vector<std::string>& a, std::size_t& i)
    {
        if (i + 1 < a.size() && number(a[i]) && number(a[i + 1])) {
            const ImVec2 p(float(*number(a[i])), float(*number(a[i + 1])));
            i += 2;
            return p;
        }
        if (i >= a.size()) throw StepFailed("missing target (X Y, view or a control's path)");
        if (a[i] == "view") {
            ++i;
            const nlohmann::json view = app_.state()["view"];
            return ImVec2(float(view["x"].get<double>() + 0.5 * view["width"].get<double>()), float(view["y"].get<double>() + 0.5 * view["height"].get<double>()));
        }
        return visibleItem(a[i++]).centre();
    }

    void clickItem(const std::string& path)
    {
        // Aimed, then aimed again where the item is once the cursor is there, as a hand follows
        // a control that moves: a frame drawn meanwhile can move it (a bake that lands adds
        // status lines above the sections below it, and the click would land on what moved in).
        ImVec2 p = visibleItem(path).centre();
        for (int aim = 0; aim < 4; ++aim) {
            moveTo(p);
            settle(0);
            const ImVec2 now = visibleItem(path).centre();
            if (now.x == p.x && now.y == p.y) break;
            p = now;
        }
        push({.type = InputEvent::Type::MouseButton, .code = 0, .pressed = true});
        push({.type = InputEvent::Type::MouseButton, .code = 0, .pressed = false});
        settle();
    }

    bool sectionOpen(const std::string& path) const
    {
        const ui::TrackedItem& header = item(path);
        const std::string prefix = header.path + "/";
        return std::any_of(app_.items().items().begin(), app_.items().items().end(),
                           [&](const ui::TrackedItem& i) { return i.path.compare(0, prefix.size(), prefix) == 0; });
    }

    // As a user types a value: Ctrl+click turns a slider into a text field (a plain click
    // focuses an input), Ctrl+A selects what is there, the value is typed and Enter commits.
    void setValue(const std::string& path, const std::string& value)
    {
        const ui::TrackedItem control = visibleItem(path); // a copy: frames below replace the registry's
        if (control.kind == "combo") {
            clickItem(path);
            clickItem(control.path + "/" + value);
            return;
        }
        if (control.kind != "slider" && control.kind != "part" && control.kind != "input")
            throw StepFailed("\"" + path + "\" is a " + control.kind + ": set takes a slider, a field or a combo (click a " + control.kind + ")");
        moveTo(control.centre());
        const bool slider = control.kind != "input";
        if (slider) key(GLFW_KEY_LEFT_CONTROL, true);
        push({.type = InputEvent::Type::MouseButton, .code = 0, .pressed = true});
        push({.type = InputEvent::Type::MouseButton, .code = 0, .pressed = false});
        if (slider) key(GLFW_KEY_LEFT_CONTROL, false);
        settle(1);
        key(GLFW_KEY_LEFT_CONTROL, true);
        key(GLFW_KEY_A, true);
        key(GLFW_KEY_A, false);
        key(GLFW_KEY_LEFT_CONTROL, false);
        typeText(value);
        key(GLFW_KEY_ENTER, true);
        key(GLFW_KEY_ENTER, false);
        settle();
    }

    Region region(const std::vector<std::string>& a, std::size_t& i)
    {
        if (i >= a.size()) throw StepFailed("missing region (view, window, panel, item PATH or X0 Y0 X1 Y1)");
        const nlohmann::json state = app_.state();
        const std::string& name = a[i];
        if (name == "view" || name == "window" || name == "panel") {
            ++i;
            const int viewX = int(state["view"]["x"].get<double>());
            const int w = app_.platform().width(), h = app_.platform().height();
            if (name == "view") return {viewX, 0, w, h};
            if (name == "panel") return {0, 0, viewX, h};
            return {0, 0, w, h};
        }
        if (name == "item") {
            if (i + 1 >= a.size()) throw StepFailed("item needs a control's path");
            const ui::TrackedItem& control = visibleItem(a[i + 1]);
            i += 2;
            return {int(control.min.x), int(control.min.y), int(control.max.x), int(control.max.y)};
        }
        if (i + 3 >= a.size()) throw StepFailed("a region is view, window, panel, item PATH or X0 Y0 X1 Y1");
        Region r{int(need(number(a[i]), "X0")), int(need(number(a[i + 1]), "Y0")), int(need(number(a[i + 2]), "X1")), int(need(number(a[i + 3]), "Y1"))};
        i += 4;
        return r;
    }

    const WindowPixels& capture()
    {
        app_.requestPixels();
        frames(1);
        return app_.lastPixels();
    }

    GuiApp& app_;
    std::map<std::string, Snapshot> snapshots_;
    std::map<std::string, nlohmann::json> remembered_;
    int frames_ = 0;
    Clock::time_point lastArrival_ = Clock::now(); // of the last input of a timed step
};

} // namespace iblab::app::script
