#pragma once
// The one exception type of the environment layer. Its message is a single line that
// names the thing it is about (a file path, a "builtin:..." spec) and the problem:
//   "env.exr: not equirectangular: 1536x512 is 3:1, expected 2:1"
// Functions that throw it have no side effects on their caller's state (they return new
// values or write atomically), so a caller that catches it keeps what it had.
#include <new>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

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

// Runs work() and lets only Error out: the libraries below (OpenImageIO, OpenEXR, tinygltf,
// nlohmann::json) throw std::bad_alloc for a header that claims more than the machine has,
// and std::exception subclasses of their own. Either becomes one Error naming `subject`:
// "<subject>: out of memory while <doing>" or "<subject>: <failure>: <what()>".
template <typename Work>
auto rethrowAsError(std::string_view subject, std::string_view doing, std::string_view failure, Work&& work) -> decltype(work())
{
    try {
        return std::forward<Work>(work)();
    } catch (const Error&) {
        throw;
    } catch (const std::bad_alloc&) {
        throw Error(subject, "out of memory while " + std::string(doing));
    } catch (const std::exception& e) {
        throw Error(subject, std::string(failure) + ": " + e.what());
    }
}

} // namespace iblab
