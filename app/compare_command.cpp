// `iblab compare`: the ground truth beside the real-time methods, on several maps. One row
// per environment: the reference (the full integral), then per method its frame and its
// error view against that reference, captioned with its relative RMSE over the pixels the
// reference resolves. The figure docs/results.md shows for the split sum's bias and
// what corrects it (issue #14), and a quick way for a user to see the same on their maps.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "asset_paths.hpp"
#include "command_support.hpp"
#include "commands.hpp"
#include "frame/camera.hpp"
#include "lab/bench_sweep.hpp"
#include "lab/harness.hpp"
#include "lab_session.hpp"
#include "panel_grid.hpp"
#include "view_overlays.hpp"

namespace iblab::app {
namespace {

struct CompareOptions {
    FrameSettings settings;
    std::vector<std::string> environments; // empty: courtyard.exr and city.exr
    std::vector<ShadingMethod> methods{ShadingMethod::SplitSum, ShadingMethod::FittedLobe};
    int size = 256; // of each square panel
    std::string output = "compare.png";
    bool json = false;
};

// The bench's name for what a frame reads (so the figure and the bench's tables agree, and a
// split sum read at a dominant direction says so), or the method's own name.
std::string methodTitle(const SamplingSettings& sampling)
{
    const std::string read = bench::specularReadName(sampling);
    return read.empty() ? std::string(enumName(sampling.method)) : read;
}

// Relative RMSE against the reference, and each method's ratio to the first one's. Printed as a
// Markdown table, then the image's path.
void printCompareTable(const CompareOptions& o, const nlohmann::ordered_json& report)
{
    std::printf("| map |");
    for (ShadingMethod m : o.methods) {
        SamplingSettings sampling = o.settings.sampling;
        sampling.method = m;
        std::printf(" %s |", methodTitle(sampling).c_str());
    }
    std::printf("\n|---|");
    for (std::size_t i = 0; i < o.methods.size(); ++i) std::printf("---|");
    std::printf("\n");
    for (const auto& entry : report["environments"]) {
        std::printf("| %s |", std::filesystem::path(entry["environment"].get<std::string>()).filename().string().c_str());
        const double first = entry["methods"][0]["error"]["relative_rmse"].get<double>();
        for (const auto& method : entry["methods"]) {
            const double rmse = method["error"]["relative_rmse"].get<double>(); // NaN: not measured
            if (std::isnan(rmse)) {
                std::printf(" not measured |");
                continue;
            }
            if (&method == &entry["methods"][0]) std::printf(" %.3f |", rmse);
            else std::printf(" %.3f (%.2fx) |", rmse, rmse / first);
        }
        std::printf("\n");
    }
    std::printf("\n%s\n", o.output.c_str());
}

int runCompare(const CompareOptions& o)
{
    try {
        std::vector<std::string> environments = o.environments;
        if (environments.empty())
            for (const char* name : {"courtyard.exr", "city.exr"}) environments.push_back((assetDirectory() / "environments" / name).string());

        HeadlessGl gl(/*debugContext=*/true);
        Renderer renderer(shaderDirectory());
        lab::Harness harness(renderer);
        OffscreenOverlay overlay;
        const int size = o.size;
        PanelGrid grid(1 + 2 * int(o.methods.size()), int(environments.size()), size, size);
        nlohmann::ordered_json report;
        report["scene"] = std::string(enumName(o.settings.scene.kind));
        report["material"] = {{"metallic", o.settings.material.metallic}, {"roughness", o.settings.material.roughness}};
        report["image"] = o.output;

        for (std::size_t row = 0; row < environments.size(); ++row) {
            FrameSettings settings = o.settings;
            const Environment& environment = harness.loadEnvironment(environments[row]);
            settings.environment.source = environment.source;
            harness.bake(bake::defaultPreset());
            if (settings.camera.distance <= 0.0f) frameAtStart(renderer, settings, 1.0f);
            const std::string mapName = std::filesystem::path(environment.source).filename().string();

            FrameSettings truth = settings;
            truth.sampling.method = ShadingMethod::Reference;
            if (!harness.advanceReference(truth, size, size, std::chrono::hours(24)).complete)
                return failCommand("compare", "the reference did not complete on " + mapName);
            harness.render(truth, size, size);
            overlay.drawOver(renderer, truth, size, size, {mapName, "reference: full integral"});
            grid.place(renderer.readDisplayImage(), 0, int(row));

            nlohmann::ordered_json entry;
            entry["environment"] = environment.source;
            entry["reference_min_resolved_roughness"] = harness.reference().minResolvedRoughness;
            for (std::size_t m = 0; m < o.methods.size(); ++m) {
                FrameSettings frame = settings;
                frame.sampling.method = o.methods[m];
                harness.render(frame, size, size);
                const lab::FrameError error = harness.compareWithReference(renderer.readHdrFrame(), frame.toneMap);
                // NaN when the reference resolves none of the surface's pixels (too rough a
                // lobe for its width): said, never shown as a number.
                char rmse[96];
                if (error.linear.pixels > 0) std::snprintf(rmse, sizeof rmse, "relative RMSE %.3f", error.linear.relativeRmse);
                else std::snprintf(rmse, sizeof rmse, "not measured: reference resolves r >= %.2f", harness.reference().minResolvedRoughness);
                overlay.drawOver(renderer, frame, size, size, {methodTitle(frame.sampling), rmse});
                grid.place(renderer.readDisplayImage(), 1 + 2 * int(m), int(row));

                FrameSettings errorView = frame;
                errorView.view.mode = ViewMode::Error;
                harness.render(errorView, size, size);
                overlay.drawOver(renderer, errorView, size, size, {"error of " + methodTitle(frame.sampling)});
                grid.place(renderer.readDisplayImage(), 2 + 2 * int(m), int(row));

                nlohmann::ordered_json method;
                method["method"] = std::string(enumName(o.methods[m]));
                method["error"] = errorMetricsJson(error.linear);
                method["display_p99_steps"] = error.display.p99Steps;
                entry["methods"].push_back(method);
            }
            report["environments"].push_back(entry);
        }
        if (gl.debug.errorCount() > 0) return failCommand("compare", std::to_string(gl.debug.errorCount()) + " GL error(s), the first: " + gl.debug.firstError());
        grid.writePng(o.output, report.dump());

        if (o.json) {
            std::printf("%s\n", report.dump(2).c_str());
            return 0;
        }
        printCompareTable(o, report);
        return 0;
    } catch (const std::exception& e) {
        return failCommand("compare", e.what());
    }
}

} // namespace

Command addCompareCommand(CLI::App& app, ProcessClock::time_point)
{
    auto o = std::make_shared<CompareOptions>();
    o->settings.scene.kind = SceneKind::Sphere;
    o->settings.camera.distance = 0.0f; // frame the scene
    CLI::App* c = app.add_subcommand("compare", "The reference (full integral) beside real-time methods and their error views, one row per "
                                                "environment, with each method's relative RMSE");
    addFrameOptions(*c, o->settings);
    // Several maps here, where a frame has one.
    c->remove_option(c->get_option("--env"));
    c->add_option("--env", o->environments, "Environment file or builtin spec; repeat for several (default: courtyard.exr and city.exr)");
    c->add_option_function<std::vector<std::string>>(
         "--methods",
         [o](const std::vector<std::string>& names) {
             o->methods.clear();
             for (const std::string& name : names) {
                 const std::optional<ShadingMethod> method = parseEnum<ShadingMethod>(name);
                 if (!method || *method == ShadingMethod::Reference)
                     throw CLI::ValidationError("--methods", "\"" + name + "\" is not a real-time method (the reference is the first column anyway)");
                 o->methods.push_back(*method);
             }
         },
         "Methods beside the reference (default: splitsum fitted-lobe)")
        ->delimiter(',');
    c->add_option("--size", o->size, "Width and height of each panel")->capture_default_str()->check(CLI::Range(16, 2048));
    c->add_option("-o,--output", o->output, "The figure (PNG)")->capture_default_str();
    c->add_flag("--json", o->json, "Print a JSON report instead of the Markdown table");
    return {c, [o] { return runCompare(*o); }};
}

} // namespace iblab::app
