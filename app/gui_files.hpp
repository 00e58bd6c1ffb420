#pragma once
// The files the GUI reads and writes for the user: presets, and the names of screenshots.
#include <filesystem>
#include <string>

#include "frame/settings.hpp"
#include "lab_session.hpp"
#include "ui/panels.hpp"

namespace iblab::app {

ui::StatusLine savePreset(const std::string& path, const FrameSettings& settings);
// A preset replaces every setting; its environment and model load like a user's choice.
ui::StatusLine loadPreset(const std::string& path, FrameSettings& settings, LabSession& session);
// A screenshot name nobody has used: iblab-<environment>-<date>-<time>[-n].<ext> in
// `directory`, or `requested` (made unique the same way) when the user typed one. A capture
// never overwrites a file.
std::filesystem::path captureName(const std::filesystem::path& directory, const std::string& requested, const std::string& environment,
                                  const std::string& extension);

} // namespace iblab::app
