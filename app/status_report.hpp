#pragma once
// What an app-layer action (loading an environment or a model, a capture, an export) reports:
// one line, whether it failed, and notes. The GUI shows it as a panel's ui::StatusLine; the
// headless commands print it, without depending on a ui/ header.
#include <filesystem>
#include <string>
#include <vector>

#include "io/builtin_environments.hpp"

namespace iblab::app {

struct StatusReport {
    std::string text;
    bool isError = false;
    // Details worth knowing that are no problem (texels a loader repaired, a model's
    // unsupported extension).
    std::vector<std::string> notes = {};
    // text and notes in one line ("a; b; c"), for logs and reports.
    std::string joined() const
    {
        std::string all = text;
        for (const std::string& note : notes) all += (all.empty() ? "" : "; ") + note;
        return all;
    }
};

// How a report names a file: by its file name (a builtin by its spec).
inline std::string displayName(const std::string& spec)
{
    return isBuiltinSpec(spec) ? spec : std::filesystem::path(spec).filename().string();
}

} // namespace iblab::app
