#pragma once
// The one exception type of the environment layer. Its message is a single line that
// names the thing it is about (a file path, a "builtin:..." spec) and the problem:
//   "env.exr: not equirectangular: 1536x512 is 3:1, expected 2:1"
// Functions that throw it have no side effects on their caller's state (they return new
// values or write atomically), so a caller that catches it keeps what it had.
#include <stdexcept>
#include <string>
#include <string_view>

namespace iblab {

// Collapses line breaks (OpenImageIO error texts often span several lines) and trims, so
// that every Error prints as exactly one line.
inline std::string oneLine(std::string_view text)
{
    std::string out;
    out.reserve(text.size());
    bool pendingBreak = false;
    for (char c : text) {
        if (c == '\n' || c == '\r') {
            pendingBreak = !out.empty();
            continue;
        }
        if (pendingBreak) {
            out += "; ";
            pendingBreak = false;
        }
        out += c;
    }
    while (!out.empty() && (out.back() == ' ' || out.back() == ';'))
        out.pop_back();
    return out;
}

struct Error : std::runtime_error {
    // "subject: problem", on one line.
    Error(std::string_view subject, std::string_view problem)
        : std::runtime_error(oneLine(std::string(subject) + ": " + std::string(problem)))
    {
    }
};

} // namespace iblab
