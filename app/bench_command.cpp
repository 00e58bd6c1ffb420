// `iblab bench`: the speed-against-accuracy sweep (renderer/lab/bench_sweep.hpp),
// headless. Writes bench.csv, bench.json, bench.md (the points nothing dominates, per
// environment) and pareto.png to --out, and prints the CSV's path (or the JSON with --json).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "asset_paths.hpp"
#include "lab/auto_quality.hpp"
#include "bench_chart.hpp"
#include "command_support.hpp"
#include "commands.hpp"
#include "io/atomic_file.hpp"
#include "io/builtin_environments.hpp"
#include "io/environment.hpp"
#include "frame/renderer.hpp"

namespace iblab::app {
namespace {

struct BenchCommandOptions {
    std::vector<std::string> environments;
    std::vector<std::string> families; // empty: every family of the sweep
    SceneSettings scene{.kind = SceneKind::Grid, .modelPath = {}};
    std::optional<float> roughness; // the material's, for the sphere (the grid has its own)
    std::string out = "bench";
    bool json = false;
    bool quick = false;
    // Every point and its reference without energy compensation (SamplingSettings::multiscatter
    // is on by default, and the points start from the default): single scattering, as the
    // bench measured before the default changed.
    bool noMultiscatter = false;
    int width = 0;  // 0: the sweep's default (bench_sweep.cpp)
    int height = 0;
    int repeats = 0;
    int referenceWidth = 0; // 0: per environment from the scene (bench::referenceWidthFor)
    int costFrames = 1;
    bool autoQuality = false;
    double autoTargetSteps = bench::kDefaultAutoTargetSteps;
    int chartWidth = 720;
    int chartHeight = 440;
};

// "courtyard" for a file, "sun" for builtin:sun?..., made unique by a suffix.
std::vector<bench::BenchEnvironment> namedEnvironments(const std::vector<std::string>& specs)
{
    std::vector<bench::BenchEnvironment> list;
    std::set<std::string> taken;
    for (const std::string& spec : specs) {
        std::string name = spec.rfind(kBuiltinPrefix, 0) == 0 ? spec.substr(kBuiltinPrefix.size(), spec.find('?') - kBuiltinPrefix.size())
                                                               : std::filesystem::path(spec).stem().string();
        std::string unique = name;
        for (int k = 2; taken.count(unique); ++k) unique = name + "-" + std::to_string(k);
        taken.insert(unique);
        list.push_back({unique, spec, nullptr});
    }
    return list;
}

// Runs the sweep to the end, naming each environment on stderr as it starts.
bench::BenchReport runReported(Renderer& renderer, const bench::BenchOptions& options)
{
    bench::BenchJob job(renderer, options);
    const bench::BenchEnvironment* reported = nullptr;
    while (job.step()) {
        const bench::BenchEnvironment* environment = job.currentEnvironment();
        const std::vector<bench::BenchEnvironment>& all = job.report().options.environments;
        if (environment && environment != reported)
            std::fprintf(stderr, "iblab bench: %s (%zu/%zu)\n", environment->name.c_str(), std::size_t(environment - all.data()) + 1, all.size());
        reported = environment;
    }
    return job.runToCompletion();
}

// One environment's auto run into the whole report: its environment, reference and points,
// and its points' settings where no earlier environment had them (the charts' series order).
void mergeReport(bench::BenchReport& into, bench::BenchReport one)
{
    if (into.options.environments.empty()) {
        into = std::move(one);
        return;
    }
    for (const bench::SweepPoint& p : one.options.points)
        if (std::none_of(into.options.points.begin(), into.options.points.end(), [&](const bench::SweepPoint& q) { return q.label == p.label; }))
            into.options.points.push_back(p);
    into.options.environments.insert(into.options.environments.end(), one.options.environments.begin(), one.options.environments.end());
    into.references.insert(into.references.end(), one.references.begin(), one.references.end());
    into.points.insert(into.points.end(), one.points.begin(), one.points.end());
    into.seconds += one.seconds;
}

void dropMultiscatter(const BenchCommandOptions& o, std::vector<bench::SweepPoint>& points)
{
    if (o.noMultiscatter)
        for (bench::SweepPoint& p : points) p.sampling.multiscatter = false;
}

int runBench(const BenchCommandOptions& o)
{
    try {
        HeadlessGl gl(/*debugContext=*/true);
        Renderer renderer(shaderDirectory());
        bench::BenchOptions options = bench::defaultBenchOptions(o.quick, assetDirectory().string());
        if (!o.environments.empty()) options.environments = namedEnvironments(o.environments);
        if (!o.families.empty())
            std::erase_if(options.points, [&](const bench::SweepPoint& p) {
                return std::find(o.families.begin(), o.families.end(), bench::sweepFamilyName(p.family)) == o.families.end();
            });
        dropMultiscatter(o, options.points);
        options.frame.scene = o.scene;
        if (o.roughness) options.frame.material.roughness = *o.roughness;
        if (o.width > 0) options.width = o.width;
        if (o.height > 0) options.height = o.height;
        if (o.repeats > 0) options.repeats = o.repeats;
        if (o.referenceWidth > 0) options.referenceWidth = o.referenceWidth;
        options.costFrames = o.costFrames;

        bench::BenchReport report;
        std::vector<bench::AutoChoice> choices;
        if (o.autoQuality) {
            // Per environment, since what it prunes depends on the environment's dynamic range.
            for (bench::BenchEnvironment environment : options.environments) {
                if (!environment.loaded) environment.loaded = std::make_shared<const Environment>(loadEnvironment(environment.spec));
                const bench::AutoCandidates candidates = bench::autoCandidates(o.quick, bench::sceneFacts(options.frame, environment.loaded->image));
                bench::BenchOptions one = options;
                one.environments = {environment};
                one.points = candidates.points;
                for (bench::SweepPoint& preset : bench::presetPoints(o.quick)) one.points.push_back(std::move(preset));
                dropMultiscatter(o, one.points);
                bench::BenchReport measured = runReported(renderer, one);
                bench::AutoChoice choice = bench::chooseAuto(measured, o.autoTargetSteps, candidates);
                bench::markChosen(measured.points, choice);
                mergeReport(report, std::move(measured));
                choices.push_back(std::move(choice));
            }
        } else {
            report = runReported(renderer, options);
        }
        if (gl.debug.errorCount() > 0) return failCommand("bench", std::to_string(gl.debug.errorCount()) + " GL error(s), the first: " + gl.debug.firstError());

        const std::filesystem::path dir(o.out);
        std::filesystem::create_directories(dir);
        const std::string json = o.autoQuality ? bench::benchJsonTextWithAuto(report, choices) : bench::benchJsonText(report);
        writeTextFileAtomic((dir / "bench.json").string(), json);
        writeTextFileAtomic((dir / "bench.csv").string(), bench::benchCsvText(report));
        writeTextFileAtomic((dir / "bench.md").string(), (o.autoQuality ? bench::autoMarkdown(report, choices) : "") + bench::benchMarkdown(report));
        writeChartsPng((dir / "pareto.png").string(), o.autoQuality ? benchCharts(report, ChartError::DisplayP99, o.autoTargetSteps) : benchCharts(report), o.chartWidth, o.chartHeight, 2);
        if (gl.debug.errorCount() > 0) return failCommand("bench", std::to_string(gl.debug.errorCount()) + " GL error(s) drawing the chart, the first: " + gl.debug.firstError());

        // The files stand (their costs are measured), but a run that could not measure an
        // environment it was given has not done what it was asked: it says why and fails.
        const std::vector<std::string> unmeasured = bench::unmeasuredEnvironments(report);
        for (const std::string& line : unmeasured) std::fprintf(stderr, "iblab bench: %s\n", line.c_str());
        const int status = unmeasured.empty() ? 0 : 1;
        if (o.json) {
            std::printf("%s\n", json.c_str());
            return status;
        }
        for (const bench::AutoChoice& c : choices)
            if (!c.found) std::printf("auto %s: nothing measured: %s\n", c.chosen.environment.c_str(), c.reasons.back().c_str());
            else std::printf("auto %s: %s (target %g steps)\n  %s\n  cost %.1f ms, display p99 %.3g steps, RMS %.3g steps, relative RMSE %.3g\n", c.chosen.environment.c_str(),
                        c.meetsTarget ? "met" : c.found ? "out of reach" : "nothing measured", c.targetSteps, bench::describeSettings(c.chosen.setting).c_str(),
                        c.chosen.costMilliseconds, c.chosen.display.p99Steps, c.chosen.display.rmsSteps, c.chosen.error.relativeRmse);
        std::printf("%s\n", (dir / "bench.csv").string().c_str());
        return status;
    } catch (const std::exception& e) {
        return failCommand("bench", e.what());
    }
}

} // namespace

Command addBenchCommand(CLI::App& app, ProcessClock::time_point)
{
    auto o = std::make_shared<BenchCommandOptions>();
    CLI::App* c = app.add_subcommand("bench", "Speed against accuracy: every method and setting of the sweep, baked, timed and compared with the "
                                              "reference; writes bench.csv, bench.json, bench.md and pareto.png");
    c->add_option("--env", o->environments, "Environment file or builtin spec; repeat for several (default: the bundled maps and three stress environments)");
    c->add_option_function<std::string>(
         "--scene",
         [o](const std::string& value) {
             if (const auto kind = parseEnum<SceneKind>(value); kind && *kind != SceneKind::Model && *kind != SceneKind::None) {
                     o->scene.kind = *kind;
                     return;
                 }
             const std::string ext = std::filesystem::path(value).extension().string();
             if (ext != ".gltf" && ext != ".glb") throw CLI::ValidationError("--scene", "expected sphere, grid, counting, sweep or a .gltf/.glb file, got \"" + value + "\"");
             o->scene.kind = SceneKind::Model;
             o->scene.modelPath = value;
         },
         "Scene: sphere|grid|counting|sweep|FILE.gltf|FILE.glb")
        ->default_str("grid");
    c->add_option_function<float>(
         "--roughness", [o](float value) { o->roughness = value; }, "Perceptual roughness of the material (the sphere; default the sliders' 0.3)")
        ->check(CLI::Range(0.0, 1.0));
    c->add_option("--family", o->families, "Only the sweep points of this family; repeat for several (default: every family)")
        ->check(CLI::IsMember(std::vector<std::string>(bench::kSweepFamilyNames.begin(), bench::kSweepFamilyNames.end())));
    c->add_option("--out", o->out, "Directory for bench.csv, bench.json, bench.md and pareto.png")->capture_default_str();
    c->add_flag("--json", o->json, "Print the JSON report on stdout instead of the CSV's path");
    c->add_flag("--quick", o->quick, "A tiny sweep on a small builtin (seconds; for tests)");
    c->add_flag("--no-multiscatter", o->noMultiscatter, "Every point and its reference without energy compensation (single scattering)");
    c->add_option("--width", o->width, "Image width (default 128, quick 48)")->check(CLI::Range(8, 4096));
    c->add_option("--height", o->height, "Image height (default 128, quick 48)")->check(CLI::Range(8, 4096));
    c->add_option("--repeats", o->repeats, "Timed frames per point, median reported (default 5, quick 3)")->check(CLI::Range(1, 1000));
    c->add_option("--reference-width", o->referenceWidth, "Width of the environment the reference sums over (default: from 64, doubled until it resolves the scene's smoothest "
                                             "surface, up to 512, quick 128, and the map's width)")
        ->check(CLI::Range(8, 4096));
    c->add_option("--cost-frames", o->costFrames, "cost = bake + this many frames")->capture_default_str()->check(CLI::Range(0, 1000000));
    c->add_flag("--auto", o->autoQuality,
                "Auto quality: per environment, measure the candidate settings the scene and environment leave, choose the cheapest within "
                "--auto-target, and measure the tutorial and default presets beside it (instead of the sweep)");
    c->add_option("--auto-target", o->autoTargetSteps, "Auto quality's target: 99th-percentile display error in 8-bit steps after tone mapping")
        ->capture_default_str()
        ->check(CLI::Range(0.01, 255.0));
    c->add_option("--chart-width", o->chartWidth, "Width of one environment's chart in pareto.png")->capture_default_str()->check(CLI::Range(320, 4096));
    c->add_option("--chart-height", o->chartHeight, "Height of one environment's chart in pareto.png")->capture_default_str()->check(CLI::Range(200, 4096));
    return {c, [o] { return runBench(*o); }};
}

} // namespace iblab::app
