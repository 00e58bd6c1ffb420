#pragma once
// The files the GUI reads and writes for the user: presets, and the names of screenshots.
#include <filesystem>
#include <string>

#include "frame/settings.hpp"
#include "lab_session.hpp"
#include "loaded_model.hpp"
#include "status_report.hpp"
#include "ui/panels.hpp"

namespace iblab::app {

// A session's, model's or capture's report, as a panel's status line.
inline ui::StatusLine toStatusLine(StatusReport report) { return {std::move(report.text), report.isError, std::move(report.notes)}; }
// The environments the panel offers: the bundled gallery and the builtins.
ui::EnvironmentCatalog environmentCatalog();

// A preset holds the frame and bake settings and the paths of its files (preset_json.hpp).
ui::StatusLine savePreset(const std::string& path, const FrameSettings& settings, const bake::BakeSettings& bake);
// A preset replaces every setting; its environment and model load like a user's choice, and
// its bake settings, where they differ, bake the environment again (the status says so).
// `convention` becomes the convention the loaded settings are, or ""; `saved`, on success,
// what counts as saved (the preset, its environment included while that loads).
ui::StatusLine loadPreset(const std::string& path, FrameSettings& settings, FrameSettings& saved, LabSession& session, LoadedModel& model,
                          std::string& convention);
// A screenshot name nobody has used: iblab-<environment>-<date>-<time>[-n].<ext> in
// `directory`, or `requested` (made unique the same way) when the user typed one. A capture
// never overwrites a file.
std::filesystem::path captureName(const std::filesystem::path& directory, const std::string& requested, const std::string& environment,
                                  const std::string& extension);

} // namespace iblab::app
