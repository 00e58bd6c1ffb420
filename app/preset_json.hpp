#pragma once
// What a preset and a capture's embedded settings hold: the frame settings (frame/settings),
// the bake settings they were drawn with (bake/bake_settings) under "bake", and where their
// files are. A file path is written relative to the preset's own directory, so that a preset
// moved with its model still finds it, and also absolute under "absolute_paths", for a
// preset moved without it.
#include <filesystem>
#include <optional>
#include <string>

#include "bake/bake_settings.hpp"
#include "frame/settings.hpp"

namespace iblab::app {

// The JSON text of a preset to be written to `file` (its directory anchors relative paths).
std::string presetJsonText(const FrameSettings& settings, const bake::BakeSettings& bake, const std::filesystem::path& file);

struct Preset {
    FrameSettings settings;
    std::optional<bake::BakeSettings> bake; // absent from presets written before it was saved
};
// Reads a preset (or a capture's .json sidecar) from `file`. Each relative path is found
// beside the file, else at its recorded absolute path, else left as written (relative to
// the working directory). Throws std::runtime_error or iblab::Error naming the problem.
Preset readPreset(const std::filesystem::path& file);

// The convention (frame/conventions) whose bake and shading choices these are, or "".
std::string matchingConvention(const bake::BakeSettings& bake, const SamplingSettings& sampling);

} // namespace iblab::app
