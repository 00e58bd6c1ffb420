#include "bake_export.hpp"

#include <cstdio>

#include "bake/engine_export.hpp"
#include "io/error.hpp"
#include "lab_session.hpp"

namespace iblab::app {

std::string checkExportFormat(const std::string& name)
{
    return parseEnum<bake::EngineFormat>(name) ? std::string()
                                               : "expected " + enumChoicesText<bake::EngineFormat>() + ", got \"" + name + "\"";
}

nlohmann::ordered_json writeEngineExport(gl::ShaderLibrary& shaders, const Environment& environment, const bake::BakeResult& result,
                                         const std::string& format, const std::string& directory, bool json)
{
    const auto engine = parseEnum<bake::EngineFormat>(format);
    if (!engine) throw Error("--export", checkExportFormat(format));
    const bake::ExportReport report = bake::exportForEngine(shaders, environment, result, *engine, directory);
    nlohmann::ordered_json files = nlohmann::ordered_json::array();
    for (const auto& f : report.files) {
        files.push_back(f.string());
        if (!json) std::printf("exported %s\n", f.string().c_str());
    }
    if (!json && report.reprefiltered)
        std::printf("(prefiltered again in %s's layout: %d mips)\n", format.c_str(),
                    bake::engineBakeSettings(*engine, result.settings).prefilter.levels);
    if (!json && report.clippedToHalf)
        std::printf("(clipped at 65504, the most %s's half-float files hold: the map is brighter)\n", format.c_str());
    return {{"format", format},
            {"files", files},
            {"reprefiltered", report.reprefiltered},
            {"clipped_to_half", report.clippedToHalf},
            {"ms", report.milliseconds}};
}

ui::StatusLine exportCurrentBake(const LabSession& session, gl::ShaderLibrary& shaders, const std::string& format,
                                 const std::string& directory)
{
    if (!session.bake() || !session.environment()) return {"export: nothing is baked yet", true};
    if (session.holdsLastImage() || session.busy()) return {"export: an environment is loading or baking; export once it is shown", true};
    try {
        const nlohmann::ordered_json report = writeEngineExport(shaders, *session.environment(), *session.bake(), format, directory, true);
        ui::StatusLine line{"exported " + std::to_string(report["files"].size()) + " " + format + " files to " + directory, false};
        if (report["reprefiltered"].get<bool>()) line.notes.push_back("prefiltered again in " + format + "'s mip layout");
        if (report["clipped_to_half"].get<bool>()) line.notes.push_back("clipped at 65504, the most " + format + "'s half-float files hold");
        return line;
    } catch (const std::exception& e) {
        return {oneLine(e.what()), true};
    }
}

} // namespace iblab::app
