// `iblab bake`: the bake from the command line, headless (`iblab sh` and `iblab lut` are in
// sh_lut_commands.cpp). It prints its result on stdout (a table, or JSON with --json) and, on
// failure, exits non-zero with one line on stderr naming the file or the problem.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <epoxy/gl.h>
#include <malloc.h>
#include <nlohmann/json.hpp>

#include "asset_paths.hpp"
#include "bake_export.hpp"
#include "bake/bake_accuracy.hpp"
#include "bake/bake_cache.hpp"
#include "bake/bake_files.hpp"
#include "bake/bake_job.hpp"
#include "command_support.hpp"
#include "field_options.hpp"
#include "commands.hpp"
#include "io/environment.hpp"
#include "io/builtin_environments.hpp"
#include "io/error.hpp"
#include "gl/context_error.hpp"
#include "gl/context_info.hpp"
#include "gl/shader_library.hpp"
#include "status_report.hpp"

namespace iblab::app {
namespace {

using Clock = std::chrono::steady_clock;
using nlohmann::ordered_json;

struct BakeCommandOptions {
    std::vector<std::string> environments; // files, builtins or directories (every .exr/.hdr in it)
    std::string preset = "default";
    // Each option given replaces the preset's value (bakeSettingsFields() makes them).
    RecordedFieldOptions<bake::BakeSettings> overrides;
    std::optional<std::string> lutGeometry;
    std::string out;
    std::optional<std::string> exportFormat; // engine layout instead of iblab's files in --out
    std::string cacheDir;
    bool json = false;
    bool noCache = false;
    bool noErrors = false;
    bool errorFloor = false;
    int errorTexelGrid = bake::AccuracyOptions{}.texelsPerFaceEdge;
    int repeat = 1;
    std::string hostWork = "auto";
};

bake::BakeSettings resolveSettings(const BakeCommandOptions& o)
{
    bake::BakeSettings s = bake::presetByName(o.preset);
    // No frame to keep responsive here: each pass is one step per mip unless asked otherwise.
    s.samplesPerStep = bake::kUnslicedBake;
    o.overrides.applyTo(s);
    // One option for the two LUT switches.
    if (o.lutGeometry) {
        if (*o.lutGeometry == "both") {
            s.lut.schlickGgx = s.lut.heightCorrelatedSmith = true;
        } else if (*o.lutGeometry == "none") {
            s.lut.schlickGgx = s.lut.heightCorrelatedSmith = false;
        } else {
            const auto g = parseEnum<GeometryTerm>(*o.lutGeometry);
            if (!g) throw Error("--lut-geometry", "expected " + enumChoicesText<GeometryTerm>() + ", both or none, got \"" + *o.lutGeometry + "\"");
            s.lut.schlickGgx = *g == GeometryTerm::SchlickGGX;
            s.lut.heightCorrelatedSmith = *g == GeometryTerm::HeightCorrelatedSmith;
        }
    }
    bake::validate(s);
    return s;
}

ordered_json textureJson(const bake::BakedTexture& t)
{
    if (!t) return nullptr;
    return {{"size", t.size},
            {"levels", t.levels},
            {"format", t.internalFormat == GL_RGBA16F ? "RGBA16F" : "RGBA32F"},
            {"bytes", t.bytes()}};
}

void printTable(const bake::BakeResult& r, const std::optional<bake::BakeErrors>& errors, const std::string& out)
{
    std::printf("%s: %dx%d, preset %s%s\n", r.source.c_str(), r.sourceWidth, r.sourceHeight, r.settings.preset.c_str(),
                r.fromCache ? " (loaded from the cache)" : "");
    std::printf("environment cube %d (%d mips), prefiltered %d x %d mips (%s layout), GPU memory %.2f MiB\n", r.environmentCube.size,
                r.environmentCube.levels, r.prefiltered.size, r.prefiltered.levels,
                std::string(enumName(r.settings.prefilter.layout)).c_str(), double(r.gpuBytes()) / (1024.0 * 1024.0));
    std::printf("timings (steady clock to each step's fence):\n");
    for (const auto& t : r.timings)
        std::printf("  %-22s %10.1f ms\n", std::string(enumName(t.phase)).c_str(), t.milliseconds);
    std::printf("  %-22s %10.1f ms\n", "total", r.totalMilliseconds);
    if (errors) {
        std::printf("errors against the exact references:\n");
        for (const auto& e : errors->prefilter)
            std::printf("  prefilter mip %d (roughness %.2f): relative RMSE %.4f\n", e.level, e.roughness, e.relativeRmse);
        for (const auto& e : errors->prefilterShaded)
            std::printf("  as shaded, roughness %.3f (lod %.2f): relative RMSE %.4f\n", e.roughness, e.lod, e.relativeRmse);
        std::printf("  as shaded, RMS over roughness:       %.4f\n", errors->prefilterShadedRms);
        std::printf("  irradiance SH9:           mean %.4f max %.4f\n", errors->shIrradiance.mean, errors->shIrradiance.max);
        std::printf("  irradiance SH9 windowed:  mean %.4f max %.4f\n", errors->shIrradianceWindowed.mean,
                    errors->shIrradianceWindowed.max);
        if (errors->irradianceCube && errors->irradianceCubeShaded)
            std::printf("  irradiance cube %-9s mean %.4f max %.4f; as shaded mean %.4f max %.4f\n",
                        (std::string(enumName(errors->irradianceMethod)) + ":").c_str(), errors->irradianceCube->mean,
                        errors->irradianceCube->max, errors->irradianceCubeShaded->mean, errors->irradianceCubeShaded->max);
        for (GeometryTerm term : bake::kGeometryTerms)
            if (errors->lutMaxAbs[std::size_t(term)])
                std::printf("  LUT %-24s max abs %.5f\n", std::string(enumName(term)).c_str(), *errors->lutMaxAbs[std::size_t(term)]);
    }
    if (!out.empty()) std::printf("written to %s\n", out.c_str());
}

// What the maps of one `iblab bake` share: the context, the programs compiled in it, and
// the cache, whose LUTs every map after the first takes from memory (with --no-cache too:
// a cache without a root keeps them in memory only).
struct BakeSession {
    explicit BakeSession(std::filesystem::path cacheRoot) : cache(std::move(cacheRoot)) {}
    HeadlessGl gl{/*debugContext=*/true};
    gl::ShaderLibrary shaders{shaderDirectory()};
    bake::BakeCache cache;
};

struct MapBake {
    std::string environment;
    std::string out; // "" or the directory for this map's files
    // true: wait for this map's cache writes before reporting (one map; its report says how
    // long that took). A batch lets them run under the next map's bake instead.
    bool waitForWrites = true;
};

struct LoadedEnvironment {
    Environment environment;
    double milliseconds = 0.0;
};

// A map decodes on a thread of its own: the first while the context is created, each later
// one of a batch while the map before it bakes (each takes tens of ms here).
std::future<LoadedEnvironment> startLoading(const std::string& path)
{
    return std::async(std::launch::async, [path] {
        const auto loadStart = Clock::now();
        Environment environment = loadEnvironment(path);
        return LoadedEnvironment{std::move(environment), millisecondsSince(loadStart)};
    });
}

// The times of one map's bake that its report gives beside the job's own.
struct BakeRunTimes {
    double loadMs = 0.0, contextMs = 0.0, compileMs = 0.0, cacheWriteWaitMs = 0.0;
    std::optional<double> gpuMs;  // a warm repeat's GL_TIME_ELAPSED, on hardware renderers
    std::vector<double> totals;   // each run's, with --repeat
};

// What --json prints for one map's bake.
ordered_json bakeReportJson(const bake::BakeSettings& settings, const MapBake& map, const bake::BakeResult& result,
                            const std::optional<bake::BakeErrors>& errors, const bake::AccuracyOptions& accuracy, bake::BakeCache& cache,
                            const BakeRunTimes& times, const std::vector<std::string>& notes, const ordered_json& exported,
                            Clock::time_point processStart)
{
    ordered_json j;
    j["source"] = result.source;
    j["source_size"] = {result.sourceWidth, result.sourceHeight};
    j["source_upsample"] = result.sourceUpsample;
    j["renderer"] = gl::describeCurrentContext();
    j["malloc_huge_pages"] = mallocHugePages();
    j["preset"] = settings.preset;
    j["settings"] = ordered_json::parse(bake::toJsonText(settings));
    j["from_cache"] = result.fromCache;
    j["lut_from_cache"] = {{"schlick-ggx", result.lutFromCache[0]}, {"height-correlated-smith", result.lutFromCache[1]}};
    ordered_json timings;
    for (const auto& t : result.timings) timings[std::string(enumName(t.phase))] = t.milliseconds;
    timings["total"] = result.totalMilliseconds;
    j["timings_ms"] = timings;
    ordered_json parts = ordered_json::object();
    for (const auto& t : result.partTimings) parts[t.name] = t.milliseconds;
    j["part_timings_ms"] = parts;
    j["longest_step"] = {{"name", result.longestStep.name}, {"milliseconds", result.longestStep.milliseconds}};
    // Begin to end of the whole job on the GPU's clock, the gaps between its steps included.
    if (times.gpuMs) j["gpu_total_ms"] = *times.gpuMs;
    j["timing_method"] = "steady clock from each step's submission to its fence, one step in flight; shaders: compile (Mesa's disk "
                         "cache makes a second run warm) of what other_ms.programs_while_loading did not compile";
    j["other_ms"] = {{"environment_load", times.loadMs},
                     {"context", times.contextMs},
                     {"programs_while_loading", times.compileMs},
                     {"cache_write_wait", times.cacheWriteWaitMs},
                     {"process", millisecondsSince(processStart)}};
    // The writes' own time, on their thread (a batch reports its total instead).
    if (cache.enabled() && map.waitForWrites) j["other_ms"]["cache_write"] = cache.writeMilliseconds();
    if (times.totals.size() > 1) {
        j["repeat_totals_ms"] = times.totals;
        j["repeat_min_total_ms"] = *std::min_element(times.totals.begin(), times.totals.end());
    }
    j["gpu_bytes"] = result.gpuBytes();
    j["textures"] = {{"environment_cube", textureJson(result.environmentCube)},
                     {"irradiance", textureJson(result.irradianceCube)},
                     {"prefiltered", textureJson(result.prefiltered)},
                     {"brdf_lut_schlick-ggx", textureJson(result.brdfLut[0])},
                     {"brdf_lut_height-correlated-smith", textureJson(result.brdfLut[1])}};
    j["textures"]["irradiance"]["method"] = enumName(result.settings.irradiance);
    j["sh"] = ordered_json::parse(bake::shJsonText(result.sh));
    if (errors) j["errors"] = ordered_json::parse(bake::errorsJsonText(*errors, accuracy));
    j["notes"] = notes;
    if (!map.out.empty()) j["output"] = map.out;
    if (!exported.is_null()) j["export"] = exported;
    return j;
}

// --out without --export: the bake's own directory (bake_files.hpp), its errors in bake.json,
// and both LUTs beside it.
void writeBakeOut(const std::filesystem::path& dir, const bake::BakeResult& result, const std::optional<bake::BakeErrors>& errors,
                  const bake::AccuracyOptions& accuracy, int lutSamples)
{
    ordered_json extra;
    if (errors) extra["errors"] = ordered_json::parse(bake::errorsJsonText(*errors, accuracy));
    bake::writeBakeDirectory(dir, result, extra.empty() ? std::string() : extra.dump());
    for (GeometryTerm term : bake::kGeometryTerms)
        if (const bake::BakedTexture& lut = result.lut(term))
            bake::writeLutExr(dir / ("brdf_lut_" + std::string(enumName(term)) + ".exr"), bake::read2D(lut),
                              lutSamples, term, true, false);
}

// The loader's warnings (texels it repaired, NaN and Inf among them; an LDR input), which the
// GUI shows under the map's line, each naming the map, since a batch prints every map's notes
// on the same stderr.
std::vector<std::string> loaderNotes(const Environment& environment)
{
    std::vector<std::string> notes;
    for (const std::string& warning : environment.warnings) notes.push_back(displayName(environment.source) + ": " + warning);
    return notes;
}

// Bakes one map in the session (made on the first map) and prints its table, or returns its
// JSON report. `loading` decodes map.environment (startLoading); `decoded` runs once it has,
// failed or not, before the bake (a batch starts the next map's decode there). Throws on
// failure; a file that cannot be loaded is the error reported, even when the context failed too.
ordered_json bakeMap(const BakeCommandOptions& o, const bake::BakeSettings& settings, const MapBake& map,
                     std::future<LoadedEnvironment> loading, const std::function<void()>& decoded,
                     std::unique_ptr<BakeSession>& session, Clock::time_point processStart)
{
    // The context and the programs while the map is still decoding (the bake's own compile
    // step then finds them built; in a batch, the first map's already are). A failure here
    // is held until the decode is over: a file that cannot be loaded is the error reported.
    const auto contextStart = Clock::now();
    double contextMs = 0.0;
    double compileMs = 0.0;
    std::exception_ptr setupError;
    try {
        if (!session)
            session = std::make_unique<BakeSession>(o.noCache          ? std::filesystem::path()
                                                    : o.cacheDir.empty() ? bake::defaultCacheDirectory()
                                                                         : std::filesystem::path(o.cacheDir));
        contextMs = millisecondsSince(contextStart);
        const auto compileStart = Clock::now();
        bake::BakeJob::compilePrograms(session->shaders, settings, &session->cache);
        compileMs = millisecondsSince(compileStart);
    } catch (...) {
        setupError = std::current_exception();
    }
    std::optional<LoadedEnvironment> loaded;
    std::exception_ptr loadError;
    try {
        loaded = loading.get();
    } catch (...) {
        loadError = std::current_exception();
    }
    if (decoded) decoded();
    if (loadError) std::rethrow_exception(loadError);
    if (setupError) std::rethrow_exception(setupError);
    auto& [environment, loadMs] = *loaded;
    gl::ShaderLibrary& shaders = session->shaders;
    bake::BakeCache& cache = session->cache;
    const std::size_t glErrorsBefore = session->gl.debug.errorCount();

    // --repeat bakes again in the same process, without the cache, to time warm runs
    // (llvmpipe loads each shader variant's machine code on its first dispatch in a
    // process, Mesa's disk cache or not); the result and timings are the last run's.
    // The pixels are moved into the job when nothing reads them after it (the errors and
    // --repeat do, and --export when it prefilters again): a copy is 6 MB of fresh pages for a
    // 1024x512 map, a few ms.
    const bool pixelsNeededAfter = !o.noErrors || o.repeat > 1 || o.exportFormat;
    const char* importedFormat = environment.imported ? importedBakeFormat(environment.imported->kind) : nullptr; // the job may take it
    std::vector<std::string> notes = loaderNotes(environment);
    bake::BakeResult result =
        bake::BakeJob(shaders, pixelsNeededAfter ? Environment(environment) : std::move(environment), settings, &cache).runToCompletion();
    std::vector<double> totals{result.totalMilliseconds};
    std::optional<double> gpuMs; // a warm repeat's GL_TIME_ELAPSED, on hardware renderers
    for (int i = 1; i < o.repeat; ++i) {
        GpuTimeQuery gpuTime;
        result = bake::BakeJob(shaders, environment, settings).runToCompletion();
        gpuMs = gpuTime.finish();
        totals.push_back(result.totalMilliseconds);
    }
    std::optional<bake::BakeErrors> errors;
    bake::AccuracyOptions accuracy;
    if (cache.enabled()) accuracy.referenceCacheDirectory = cache.root() / "reference";
    accuracy.shadedFloor = o.errorFloor;
    accuracy.texelsPerFaceEdge = o.errorTexelGrid;
    if (!o.noErrors) errors = bake::measureBakeErrors(result, environment.image, shaders, accuracy);

    ordered_json exported;
    if (!map.out.empty() && o.exportFormat) {
        exported = writeEngineExport(shaders, environment, result, *o.exportFormat, map.out, o.json);
    } else if (!map.out.empty()) {
        writeBakeOut(map.out, result, errors, accuracy, settings.lut.samples);
    }
    glFinish();
    if (const std::size_t glErrors = session->gl.debug.errorCount() - glErrorsBefore)
        throw std::runtime_error(std::to_string(glErrors) + " GL error(s), the first: " + session->gl.debug.firstError());

    // The cache's files were being written meanwhile (bake_cache.hpp): the errors above and
    // the --out files overlapped them, and only what is left is waited for here.
    const auto waitStart = Clock::now();
    notes.insert(notes.end(), result.notes.begin(), result.notes.end());
    if (importedFormat) notes.push_back(std::string("imported ") + importedFormat + ": its cubes are uploaded as made, not baked");
    if (errors) notes.insert(notes.end(), errors->notes.begin(), errors->notes.end());
    if (map.waitForWrites)
        for (std::string& note : cache.finishWrites())
            notes.push_back(std::move(note));
    const double cacheWriteWaitMs = millisecondsSince(waitStart);
    for (const std::string& note : notes)
        std::fprintf(stderr, "iblab bake: %s\n", note.c_str());

    if (!o.json) {
        printTable(result, errors, map.out);
        return nullptr;
    }
    const BakeRunTimes times{loadMs, contextMs, compileMs, cacheWriteWaitMs, gpuMs, totals};
    return bakeReportJson(settings, map, result, errors, accuracy, cache, times, notes, exported, processStart);
}

// The maps to bake: each --env in order, a directory standing for every environment image in
// it (isEnvironmentImagePath; sorted by name, hidden files skipped).
std::vector<std::string> expandEnvironments(const std::vector<std::string>& given)
{
    std::vector<std::string> maps;
    for (const std::string& entry : given) {
        std::error_code ec;
        // A directory that holds another tool's bake (a KTX2 pair, an iblab bake) is that bake.
        if (!std::filesystem::is_directory(entry, ec) || isImportedBakeSpec(entry)) {
            maps.push_back(entry);
            continue;
        }
        std::vector<std::string> files;
        for (std::filesystem::directory_iterator it(entry, ec), end; !ec && it != end; it.increment(ec))
            if (it->path().filename().string().front() != '.' && isEnvironmentImagePath(it->path().string()) && it->is_regular_file(ec))
                files.push_back(it->path().string());
        if (ec) throw Error(entry, "cannot list the directory: " + ec.message());
        if (files.empty()) throw Error(entry, std::string("no environment images (") + kEnvironmentImageKinds + ") in the directory");
        std::sort(files.begin(), files.end());
        maps.insert(maps.end(), files.begin(), files.end());
    }
    return maps;
}

// --out DIR for a batch: DIR/<the map's file name without extension>, or the builtin's name.
std::vector<std::string> batchOutputDirectories(const std::string& out, const std::vector<std::string>& maps)
{
    std::vector<std::string> dirs;
    for (const std::string& map : maps) {
        std::string name = std::filesystem::path(map).stem().string();
        if (isBuiltinSpec(map)) name = map.substr(0, map.find('?'));
        std::replace(name.begin(), name.end(), ':', '-');
        const std::string dir = (std::filesystem::path(out) / name).string();
        if (std::find(dirs.begin(), dirs.end(), dir) != dirs.end())
            throw Error("--out", "two maps would be written to " + dir + "; bake them in separate runs");
        dirs.push_back(dir);
    }
    return dirs;
}

// Several maps in one process: one context, its programs and the LUTs for all of them, a
// progress line per map on stderr, one report ({"maps": [...]}: each entry what one map's
// report is, or {"source", "error"} for a map that failed). A map that fails does not stop
// the others; the exit status is 1 if any failed.
int runBakeBatch(const BakeCommandOptions& o, const bake::BakeSettings& settings, const std::vector<std::string>& maps,
                 Clock::time_point processStart)
{
    const std::vector<std::string> outs = o.out.empty() ? std::vector<std::string>(maps.size()) : batchOutputDirectories(o.out, maps);
    std::unique_ptr<BakeSession> session;
    ordered_json reports = ordered_json::array();
    int failed = 0;
    std::future<LoadedEnvironment> next = startLoading(maps.front());
    for (std::size_t i = 0; i < maps.size(); ++i) {
        const auto start = Clock::now();
        std::future<LoadedEnvironment> loading = std::move(next);
        // The next map decodes while this one bakes, not while this one decodes too.
        const auto startNext = [&] {
            if (i + 1 < maps.size()) next = startLoading(maps[i + 1]);
        };
        try {
            reports.push_back(bakeMap(o, settings, {.environment = maps[i], .out = outs[i], .waitForWrites = false}, std::move(loading),
                                      startNext, session, processStart));
            std::fprintf(stderr, "iblab bake: [%zu/%zu] %s: %.0f ms\n", i + 1, maps.size(), maps[i].c_str(), millisecondsSince(start));
        } catch (const std::exception& e) {
            ++failed;
            reports.push_back({{"source", maps[i]}, {"error", oneLine(e.what())}});
            std::fprintf(stderr, "iblab bake: [%zu/%zu] %s: failed: %s\n", i + 1, maps.size(), maps[i].c_str(), oneLine(e.what()).c_str());
        }
    }
    const auto waitStart = Clock::now();
    std::vector<std::string> notes;
    if (session) notes = session->cache.finishWrites();
    const double cacheWriteWaitMs = millisecondsSince(waitStart);
    for (const std::string& note : notes)
        std::fprintf(stderr, "iblab bake: %s\n", note.c_str());
    if (o.json) {
        ordered_json j;
        j["maps"] = reports;
        j["failed"] = failed;
        j["notes"] = notes;
        j["other_ms"] = {{"cache_write_wait", cacheWriteWaitMs}, {"process", millisecondsSince(processStart)}};
        if (session && session->cache.enabled()) j["other_ms"]["cache_write"] = session->cache.writeMilliseconds();
        std::printf("%s\n", j.dump(2).c_str());
    }
    return exitWithoutTeardown(failed > 0 ? 1 : 0);
}

int runBake(const BakeCommandOptions& o, Clock::time_point processStart)
{
    // First, so that nothing below runs twice (the settings, the directory listing).
    restartWithHugePages();
    bake::setHostWorkPlacement(o.hostWork == "threads" ? bake::HostWorkPlacement::WorkerThreads
                               : o.hostWork == "steps" ? bake::HostWorkPlacement::OwnSteps
                                                       : bake::HostWorkPlacement::Auto);
    // Each map's textures and read-backs are the same few sizes (MBs each). From the heap
    // rather than their own mappings, and kept there once freed, the next map of a batch
    // reuses the last one's memory instead of faulting in fresh pages: `measure-bake.sh
    // batch` took about 0.9x the time with these two settings. A one-map bake gets them too
    // (its numbers in docs/performance.md were measured so); it frees little before it exits.
    mallopt(M_MMAP_THRESHOLD, 32 * 1024 * 1024); // glibc's largest
    mallopt(M_TRIM_THRESHOLD, 1024 * 1024 * 1024);
    try {
        const bake::BakeSettings settings = resolveSettings(o);
        if (o.exportFormat && o.out.empty()) throw Error("--export", "needs --out DIR, the directory to write the engine's files to");
        const std::vector<std::string> maps = expandEnvironments(o.environments);
        // One map named as one --env keeps the single report scripts read; a directory or
        // several maps make a batch.
        const bool single = o.environments.size() == 1 && maps.size() == 1 && maps.front() == o.environments.front();
        if (!single) return runBakeBatch(o, settings, maps, processStart);
        std::unique_ptr<BakeSession> session;
        const ordered_json report =
            bakeMap(o, settings, {.environment = maps.front(), .out = o.out}, startLoading(maps.front()), nullptr, session, processStart);
        if (o.json) std::printf("%s\n", report.dump(2).c_str());
        return exitWithoutTeardown(0); // the session's context included
    } catch (const std::exception& e) {
        return failCommand("bake", e.what());
    }
}

} // namespace

Command addBakeCommand(CLI::App& app, ProcessClock::time_point processStart)
{
    auto o = std::make_shared<BakeCommandOptions>();
    CLI::App* c = app.add_subcommand("bake", "Bake an environment on the GPU (headless): cubemap, SH9, irradiance, GGX "
                                             "prefilter, BRDF LUTs; prints per-phase timings and errors against exact references");
    c->add_option("--env", o->environments,
                  "Environment: an image file (.exr, .hdr, .pfm, .tif, .png, .jpg, or any other OpenImageIO reads), builtin:NAME, another "
                  "tool's bake (.ktx, .ktx2, a KTX2 pair's directory), or a directory (every .exr, .hdr, .pfm, .tif, .png and .jpg in it); several --env bake "
                  "one after another in one process (--env A --env B, or --env A B), with a progress line each and one report")
        ->required();
    c->add_option("--preset", o->preset, "Starting settings: default (fast, accurate) or tutorial (LearnOpenGL's)")
        ->capture_default_str()
        ->check(CLI::IsMember({"default", "tutorial"}));
    o->overrides.add(*c, bake::bakeSettingsFields());
    c->add_option("--lut-geometry", o->lutGeometry, "LUT geometry terms: " + enumChoicesText<GeometryTerm>() + ", both or none");
    c->add_option("--out", o->out, "Write the results to DIR (EXR + JSON, see docs/bake.md)");
    c->add_option("--export", o->exportFormat, "Write --out as an engine loads it: filament, khronos or bevy (docs/engine-export.md)")
        ->check([](const std::string& v) { return checkExportFormat(v); });
    c->add_option("--cache-dir", o->cacheDir, "Cache directory (default $IBLAB_CACHE_DIR, $XDG_CACHE_HOME/iblab or ~/.cache/iblab)");
    c->add_flag("--no-cache", o->noCache, "Neither read nor write the cache's files (a batch still bakes its LUTs once)");
    c->add_flag("--no-errors", o->noErrors, "Skip the comparison with the exact references");
    c->add_flag("--error-floor", o->errorFloor,
                "Also measure an exact prefilter of the same sizes as shaded (errors.prefilter_shaded_floor): the interpolation's share");
    c->add_option("--error-texel-grid", o->errorTexelGrid,
                  "The per-mip errors at an N x N grid of texel centres per face, 6 N^2 directions a mip (default 16: 1536; "
                  "each direction costs a sum over the map)")
        ->check(CLI::Range(1, 64));
    c->add_option("--repeat", o->repeat, "Bake N times in this process (the later ones without the cache) and report each total")
        ->check(CLI::Range(1, 100));
    c->add_option("--host-work", o->hostWork,
                  "Where the host work that reads only the map (shading lights, the bright-texel split's plan) runs: auto (worker "
                  "threads beside the GPU's passes on a hardware GPU, steps of its own, with no GL work in flight, on llvmpipe), threads or steps")
        ->capture_default_str()
        ->check(CLI::IsMember({"auto", "threads", "steps"}));
    c->add_flag("--json", o->json, "Print a JSON report");
    return {c, [o, processStart] { return runBake(*o, processStart); }};
}

} // namespace iblab::app
