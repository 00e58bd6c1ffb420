// Running a GUI script: each step becomes real input events pushed into the app's input
// queue (clicks aimed at controls found by path and scrolled into view first, drags over
// several frames, text as code points), frames are run until the queue drains, and the
// expect steps check the state and the pixels (gui_script_checks.hpp). The first failure
// ends the run, reported as FILE:LINE: step: reason.
#include "gui_script.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>

#include <GLFW/glfw3.h>
#include <nlohmann/json.hpp>

#include "io/atomic_file.hpp"
#include "io/error.hpp"
#include "io/image_writer.hpp"
#include "gui_app.hpp"
#include "gui_script_checks.hpp"
#include "ui/widgets.hpp"

namespace iblab::app {
namespace {

using Clock = std::chrono::steady_clock;

std::optional<double> number(const std::string& text)
{
    if (text.empty()) return std::nullopt;
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (end != text.c_str() + text.size() || !std::isfinite(value)) return std::nullopt;
    return value;
}

// As lower-casing both and finding one in the other would say (ASCII).
bool containsIgnoringCase(const std::string& text, const std::string& part)
{
    const auto sameLetter = [](char a, char b) {
        return std::tolower(static_cast<unsigned char>(a)) == std::tolower(static_cast<unsigned char>(b));
    };
    return part.empty() || std::search(text.begin(), text.end(), part.begin(), part.end(), sameLetter) != text.end();
}

class ScriptRunner {
public:
    ScriptRunner(GuiApp& app) : app_(app) {}

