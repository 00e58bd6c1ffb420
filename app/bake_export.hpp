#pragma once
// `iblab bake --export FORMAT --out DIR`: the bake written as an engine loads it
// (bake/engine_export.hpp), reported as JSON.
#include <string>

#include <nlohmann/json.hpp>

#include "bake/bake_result.hpp"
#include "gl/shader_library.hpp"
#include "io/environment.hpp"
#include "ui/panels.hpp"

namespace iblab::app {

class LabSession;

// The --export option's check: one of the format names, or a message naming the choices.
std::string checkExportFormat(const std::string& name);
// Writes the files and prints one line per file unless json; returns
// {"format", "files": [...], "reprefiltered", "ms"}.
nlohmann::ordered_json writeEngineExport(gl::ShaderLibrary& shaders, const Environment& environment, const bake::BakeResult& result,
                                         const std::string& format, const std::string& directory, bool json);

// The GUI's Export: the session's current bake (refused while an environment switch is under
// way, when the bake shown may not be the loaded pixels'). Blocks for a new prefilter.
ui::StatusLine exportCurrentBake(const LabSession& session, gl::ShaderLibrary& shaders, const std::string& format,
                                 const std::string& directory);

} // namespace iblab::app
