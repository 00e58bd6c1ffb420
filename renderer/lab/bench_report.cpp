// The bench's reports: CSV and JSON (every point, for scripts) and Markdown (what a reader
// needs first: per environment, what nothing beats).
#include <algorithm>
#include <cstdio>
#include <sstream>

#include <nlohmann/json.hpp>

#include "lab/bench_sweep.hpp"
#include "lab/format.hpp"

namespace iblab::bench {
namespace {

using lab::formatNumber;

// What the frame reads for diffuse, in the reports' words (the sampled method reads SH9).
std::string diffuseName(const SweepPoint& p)
{
    if (p.sampling.diffuse != DiffuseSource::IrradianceCube || p.sampling.method == ShadingMethod::Sampled)
        return p.sampling.diffuse == DiffuseSource::Sh9Plain ? "sh9" : "sh9-windowed";
    return p.bake.irradiance == bake::IrradianceMethod::Moments      ? "moment-cube"
           : p.bake.irradiance == bake::IrradianceMethod::Importance ? "importance-cube"
                                                                     : "riemann-cube";
}

bool pdfFiltering(const SweepPoint& p)
{
    return p.sampling.method == ShadingMethod::Sampled ? p.sampling.pdfMipFiltering : p.bake.prefilter.mipFiltering;
}

std::string csvField(const std::string& text)
{
    if (text.find_first_of(",\"\n") == std::string::npos) return text;
    std::string quoted = "\"";
    for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

} // namespace

const std::vector<std::string>& benchCsvColumns()
{
    static const std::vector<std::string> columns{
        "environment", "family",        "series",         "label",        "method",        "diffuse",      "prefilter_face", "prefilter_samples",
        "pdf_mips",    "sampled_n",     "riemann_delta",  "importance_samples", "bake_ms", "frame_ms",     "cost_ms",        "relative_rmse",
        "mean_relative", "p99_relative", "max_relative",  "fireflies",    "pixels",        "display_p99_steps", "display_rms_steps",
        "display_max_steps", "dominated", "auto_chosen"};
    return columns;
}

std::string benchCsvText(const BenchReport& report)
{
    std::ostringstream out;
    const auto& columns = benchCsvColumns();
    for (std::size_t i = 0; i < columns.size(); ++i) out << (i ? "," : "") << columns[i];
    out << "\n";
    for (const BenchPoint& p : report.points) {
        const SweepPoint& s = p.setting;
        const bool splitSum = readsPrefilteredCube(s.sampling.method);
        // Empty, not 0, where nothing was measured: 0 would read as exact.
        const auto error = [&](double value, const char* format) { return measured(p) ? formatNumber(value, format) : std::string(); };
        const std::vector<std::string> row{csvField(p.environment),
                                           std::string(sweepFamilyName(s.family)),
                                           csvField(s.series),
                                           csvField(s.label),
                                           std::string(enumName(s.sampling.method)),
                                           diffuseName(s),
                                           splitSum ? std::to_string(s.bake.prefilter.faceSize) : "",
                                           splitSum ? std::to_string(s.bake.prefilter.samples) : "",
                                           pdfFiltering(s) ? "1" : "0",
                                           splitSum ? "" : std::to_string(s.sampling.samples),
                                           s.bake.irradiance == bake::IrradianceMethod::Riemann ? formatNumber(s.bake.riemann.sampleDelta, "%g") : "",
                                           s.bake.irradiance == bake::IrradianceMethod::Importance ? std::to_string(s.bake.importance.samples) : "",
                                           formatNumber(p.bakeMilliseconds, "%.3f"),
                                           formatNumber(p.frameMilliseconds, "%.3f"),
                                           formatNumber(p.costMilliseconds, "%.3f"),
                                           error(p.error.relativeRmse, "%.6g"),
                                           error(p.error.meanRelative, "%.6g"),
                                           error(p.error.p99Relative, "%.6g"),
                                           error(p.error.maxRelative, "%.6g"),
                                           measured(p) ? std::to_string(p.error.fireflies) : "",
                                           std::to_string(p.error.pixels),
                                           error(p.display.p99Steps, "%.4g"),
                                           error(p.display.rmsSteps, "%.4g"),
                                           error(p.display.maxSteps, "%.4g"),
                                           p.dominated ? "1" : "0",
                                           p.chosen ? "1" : "0"};
        for (std::size_t i = 0; i < row.size(); ++i) out << (i ? "," : "") << row[i];
        out << "\n";
    }
    return out.str();
}

std::string benchJsonText(const BenchReport& report)
{
    const BenchOptions& o = report.options;
    nlohmann::ordered_json j;
    j["renderer"] = report.renderer;
    j["timing_method"] = "steady clock around glFinish, median of the repeats";
    j["options"] = {{"quick", o.quick},
                    {"scene", enumName(o.frame.scene.kind)},
                    {"width", o.width},
                    {"height", o.height},
                    {"repeats", o.repeats},
                    // null: chosen per environment from the scene (the references' environment_width)
                    {"reference_width", o.referenceWidth > 0 ? nlohmann::ordered_json(o.referenceWidth) : nlohmann::ordered_json(nullptr)},
                    {"cost", "bake_ms + " + std::to_string(o.costFrames) + " x frame_ms"},
                    {"error", "relative RMSE, linear HDR, surface pixels with roughness >= min_resolved_roughness; null where there is none (references' not_measured)"},
                    {"display_error", "largest channel difference after exposure, tone mapping and sRGB encoding, in 8-bit steps, same pixels"},
                    {"tone_map", std::string(enumName(o.frame.toneMap.op)) + ", exposure " + formatNumber(o.frame.toneMap.exposureEv, "%g") + " EV"}};
    for (const BenchEnvironment& e : o.environments) j["environments"].push_back({{"name", e.name}, {"spec", e.spec}});
    for (const ReferenceSummary& r : report.references) {
        nlohmann::ordered_json reference{{"environment", r.environment},
                                         {"environment_width", r.environmentWidth},
                                         {"min_resolved_roughness", r.minResolvedRoughness},
                                         {"milliseconds", r.milliseconds}};
        if (!r.unmeasured.empty()) reference["not_measured"] = r.unmeasured;
        j["references"].push_back(reference);
    }
    for (const BenchPoint& p : report.points) {
        const SweepPoint& s = p.setting;
        nlohmann::ordered_json point{{"environment", p.environment},
                                     {"family", sweepFamilyName(s.family)},
                                     {"series", s.series},
                                     {"label", s.label},
                                     {"method", enumName(s.sampling.method)},
                                     {"diffuse", diffuseName(s)},
                                     {"pdf_mips", pdfFiltering(s)}};
        if (readsPrefilteredCube(s.sampling.method)) {
            point["prefilter"] = {{"face", s.bake.prefilter.faceSize}, {"samples", s.bake.prefilter.samples}, {"levels", s.bake.prefilter.levels}};
            point["specular_read"] = specularReadName(s.sampling);
        } else point["sampled_n"] = s.sampling.samples;
        if (s.bake.irradiance == bake::IrradianceMethod::Riemann) point["riemann_delta"] = s.bake.riemann.sampleDelta;
        if (s.bake.irradiance == bake::IrradianceMethod::Importance) point["importance_samples"] = s.bake.importance.samples;
        nlohmann::ordered_json phases = nlohmann::ordered_json::array();
        for (const bake::BakePhase phase : bakePhasesRead(s)) phases.push_back(enumName(phase));
        point["bake_phases"] = phases;
        point["bake_ms"] = p.bakeMilliseconds;
        point["frame_ms"] = p.frameMilliseconds;
        point["cost_ms"] = p.costMilliseconds;
        // null, not 0, where nothing was measured: 0 would read as exact.
        const auto error = [&](auto value) { return measured(p) ? nlohmann::ordered_json(value) : nlohmann::ordered_json(nullptr); };
        point["error"] = {{"relative_rmse", error(p.error.relativeRmse)},
                          {"mean_relative", error(p.error.meanRelative)},
                          {"p99_relative", error(p.error.p99Relative)},
                          {"max_relative", error(p.error.maxRelative)},
                          {"fireflies", error(p.error.fireflies)},
                          {"pixels", p.error.pixels}};
        point["display_error"] = {
            {"p99_steps", error(p.display.p99Steps)}, {"rms_steps", error(p.display.rmsSteps)}, {"max_steps", error(p.display.maxSteps)}};
        point["dominated"] = p.dominated;
        if (p.chosen) point["auto_chosen"] = true;
        j["points"].push_back(point);
    }
    j["seconds"] = report.seconds;
    return j.dump(2);
}

std::string benchMarkdown(const BenchReport& report)
{
    struct Environment {
        std::string name;
        std::vector<const BenchPoint*> points, front; // front: measured and not dominated
        double cheapest = 0.0;
        std::string unmeasured; // ReferenceSummary::unmeasured
        // The lowest error of a family and what it costs.
        const BenchPoint* best(SweepFamily family) const
        {
            const BenchPoint* found = nullptr;
            for (const BenchPoint* p : points)
                if (measured(*p) && p->setting.family == family && (!found || p->error.relativeRmse < found->error.relativeRmse)) found = p;
            return found;
        }
    };
    std::vector<Environment> environments;
    for (const BenchEnvironment& e : report.options.environments) {
        Environment env{e.name, {}, {}, 0.0, {}};
        for (const BenchPoint& p : report.points) {
            if (p.environment != e.name) continue;
            env.points.push_back(&p);
            if (!p.dominated && measured(p)) env.front.push_back(&p);
        }
        if (env.points.empty()) continue;
        for (const ReferenceSummary& r : report.references)
            if (r.environment == e.name) env.unmeasured = r.unmeasured;
        std::sort(env.front.begin(), env.front.end(), [](const BenchPoint* a, const BenchPoint* b) { return a->costMilliseconds < b->costMilliseconds; });
        if (!env.front.empty()) env.cheapest = std::max(env.front.front()->costMilliseconds, 1e-9);
        environments.push_back(std::move(env));
    }

    std::ostringstream out;
    const auto bestCell = [&](const Environment& env, SweepFamily family) {
        const BenchPoint* p = env.best(family);
        if (!p) return std::string("-");
        return formatNumber(p->error.relativeRmse, "%.3g") + " at " + formatNumber(p->costMilliseconds / env.cheapest, "%.1f") + "x (" + p->setting.label + ")";
    };
    out << "Per environment: how many settings nothing beats on both axes, and each family's lowest relative RMSE with its cost as a "
           "multiple of the environment's cheapest setting.\n\n";
    out << "| environment | not dominated | split-sum: lowest error | sampled: lowest error | diffuse variants: error range |\n|---|---|---|---|---|\n";
    for (const Environment& env : environments) {
        if (env.front.empty()) {
            out << "| " << env.name << " | not measured | n/a | n/a | n/a |\n";
            continue;
        }
        double lo = 1e300, hi = 0.0;
        for (const BenchPoint* p : env.points)
            if (measured(*p) && p->setting.family == SweepFamily::Diffuse) lo = std::min(lo, p->error.relativeRmse), hi = std::max(hi, p->error.relativeRmse);
        out << "| " << env.name << " | " << env.front.size() << " of " << env.points.size() << " | " << bestCell(env, SweepFamily::SplitSum) << " | "
            << bestCell(env, SweepFamily::Sampled) << " | " << (hi > 0.0 ? formatNumber(lo, "%.3g") + " - " + formatNumber(hi, "%.3g") : "-") << " |\n";
    }
    out << "\n";
    for (const Environment& env : environments) {
        if (env.front.empty()) {
            out << "**" << env.name << "**: not measured: " << env.unmeasured << "\n\n";
            continue;
        }
        out << "**" << env.name << "**: " << env.front.size() << " of " << env.points.size() << " settings are not dominated\n\n";
        out << "| setting | cost / cheapest | relative RMSE | bake ms | frame ms |\n|---|---|---|---|---|\n";
        for (const BenchPoint* p : env.front)
            out << "| " << p->setting.label << " | " << formatNumber(p->costMilliseconds / env.cheapest, "%.2f") << " | "
                << formatNumber(p->error.relativeRmse, "%.3g") << " | " << formatNumber(p->bakeMilliseconds, "%.1f") << " | "
                << formatNumber(p->frameMilliseconds, "%.1f") << " |\n";
        out << "\n";
    }
    return out.str();
}

} // namespace iblab::bench