    void run(const ScriptStep& step)
    {
        const std::string& c = step.command;
        const std::vector<std::string>& a = step.args;
        if (c == "window") {
            app_.platform().resize(int(need(number(a[0]), "a width")), int(need(number(a[1]), "a height")));
            frames(2);
        } else if (c == "frames") {
            frames(int(need(number(a[0]), "a frame count")));
        } else if (c == "wait-idle") {
            waitFor([&] { return app_.idle(); }, a.empty() ? 180.0 : need(number(a[0]), "seconds"), [] { return std::string("the app to be idle"); });
        } else if (c == "wait-until") {
            std::string why;
            waitFor([&] { return checkState(app_.state(), a[0], a[1], a[2], why); }, a.size() > 3 ? need(number(a[3]), "seconds") : 180.0,
                    [&] { return a[0] + " " + a[1] + " " + a[2] + " (last: " + why + ")"; });
        } else if (c == "move") {
            std::size_t i = 0;
            const ImVec2 p = target(a, i);
            moveTo(p);
            settle();
        } else if (c == "click" || c == "double-click") {
            std::size_t i = 0;
            const ImVec2 p = target(a, i);
            const int button = i < a.size() ? mouseButton(a[i]) : 0;
            moveTo(p);
            for (int n = 0; n < (c == "click" ? 1 : 2); ++n) {
                push({.type = InputEvent::Type::MouseButton, .code = button, .pressed = true});
                push({.type = InputEvent::Type::MouseButton, .code = button, .pressed = false});
            }
            settle();
        } else if (c == "press" || c == "release") {
            push({.type = InputEvent::Type::MouseButton, .code = a.empty() ? 0 : mouseButton(a[0]), .pressed = c == "press"});
            settle();
        } else if (c == "drag") {
            std::size_t i = 0;
            const ImVec2 from = target(a, i);
            if (i + 2 > a.size()) throw StepFailed("drag needs a target, then DX DY");
            const ImVec2 by(float(need(number(a[i]), "DX")), float(need(number(a[i + 1]), "DY")));
            const int button = i + 2 < a.size() ? mouseButton(a[i + 2]) : 0;
            moveTo(from);
            push({.type = InputEvent::Type::MouseButton, .code = button, .pressed = true});
            settle(0);
            // A drag over several frames, as a hand makes it: what follows the mouse (a
            // slider, the orbit, the divider) sees every step.
            constexpr int kSteps = 8;
            for (int s = 1; s <= kSteps; ++s) {
                moveTo(ImVec2(from.x + by.x * float(s) / kSteps, from.y + by.y * float(s) / kSteps));
                settle(0);
            }
            push({.type = InputEvent::Type::MouseButton, .code = button, .pressed = false});
            settle();
        } else if (c == "wheel") {
            const double steps = need(number(a[0]), "wheel steps");
            if (a.size() > 1) {
                std::size_t i = 1;
                moveTo(target(a, i));
            }
            push({.type = InputEvent::Type::Scroll, .y = steps});
            settle();
        } else if (c == "key") {
            for (const std::string& name : a) {
                const KeyChord chord = *parseKeyChord(name);
                for (int m : chord.modifiers) key(m, true);
                key(chord.key, true);
                key(chord.key, false);
                for (int m : chord.modifiers) key(m, false);
            }
            settle();
        } else if (c == "key-events") {
            // Presses (+KEY) and releases (-KEY) that all arrive before the next frame, in
            // this order: a fast chord's events on a slow frame.
            for (const std::string& event : a) key(parseKeyChord(event.substr(1))->key, event[0] == '+');
            settle();
        } else if (c == "key-down" || c == "key-up") {
            key(parseKeyChord(a[0])->key, c == "key-down");
            settle();
        } else if (c == "type") {
            typeText(a[0]);
            settle();
        } else if (c == "set") {
            setValue(a[0], a[1]);
        } else if (c == "select") {
            clickItem(a[0]);
            clickItem(a[0] + "/" + a[1]);
        } else if (c == "open" || c == "close-section") {
            if (sectionOpen(a[0]) != (c == "open")) clickItem(a[0]);
            if (sectionOpen(a[0]) != (c == "open")) throw StepFailed("\"" + a[0] + "\" did not " + (c == "open" ? "open" : "close"));
        } else if (c == "drop") {
            push({.type = InputEvent::Type::Drop, .paths = a});
            settle();
        } else if (c == "close") {
            push({.type = InputEvent::Type::CloseRequest});
            settle();
        } else if (c == "expect") {
            std::string why;
            if (!checkState(app_.state(), a[0], a[1], a[2], why)) throw StepFailed(why);
        } else if (c == "expect-item" || c == "expect-no-item") {
            const bool present = app_.items().find(a[0]) != nullptr;
            if (present != (c == "expect-item")) throw StepFailed(present ? "\"" + a[0] + "\" is shown" : "no control \"" + a[0] + "\" is shown" + nearby(a[0]));
        } else if (c == "expect-pixel") {
            const WindowPixels& pixels = capture();
            const int x = int(need(number(a[0]), "X")), y = int(need(number(a[1]), "Y"));
            const double tolerance = a.size() > 5 ? need(number(a[5]), "a tolerance") : 8.0;
            if (x < 0 || y < 0 || x >= pixels.width || y >= pixels.height) throw StepFailed("pixel outside the window");
            const std::uint8_t* p = &pixels.rgba[(std::size_t(y) * std::size_t(pixels.width) + std::size_t(x)) * 4];
            for (int ch = 0; ch < 3; ++ch)
                if (std::abs(double(p[ch]) - need(number(a[2 + std::size_t(ch)]), "R G B")) > tolerance)
                    throw StepFailed("pixel (" + a[0] + ", " + a[1] + ") is " + std::to_string(p[0]) + " " + std::to_string(p[1]) + " " +
                                     std::to_string(p[2]));
        } else if (c == "expect-mean") {
            std::size_t i = 0;
            const Region r = region(a, i);
            if (i + 2 != a.size()) throw StepFailed("expect-mean REGION OP VALUE");
            const double mean = meanLevel(capture(), r);
            std::string why;
            if (!compareValues(nlohmann::json(mean), a[i], nlohmann::json(need(number(a[i + 1]), "a value")), why))
                throw StepFailed("mean level " + std::to_string(mean) + ": " + why);
        } else if (c == "snapshot") {
            std::size_t i = 1;
            const Region r = a.size() > 1 ? region(a, i) : Region{0, 0, app_.platform().width(), app_.platform().height()};
            snapshots_[a[0]] = {r, capture()};
        } else if (c == "expect-changed" || c == "expect-unchanged") {
            const auto found = snapshots_.find(a[0]);
            if (found == snapshots_.end()) throw StepFailed("no snapshot \"" + a[0] + "\"");
            const double difference = meanDifference(found->second, capture());
            const bool changed = c == "expect-changed";
            const double limit = a.size() > 1 ? need(number(a[1]), "a level difference") : (changed ? 2.0 : 1.0);
            if (changed ? difference < limit : difference > limit)
                throw StepFailed("mean difference from \"" + a[0] + "\" is " + std::to_string(difference) + (changed ? ", below " : ", above ") +
                                 std::to_string(limit));
        } else if (c == "screenshot") {
            const WindowPixels& pixels = capture();
            writePng8(a[0], pixels.width, pixels.height, 4, pixels.rgba, {});
        } else if (c == "print") {
            const nlohmann::json state = app_.state();
            const nlohmann::json::json_pointer pointer(a[0]);
            std::printf("%s = %s\n", a[0].c_str(), state.contains(pointer) ? state.at(pointer).dump().c_str() : "(absent)");
        } else if (c == "list-items") {
            for (const ui::TrackedItem& shown : app_.items().items())
                if (a.empty() || shown.path.compare(0, a[0].size(), a[0]) == 0)
                    std::printf("  %-60s %-8s (%.0f, %.0f)-(%.0f, %.0f)\n", shown.path.c_str(), shown.kind.c_str(), shown.min.x, shown.min.y, shown.max.x,
                                shown.max.y);
        } else if (c == "timed-keys") {
            timedKeys(*parseKeyChord(a[0]), int(need(number(a[1]), "a count")), need(number(a[2]), "seconds"));
        } else if (c == "timed-click") {
            std::size_t i = 0;
            const ImVec2 p = target(a, i);
            const int button = i < a.size() ? mouseButton(a[i]) : 0;
            moveTo(p);
            push({.type = InputEvent::Type::MouseButton, .code = button, .pressed = true});
            push({.type = InputEvent::Type::MouseButton, .code = button, .pressed = false});
            lastArrival_ = Clock::now();
        } else if (c == "expect-within") {
            expectWithin(need(number(a[0]), "milliseconds"), a[1], a[2], a[3]);
        } else if (c == "remember" || c == "expect-same") {
            const nlohmann::json value = rememberable(a[0]);
            if (c == "remember") remembered_[a[0]] = value;
            else if (!remembered_.contains(a[0])) throw StepFailed("nothing remembered at " + a[0]);
            else if (remembered_[a[0]] != value) throw StepFailed(a[0] + " is " + value.dump() + ", was " + remembered_[a[0]].dump());
        } else if (c == "sleep") {
            const auto until = Clock::now() + std::chrono::milliseconds(int(need(number(a[0]), "milliseconds")));
            while (Clock::now() < until) frames(1);
        }
    }

