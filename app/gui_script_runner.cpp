// Running a GUI script: what each command of the runner's table (gui_script_runner.hpp) does,
// and the run itself. The first failure ends the run, reported as FILE:LINE: step: reason.
#include "gui_script_runner.hpp"

namespace iblab::app {
namespace script {

void ScriptRunner::windowStep(const std::string&, const std::vector<std::string>& a)
{
    app_.platform().resize(int(need(number(a[0]), "a width")), int(need(number(a[1]), "a height")));
    frames(2);
}

void ScriptRunner::framesStep(const std::string&, const std::vector<std::string>& a)
{
    frames(int(need(number(a[0]), "a frame count")));
}

void ScriptRunner::waitIdleStep(const std::string&, const std::vector<std::string>& a)
{
    waitFor([&] { return app_.idle(); }, a.empty() ? 180.0 : need(number(a[0]), "seconds"), [] { return std::string("the app to be idle"); });
}

void ScriptRunner::waitUntilStep(const std::string&, const std::vector<std::string>& a)
{
    std::string why;
    waitFor([&] { return checkState(app_.state(), a[0], a[1], a[2], why); }, a.size() > 3 ? need(number(a[3]), "seconds") : 180.0,
            [&] { return a[0] + " " + a[1] + " " + a[2] + " (last: " + why + ")"; });
}

void ScriptRunner::moveStep(const std::string&, const std::vector<std::string>& a)
{
    std::size_t i = 0;
    const ImVec2 p = target(a, i);
    moveTo(p);
    settle();
}

void ScriptRunner::clickStep(const std::string& c, const std::vector<std::string>& a)
{
    std::size_t i = 0;
    const ImVec2 p = target(a, i);
    const int button = i < a.size() ? mouseButton(a[i]) : 0;
    moveTo(p);
    for (int n = 0; n < (c == "click" ? 1 : 2); ++n) {
        push({.type = InputEvent::Type::MouseButton, .code = button, .pressed = true});
        push({.type = InputEvent::Type::MouseButton, .code = button, .pressed = false});
    }
    settle();
}

void ScriptRunner::pressStep(const std::string& c, const std::vector<std::string>& a)
{
    push({.type = InputEvent::Type::MouseButton, .code = a.empty() ? 0 : mouseButton(a[0]), .pressed = c == "press"});
    settle();
}

void ScriptRunner::dragStep(const std::string&, const std::vector<std::string>& a)
{
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
}

void ScriptRunner::wheelStep(const std::string&, const std::vector<std::string>& a)
{
    const double steps = need(number(a[0]), "wheel steps");
    if (a.size() > 1) {
        std::size_t i = 1;
        moveTo(target(a, i));
    }
    push({.type = InputEvent::Type::Scroll, .y = steps});
    settle();
}

void ScriptRunner::keyStep(const std::string&, const std::vector<std::string>& a)
{
    for (const std::string& name : a) {
        const KeyChord chord = *parseKeyChord(name);
        for (int m : chord.modifiers) key(m, true);
        key(chord.key, true);
        key(chord.key, false);
        for (int m : chord.modifiers) key(m, false);
    }
    settle();
}

void ScriptRunner::keyDownStep(const std::string& c, const std::vector<std::string>& a)
{
    key(parseKeyChord(a[0])->key, c == "key-down");
    settle();
}

void ScriptRunner::keyEventsStep(const std::string&, const std::vector<std::string>& a)
{
    // Presses (+KEY) and releases (-KEY) that all arrive before the next frame, in this
    // order: a fast chord's events on a slow frame.
    for (const std::string& event : a) key(parseKeyChord(event.substr(1))->key, event[0] == '+');
    settle();
}

void ScriptRunner::typeStep(const std::string&, const std::vector<std::string>& a)
{
    typeText(a[0]);
    settle();
}

void ScriptRunner::setStep(const std::string&, const std::vector<std::string>& a)
{
    setValue(a[0], a[1]);
}

void ScriptRunner::selectStep(const std::string&, const std::vector<std::string>& a)
{
    clickItem(a[0]);
    clickItem(a[0] + "/" + a[1]);
}

void ScriptRunner::openStep(const std::string& c, const std::vector<std::string>& a)
{
    if (sectionOpen(a[0]) != (c == "open")) clickItem(a[0]);
    if (sectionOpen(a[0]) != (c == "open")) throw StepFailed("\"" + a[0] + "\" did not " + (c == "open" ? "open" : "close"));
}

void ScriptRunner::dropStep(const std::string&, const std::vector<std::string>& a)
{
    push({.type = InputEvent::Type::Drop, .paths = a});
    settle();
}

void ScriptRunner::closeStep(const std::string&, const std::vector<std::string>&)
{
    push({.type = InputEvent::Type::CloseRequest});
    settle();
}

void ScriptRunner::expectStep(const std::string&, const std::vector<std::string>& a)
{
    std::string why;
    if (!checkState(app_.state(), a[0], a[1], a[2], why)) throw StepFailed(why);
}

void ScriptRunner::expectItemStep(const std::string& c, const std::vector<std::string>& a)
{
    const bool present = app_.items().find(a[0]) != nullptr;
    if (present != (c == "expect-item")) throw StepFailed(present ? "\"" + a[0] + "\" is shown" : "no control \"" + a[0] + "\" is shown" + nearby(a[0]));
}

void ScriptRunner::expectPixelStep(const std::string&, const std::vector<std::string>& a)
{
    const WindowPixels& pixels = capture();
    const int x = int(need(number(a[0]), "X")), y = int(need(number(a[1]), "Y"));
    const double tolerance = a.size() > 5 ? need(number(a[5]), "a tolerance") : 8.0;
    if (x < 0 || y < 0 || x >= pixels.width || y >= pixels.height) throw StepFailed("pixel outside the window");
    const std::uint8_t* p = &pixels.rgba[(std::size_t(y) * std::size_t(pixels.width) + std::size_t(x)) * 4];
    for (int ch = 0; ch < 3; ++ch)
        if (std::abs(double(p[ch]) - need(number(a[2 + std::size_t(ch)]), "R G B")) > tolerance)
            throw StepFailed("pixel (" + a[0] + ", " + a[1] + ") is " + std::to_string(p[0]) + " " + std::to_string(p[1]) + " " +
                             std::to_string(p[2]));
}

void ScriptRunner::expectMeanStep(const std::string&, const std::vector<std::string>& a)
{
    std::size_t i = 0;
    const Region r = region(a, i);
    if (i + 2 != a.size()) throw StepFailed("expect-mean REGION OP VALUE");
    const double mean = meanLevel(capture(), r);
    std::string why;
    if (!compareValues(nlohmann::json(mean), a[i], nlohmann::json(need(number(a[i + 1]), "a value")), why))
        throw StepFailed("mean level " + std::to_string(mean) + ": " + why);
}

void ScriptRunner::snapshotStep(const std::string&, const std::vector<std::string>& a)
{
    std::size_t i = 1;
    const Region r = a.size() > 1 ? region(a, i) : Region{0, 0, app_.platform().width(), app_.platform().height()};
    snapshots_[a[0]] = {r, capture()};
}

void ScriptRunner::expectChangedStep(const std::string& c, const std::vector<std::string>& a)
{
    const auto found = snapshots_.find(a[0]);
    if (found == snapshots_.end()) throw StepFailed("no snapshot \"" + a[0] + "\"");
    const double difference = meanDifference(found->second, capture());
    const bool changed = c == "expect-changed";
    const double limit = a.size() > 1 ? need(number(a[1]), "a level difference") : (changed ? 2.0 : 1.0);
    if (changed ? difference < limit : difference > limit)
        throw StepFailed("mean difference from \"" + a[0] + "\" is " + std::to_string(difference) + (changed ? ", below " : ", above ") +
                         std::to_string(limit));
}

void ScriptRunner::screenshotStep(const std::string&, const std::vector<std::string>& a)
{
    const WindowPixels& pixels = capture();
    writePng8(a[0], pixels.width, pixels.height, 4, pixels.rgba, {});
}

void ScriptRunner::printStep(const std::string&, const std::vector<std::string>& a)
{
    const nlohmann::json state = app_.state();
    const nlohmann::json::json_pointer pointer(a[0]);
    std::printf("%s = %s\n", a[0].c_str(), state.contains(pointer) ? state.at(pointer).dump().c_str() : "(absent)");
}

void ScriptRunner::listItemsStep(const std::string&, const std::vector<std::string>& a)
{
    for (const ui::TrackedItem& shown : app_.items().items())
        if (a.empty() || shown.path.compare(0, a[0].size(), a[0]) == 0)
            std::printf("  %-60s %-8s (%.0f, %.0f)-(%.0f, %.0f)\n", shown.path.c_str(), shown.kind.c_str(), shown.min.x, shown.min.y, shown.max.x,
                        shown.max.y);
}

void ScriptRunner::timedKeysStep(const std::string&, const std::vector<std::string>& a)
{
    timedKeys(*parseKeyChord(a[0]), int(need(number(a[1]), "a count")), need(number(a[2]), "seconds"));
}

void ScriptRunner::timedClickStep(const std::string&, const std::vector<std::string>& a)
{
    std::size_t i = 0;
    const ImVec2 p = target(a, i);
    const int button = i < a.size() ? mouseButton(a[i]) : 0;
    moveTo(p);
    push({.type = InputEvent::Type::MouseButton, .code = button, .pressed = true});
    push({.type = InputEvent::Type::MouseButton, .code = button, .pressed = false});
    lastArrival_ = Clock::now();
}

void ScriptRunner::expectWithinStep(const std::string&, const std::vector<std::string>& a)
{
    expectWithin(need(number(a[0]), "milliseconds"), a[1], a[2], a[3]);
}

void ScriptRunner::rememberStep(const std::string& c, const std::vector<std::string>& a)
{
    const nlohmann::json value = rememberable(a[0]);
    if (c == "remember") remembered_[a[0]] = value;
    else if (!remembered_.contains(a[0])) throw StepFailed("nothing remembered at " + a[0]);
    else if (remembered_[a[0]] != value) throw StepFailed(a[0] + " is " + value.dump() + ", was " + remembered_[a[0]].dump());
}

void ScriptRunner::sleepStep(const std::string&, const std::vector<std::string>& a)
{
    const auto until = Clock::now() + std::chrono::milliseconds(int(need(number(a[0]), "milliseconds")));
    while (Clock::now() < until) frames(1);
}

} // namespace script

namespace {

using script::Clock;
using script::ScriptRunner;

void writeCoverage(const std::string& path, const ui::ItemRegistry& items)
{
    nlohmann::json shown = nlohmann::json::object();
    for (const auto& [itemPath, kind] : items.everShown()) shown[itemPath] = kind;
    nlohmann::json used = nlohmann::json::array();
    for (const std::string& itemPath : items.interacted()) used.push_back(itemPath);
    writeTextFileAtomic(path, nlohmann::json{{"shown", shown}, {"used", used}}.dump(1) + "\n");
}

} // namespace

std::optional<ScriptCommandShape> scriptCommandShape(const std::string& command)
{
    for (const ScriptRunner::Command& each : ScriptRunner::commands())
        if (each.name == command) return ScriptCommandShape{each.minArgs, each.maxArgs};
    return std::nullopt;
}

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
                runner.framesRun(), platformKindName(app.platform().kind()), std::chrono::duration<double>(Clock::now() - start).count());
    return status;
}

} // namespace iblab::app
