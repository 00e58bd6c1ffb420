// The GUI script's checks: pixel measures over regions and snapshots, and comparisons of
// the app's state (JSON) with expected values.
#include "gui_script_checks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace iblab::app {
namespace {

Region clipped(Region r, const WindowPixels& p)
{
    return {std::clamp(r.x0, 0, p.width), std::clamp(r.y0, 0, p.height), std::clamp(r.x1, 0, p.width), std::clamp(r.y1, 0, p.height)};
}

} // namespace

double meanLevel(const WindowPixels& p, Region r)
{
    r = clipped(r, p);
    double sum = 0.0;
    std::size_t count = 0;
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x, ++count) {
            const std::uint8_t* px = &p.rgba[(std::size_t(y) * std::size_t(p.width) + std::size_t(x)) * 4];
            sum += (double(px[0]) + double(px[1]) + double(px[2])) / 3.0;
        }
    if (count == 0) throw StepFailed("empty region");
    return sum / double(count);
}

double meanDifference(const Snapshot& before, const WindowPixels& now)
{
    if (before.pixels.width != now.width || before.pixels.height != now.height) return 255.0;
    const Region r = clipped(before.region, now);
    double sum = 0.0;
    std::size_t count = 0;
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x)
            for (int ch = 0; ch < 3; ++ch, ++count) {
                const std::size_t at = (std::size_t(y) * std::size_t(now.width) + std::size_t(x)) * 4 + std::size_t(ch);
                sum += std::abs(double(now.rgba[at]) - double(before.pixels.rgba[at]));
            }
    if (count == 0) throw StepFailed("empty region");
    return sum / double(count);
}

bool compareValues(const nlohmann::json& actual, const std::string& op, const nlohmann::json& expected, std::string& why)
{
    bool ok = false;
    if (actual.is_number() && expected.is_number()) {
        const double a = actual.get<double>(), e = expected.get<double>();
        // Settings travel as float: 0.3 reads back as 0.30000001.
        const double tolerance = 1e-5 * std::max(1.0, std::abs(e));
        if (op == "==") ok = std::abs(a - e) <= tolerance;
        else if (op == "!=") ok = std::abs(a - e) > tolerance;
        else if (op == "<") ok = a < e;
        else if (op == "<=") ok = a <= e + tolerance;
        else if (op == ">") ok = a > e;
        else if (op == ">=") ok = a >= e - tolerance;
        else if (op == "~") ok = std::abs(a - e) <= 0.01 * std::max(1.0, std::abs(e));
        else throw StepFailed("unknown comparison \"" + op + "\" (== != < <= > >= ~ contains)");
    } else if (op == "==") {
        ok = actual == expected;
    } else if (op == "!=") {
        ok = actual != expected;
    } else if (op == "contains" || op == "~") {
        ok = actual.is_string() && expected.is_string() && actual.get<std::string>().find(expected.get<std::string>()) != std::string::npos;
        if (actual.is_array()) ok = std::find(actual.begin(), actual.end(), expected) != actual.end();
    } else {
        throw StepFailed("\"" + op + "\" compares numbers only; got " + actual.dump() + " and " + expected.dump());
    }
    if (!ok) why = "got " + actual.dump() + ", expected " + op + " " + expected.dump();
    return ok;
}

bool checkState(const nlohmann::json& state, const std::string& pointerText, const std::string& op,
                const std::string& valueText, std::string& why)
{
    nlohmann::json::json_pointer pointer;
    try {
        pointer = nlohmann::json::json_pointer(pointerText);
    } catch (const std::exception&) {
        throw StepFailed("\"" + pointerText + "\" is not a JSON pointer (like /settings/scene/kind)");
    }
    if (!state.contains(pointer)) throw StepFailed("the state has no " + pointerText);
    nlohmann::json expected;
    try {
        expected = nlohmann::json::parse(valueText);
    } catch (const std::exception&) {
        expected = valueText; // a bare word is a string: grid, splitsum
    }
    return compareValues(state.at(pointer), op, expected, why);
}

} // namespace iblab::app
