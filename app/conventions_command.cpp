// `iblab conventions`: one material under each convention preset (conventions.hpp), side by
// side with its error against the exact reference, to show where viewers differ. Each row is
// a convention: its frame on the left, its per-pixel error against the reference of its own
// BRDF (the full integral over the environment's texels) on the right, captioned with what it
// chose and the numbers. Prints a Markdown table (or JSON) of the choices and the errors.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "asset_paths.hpp"
#include "frame/camera.hpp"
#include "command_support.hpp"
#include "commands.hpp"
#include "frame/conventions.hpp"
#include "lab/harness.hpp"
#include "lab_session.hpp"
#include "panel_grid.hpp"
#include "view_overlays.hpp"

namespace iblab::app {
namespace {

using Clock = std::chrono::steady_clock;

struct ConventionsOptions {
    FrameSettings settings;
    int width = 480; // of each of the two panels of a row
    int height = 270;
    std::string output = "conventions.png";
    std::vector<std::string> only; // conventions to show; empty: all
    bool json = false;
};

struct Row {
    const ConventionPreset* convention = nullptr;
    ErrorMetrics error = {}; // over the pixels the reference resolves (lab::Harness)
    double bakeMs = 0.0;
    double referenceMs = 0.0;
};

std::string percent(double fraction)
{
    char text[32];
    std::snprintf(text, sizeof text, "%.2f%%", 100.0 * fraction);
    return text;
}

// The frame's caption: the title and the choices that change the picture most; the table has
// all of them.
std::vector<std::string> frameCaption(const ConventionPreset& convention)
{
    const auto choices = conventionChoices(convention);
    auto choice = [&](const char* aspect) {
        for (const auto& [name, value] : choices)
            if (name == aspect) return value;
        return std::string();
    };
    return {std::string(convention.title), choice("geometry term") + ", mip bias " + choice("source-mip bias"),
            choice("roughness per mip"), "LUT: " + choice("Fresnel on LUT") + ", energy comp. " + choice("energy compensation")};
}

// What was shown and measured: printed with --json and stored in the PNG.
nlohmann::ordered_json conventionsReport(const FrameSettings& settings, const std::string& image, const std::vector<Row>& rows)
{
    nlohmann::ordered_json report;
    report["environment"] = settings.environment.source;
    report["material"] = {{"metallic", settings.material.metallic}, {"roughness", settings.material.roughness}};
    report["scene"] = std::string(enumName(settings.scene.kind));
    report["image"] = image;
    for (const Row& row : rows) {
        nlohmann::ordered_json entry;
        entry["name"] = row.convention->name;
        for (const auto& [aspect, choice] : conventionChoices(*row.convention)) entry["choices"][aspect] = choice;
        entry["error"] = errorMetricsJson(row.error);
        entry["timings_ms"] = {{"bake", row.bakeMs}, {"reference", row.referenceMs}};
        report["conventions"].push_back(entry);
    }
    return report;
}

// The Markdown table: a column per convention, a row per choice, then the errors.
void printConventionsTable(const std::vector<Row>& rows, const std::string& image)
{
    std::printf("| |");
    for (const Row& row : rows) std::printf(" %s |", std::string(row.convention->title).c_str());
    std::printf("\n|---|");
    for (std::size_t i = 0; i < rows.size(); ++i) std::printf("---|");
    std::printf("\n");
    const std::size_t aspects = conventionChoices(*rows.front().convention).size();
    for (std::size_t a = 0; a < aspects; ++a) {
        std::printf("| %s |", conventionChoices(*rows.front().convention)[a].first.c_str());
        for (const Row& row : rows) std::printf(" %s |", conventionChoices(*row.convention)[a].second.c_str());
        std::printf("\n");
    }
    std::printf("| relative RMSE vs exact |");
    for (const Row& row : rows) std::printf(" %s |", percent(row.error.relativeRmse).c_str());
    std::printf("\n| p99 / max relative |");
    for (const Row& row : rows) std::printf(" %s / %s |", percent(row.error.p99Relative).c_str(), percent(row.error.maxRelative).c_str());
    std::printf("\n\n%s\n", image.c_str());
}

int runConventions(const ConventionsOptions& o)
{
    try {
        std::vector<const ConventionPreset*> shown;
        for (const ConventionPreset& c : conventionPresets())
            if (o.only.empty() || std::find(o.only.begin(), o.only.end(), c.name) != o.only.end()) shown.push_back(&c);

        HeadlessGl gl(/*debugContext=*/true);
        Renderer renderer(shaderDirectory());
        FrameSettings settings = o.settings;
        if (settings.environment.source.empty()) settings.environment.source = defaultEnvironmentSpec();
        // The lab's harness, as the bench and the stress suite use it: one environment, a bake
        // per convention that reuses the LUTs the ones before it baked, and each frame
        // measured against the reference over the pixels that reference resolves.
        lab::Harness harness(renderer);
        settings.environment.source = harness.loadEnvironment(settings.environment.source).source;
        if (settings.camera.distance <= 0.0f) frameAtStart(renderer, settings, float(o.width) / float(o.height));
        OffscreenOverlay overlay;

        const int width = o.width, height = o.height;
        PanelGrid grid(2, int(shown.size()), width, height);
        std::vector<Row> rows;
        for (std::size_t i = 0; i < shown.size(); ++i) {
            const ConventionPreset& convention = *shown[i];
            Row row{&convention};
            const auto bakeStart = Clock::now();
            harness.bake(conventionBakeSettings(convention));
            row.bakeMs = millisecondsSince(bakeStart);
            applyConvention(convention, settings.sampling);

            // The reference of this convention's BRDF (geometry term, energy compensation),
            // then the frame it is compared with, then the error view of that frame.
            FrameSettings frame = settings;
            frame.view.mode = ViewMode::Final;
            if (!harness.advanceReference(frame, width, height, std::chrono::hours(24)).complete)
                return failCommand("conventions", "the reference did not complete");
            row.referenceMs = harness.reference().milliseconds;

            harness.render(frame, width, height);
            row.error = harness.compareWithReference(renderer.readHdrFrame(), frame.toneMap).linear;
            overlay.drawOver(renderer, frame, width, height, frameCaption(convention));
            grid.place(renderer.readDisplayImage(), 0, int(i));

            FrameSettings errorView = frame;
            errorView.view.mode = ViewMode::Error;
            harness.render(errorView, width, height);
            overlay.drawOver(renderer, errorView, width, height,
                             {"error against the exact integral (" + std::string(enumName(convention.geometry)) +
                                  (convention.multiscatter ? ", energy compensated)" : ")"),
                              "relative RMSE " + percent(row.error.relativeRmse) + ", p99 " + percent(row.error.p99Relative) +
                                  ", max " + percent(row.error.maxRelative)});
            grid.place(renderer.readDisplayImage(), 1, int(i));
            rows.push_back(row);
        }
        if (gl.debug.errorCount() > 0) return failCommand("conventions", std::to_string(gl.debug.errorCount()) + " GL error(s), the first: " + gl.debug.firstError());

        const nlohmann::ordered_json report = conventionsReport(settings, o.output, rows);
        grid.writePng(o.output, report.dump());

        if (o.json)
            std::printf("%s\n", report.dump(2).c_str());
        else
            printConventionsTable(rows, o.output);
        return 0;
    } catch (const std::exception& e) {
        return failCommand("conventions", e.what());
    }
}

} // namespace

Command addConventionsCommand(CLI::App& app, ProcessClock::time_point)
{
    auto o = std::make_shared<ConventionsOptions>();
    o->settings.material.roughness = 0.5f;
    o->settings.camera.distance = 0.0f; // frame the scene
    CLI::App* c = app.add_subcommand("conventions", "One material under each viewer's IBL conventions (LearnOpenGL, Filament, glTF Sample "
                                                    "Viewer, iblab), side by side with each one's error against the exact integral");
    addFrameOptions(*c, o->settings);
    c->add_option("--width", o->width, "Width of each panel (a row is frame + error view)")->capture_default_str()->check(CLI::Range(16, 4096));
    c->add_option("--height", o->height, "Height of each row")->capture_default_str()->check(CLI::Range(16, 4096));
    c->add_option("-o,--output", o->output, "The side-by-side PNG")->capture_default_str();
    c->add_option("--only", o->only, "Show only these conventions (" + conventionNames() + ")")
        ->check([](const std::string& name) { return findConvention(name) ? std::string() : "unknown convention \"" + name + "\""; });
    c->add_flag("--json", o->json, "Print a JSON report instead of the Markdown table");
    return {c, [o] { return runConventions(*o); }};
}

} // namespace iblab::app