    int framesRun() const { return frames_; }

private:
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

void writeCoverage(const std::string& path, const ui::ItemRegistry& items)
{
    nlohmann::json shown = nlohmann::json::object();
    for (const auto& [itemPath, kind] : items.everShown()) shown[itemPath] = kind;
    nlohmann::json used = nlohmann::json::array();
    for (const std::string& itemPath : items.interacted()) used.push_back(itemPath);
    writeTextFileAtomic(path, nlohmann::json{{"shown", shown}, {"used", used}}.dump(1) + "\n");
}

} // namespace

int runGuiScript(GuiApp& app, const std::string& path, const std::string& coverageOut)
{
    std::vector<ScriptStep> steps;
    try {
        steps = parseGuiScript(readTextFile(path));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "iblab: %s: %s\n", path.c_str(), e.what());
        return 2;
    }
    app.setScripted(true);
    ScriptRunner runner(app);
    const auto start = Clock::now();
    int status = 0;
    try {
        // As a person does, the script starts once the window shows the start's environment:
        // the panel's status lines change when it lands, and controls below them move.
        runner.run({0, "wait-until", {"/session/busy", "==", "false"}, "(start)"});
        runner.run({0, "frames", {"2"}, "(start)"});
        for (const ScriptStep& step : steps) {
            try {
                runner.run(step);
            } catch (const StepFailed& e) {
                std::fprintf(stderr, "%s:%d: %s: %s\n", path.c_str(), step.line, step.text.c_str(), e.what());
                status = 1;
                break;
            } catch (const std::exception& e) {
                std::fprintf(stderr, "%s:%d: %s: %s\n", path.c_str(), step.line, step.text.c_str(), e.what());
                status = 1;
                break;
            }
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", path.c_str(), e.what());
        status = 1;
    }
    if (app.glErrorCount() > 0) {
        std::fprintf(stderr, "%s: %d GL errors (KHR_debug); the script fails on any\n", path.c_str(), app.glErrorCount());
        status = 1;
    }
    if (!coverageOut.empty()) try {
            writeCoverage(coverageOut, app.items());
        } catch (const std::exception& e) {
            std::fprintf(stderr, "%s: %s\n", path.c_str(), e.what());
            status = 1;
        }
    std::printf("gui script %s: %s, %zu steps, %d frames, %s, %.1f s\n", path.c_str(), status == 0 ? "passed" : "FAILED", steps.size(),
                runner.framesRun(), app.platform().kind().c_str(), std::chrono::duration<double>(Clock::now() - start).count());
    return status;
}

} // namespace iblab::app
