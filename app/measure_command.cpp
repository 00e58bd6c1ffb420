// `iblab measure --env MAP --bake FOREIGN`: another tool's bake (cmgen's _ibl.ktx, a
// glTF-IBL-Sampler KTX2 pair; io/imported_bake.hpp) measured against the exact references
// of the map it was made from, in the measures and JSON keys of `iblab bake --json`'s
// "errors" (bake_accuracy.hpp), so that the two bakes compare on equal terms.
#include <cstdio>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "asset_paths.hpp"
#include "bake/bake_accuracy.hpp"
#include "bake/bake_cache.hpp"
#include "bake/bake_job.hpp"
#include "command_support.hpp"
#include "commands.hpp"
#include "gl/shader_library.hpp"
#include "io/environment.hpp"
#include "io/error.hpp"
#include "io/image_writer.hpp"

namespace iblab::app {
namespace {

using nlohmann::ordered_json;

struct MeasureOptions {
    std::string environment;
    std::string bake;
    std::string writeMap;
    bool json = false;
    bool noCache = false;
    std::string cacheDir;
};

void printTable(const std::string& bake, const bake::BakeResult& result, const bake::BakeErrors& errors)
{
    std::printf("%s: prefiltered %d^2 x %d levels (%s layout), diffuse %s\n", bake.c_str(), result.prefiltered.size, result.prefiltered.levels,
                enumName(result.settings.prefilter.layout).data(), result.irradianceCube ? "cube + SH" : "SH");
    std::printf("  mip  roughness  relative RMSE\n");
    for (const bake::PrefilterLevelError& e : errors.prefilter)
        std::printf("  %3d  %9.3f  %13.4f\n", e.level, double(e.roughness), e.relativeRmse);
    std::printf("  as shaded, RMS over roughness 0..1: %.4f\n", errors.prefilterShadedRms);
    std::printf("  SH irradiance, as shaded: mean %.4f, max %.4f\n", errors.shIrradianceShaded.mean, errors.shIrradianceShaded.max);
    if (errors.irradianceCubeShaded)
        std::printf("  irradiance cube, as shaded: mean %.4f, max %.4f\n", errors.irradianceCubeShaded->mean, errors.irradianceCubeShaded->max);
}

int runMeasure(const MeasureOptions& o)
{
    try {
        const Environment map = loadEnvironment(o.environment);
        if (map.imported) throw Error(o.environment, "--env is the map the bake was made from, not a bake");
        if (!o.writeMap.empty()) {
            // For tools that cannot read the map's compression (cmgen 1.9.25 reads no DWAB):
            // the pixels iblab measures against, as a ZIP float EXR.
            writeExr(o.writeMap, map.image, {.exrCompression = "zip"});
            if (o.bake.empty()) return 0;
        }
        if (o.bake.empty()) throw Error("iblab measure", "--bake is required (or --write-map alone)");
        Environment foreign = loadEnvironment(o.bake);
        if (!foreign.imported) throw Error(o.bake, "not a bake iblab imports (.ktx from cmgen, a .ktx2 pair or its directory)");
        for (const std::string& note : foreign.warnings)
            std::fprintf(stderr, "iblab measure: %s\n", note.c_str());

        HeadlessGl gl{/*debugContext=*/true};
        gl::ShaderLibrary shaders{shaderDirectory()};
        bake::BakeCache cache(o.noCache            ? std::filesystem::path()
                              : o.cacheDir.empty() ? bake::defaultCacheDirectory()
                                                   : std::filesystem::path(o.cacheDir));
        const bake::BakeResult result = bake::BakeJob(shaders, std::move(foreign), bake::defaultPreset(), &cache).runToCompletion();
        bake::AccuracyOptions accuracy;
        if (cache.enabled()) accuracy.referenceCacheDirectory = cache.root() / "reference";
        const bake::BakeErrors errors = bake::measureBakeErrors(result, map.image, shaders, accuracy);
        for (const std::string& note : errors.notes)
            std::fprintf(stderr, "iblab measure: %s\n", note.c_str());
        if (gl.debug.errorCount() > 0) throw std::runtime_error("GL error: " + gl.debug.firstError());
        if (!o.json) {
            printTable(o.bake, result, errors);
            return 0;
        }
        ordered_json j;
        j["source"] = o.environment;
        j["bake"] = o.bake;
        j["files"] = result.source;
        j["imported"] = {{"prefiltered", {{"size", result.prefiltered.size},
                                          {"levels", result.prefiltered.levels},
                                          {"layout", enumName(result.settings.prefilter.layout)}}},
                         {"irradiance_cube", bool(result.irradianceCube)}};
        j["sh"] = ordered_json::parse(bake::shJsonText(result.sh));
        j["errors"] = ordered_json::parse(bake::errorsJsonText(errors, accuracy));
        std::printf("%s\n", j.dump(2).c_str());
        return 0;
    } catch (const std::exception& e) {
        return failCommand("measure", e.what());
    }
}

} // namespace

Command addMeasureCommand(CLI::App& app, ProcessClock::time_point)
{
    auto o = std::make_shared<MeasureOptions>();
    CLI::App* c = app.add_subcommand("measure", "Another tool's bake (cmgen's _ibl.ktx, a glTF-IBL-Sampler KTX2 specular + diffuse pair) "
                                                "against the exact references of the map it was made from, in the measures of "
                                                "`iblab bake --json`'s errors");
    c->add_option("--env", o->environment, "The map the bake was made from (file or builtin spec)")->required();
    c->add_option("--bake", o->bake, "The bake: NAME_ibl.ktx, SPECULAR.ktx2,DIFFUSE.ktx2, or a directory with specular.ktx2 and diffuse.ktx2");
    c->add_option("--write-map", o->writeMap, "Also write the map as iblab loads it (float EXR, ZIP) for tools that cannot read its compression");
    c->add_flag("--json", o->json, "Print JSON (the same \"errors\" object as `iblab bake --json`)");
    c->add_option("--cache-dir", o->cacheDir, "The bake cache's directory, whose LUTs and exact references are used (default: as `iblab bake`)");
    c->add_flag("--no-cache", o->noCache, "Neither read nor write the cached LUTs and references");
    return {c, [o] { return runMeasure(*o); }};
}

} // namespace iblab::app
