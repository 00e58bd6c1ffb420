// The stress report as JSON (everything measured) and as Markdown (what a reader needs first:
// where each method fails and how, then the tables behind it).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "lab/stress_suite.hpp"

namespace iblab::stress {
namespace {

using nlohmann::ordered_json;

// JSON has no NaN or Inf: they are written as strings, so a NaN finding stays visible.
ordered_json number(double v)
{
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    return v;
}

std::string fixed(double v, int digits = 3)
{
    if (std::isnan(v)) return "NaN";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char text[48];
    std::snprintf(text, sizeof text, "%.*g", digits, v);
    return text;
}

int severity(Verdict v) { return v == Verdict::Fail ? 2 : v == Verdict::Warn ? 1 : 0; }

std::string verdictCell(Verdict v)
{
    return v == Verdict::Fail ? "**FAIL**" : v == Verdict::Warn ? "warn" : "pass";
}

std::string where(const Finding& f)
{
    std::string text = f.environment.empty() ? f.condition : f.environment + ", " + f.condition;
    return text;
}

void writeSummary(std::ostream& md, const StressReport& report)
{
    md << "# iblab stress\n\n";
    md << "Renderer: " << report.renderer << (report.options.quick ? " (--quick)" : "") << "; " << fixed(report.seconds, 3) << " s. "
       << "Environments " << report.options.environmentWidth << "x" << report.options.environmentWidth / 2 << ", frames "
       << report.options.frameSize << "x" << report.options.frameSize << ", prefiltered cube " << report.options.bake.prefilter.faceSize
       << " x " << report.options.bake.prefilter.levels << " mips (half floats), LUT " << report.options.bake.lut.size << "^2.\n\n";
    md << "Findings: " << report.count(Verdict::Pass) << " pass, " << report.count(Verdict::Warn) << " warn, " << report.count(Verdict::Fail)
       << " fail. Views: all sphere pixels, normal incidence (n.v >= " << fixed(kNormalMinNdotV) << "), grazing (n.v <= "
       << fixed(kGrazingMaxNdotV) << "). Materials: white metal (F0 = 1) for `splitsum` and `sampled-*`, white plastic (albedo 1, F0 = 0.04) "
       << "for the diffuse variants. Exact references: renderer/ibl/reference.hpp, on the full map for lobes narrower than two texels "
       << "(a mirror there), on a 64-wide copy for wider ones.\n\n";
}

// Per method and check: the worst finding, and where.
void writeWorstPerMethod(std::ostream& md, const StressReport& report)
{
    const std::vector<StressCheck> checks = {StressCheck::Fireflies, StressCheck::NonFinite, StressCheck::Negative,
                                             StressCheck::Furnace,   StressCheck::ShRinging, StressCheck::Seams};
    md << "## Where each method fails\n\nEach cell: the worst value of the check over every environment, roughness and view, and where. "
          "Fireflies: render max / exact max; furnace: |reflected - 1| with multiscatter, energy lost without; SH ringing: -(minimum / mean) "
          "irradiance; seams: jump across cube edges / step inside faces.\n\n";
    md << "| method |";
    for (StressCheck c : checks) md << " " << stressCheckName(c) << " |";
    md << "\n|---|";
    for (std::size_t i = 0; i < checks.size(); ++i) md << "---|";
    md << "\n";
    for (const std::string& method : report.methods) {
        md << "| " << method << " |";
        for (StressCheck check : checks) {
            const Finding* worst = nullptr;
            for (const Finding& f : report.findings) {
                if (f.method != method || f.check != check) continue;
                const bool worse = !worst || severity(f.verdict) > severity(worst->verdict) ||
                                   (severity(f.verdict) == severity(worst->verdict) && (std::isnan(f.value) || f.value > worst->value));
                if (worse) worst = &f;
            }
            if (!worst) md << " - |";
            else if (worst->verdict == Verdict::Pass) md << " pass (" << fixed(worst->value) << ") |";
            else md << " " << verdictCell(worst->verdict) << " " << fixed(worst->value) << " (" << where(*worst) << ") |";
        }
        md << "\n";
    }
}

void writeEnvironments(std::ostream& md, const StressReport& report)
{
    md << "\n## Environments\n\n| name | made to break | peak / mean (map) | repair | bake ms | bake: invalid components | cube power kept |\n"
          "|---|---|---|---|---|---|---|\n";
    for (std::size_t i = 0; i < report.environments.size(); ++i) {
        const EnvironmentSummary& e = report.environments[i];
        const BakeHealth& b = report.bakes[i];
        md << "| `" << e.spec << "` | " << e.breaks << " | " << (e.meanLuminance > 0.0 ? fixed(e.peakLuminance / e.meanLuminance) : "-") << " | "
           << e.repair << " | " << fixed(e.bakeMilliseconds, 4) << " | " << b.nonFiniteTexels + b.negativeTexels << " | " << fixed(b.energyKept, 4)
           << " |\n";
    }
}

void writeFurnace(std::ostream& md, const StressReport& report)
{
    md << "\n## White furnace (reflected energy of a white metal sphere; 1 is exact)\n\n| method | multiscatter | view |";
    for (float r : report.options.roughnesses) md << " r " << fixed(r) << " |";
    md << "\n|---|---|---|";
    for (std::size_t i = 0; i < report.options.roughnesses.size(); ++i) md << "---|";
    md << "\n";
    std::vector<std::string> furnaces;
    for (const EnvironmentSummary& e : report.environments)
        if (e.furnace) furnaces.push_back(e.name);
    const auto inFurnace = [&](const RenderMeasurement& r) { return std::find(furnaces.begin(), furnaces.end(), r.environment) != furnaces.end(); };
    for (const StressMethod& m : stressMethods()) {
        if (m.material != StressMaterial::WhiteMetal) continue; // the furnace identity holds for F0 = 1 alone
        const std::string& method = m.name;
        for (bool multiscatter : {true, false})
            for (ViewBin bin : {ViewBin::Normal, ViewBin::Grazing}) {
                std::string cells;
                for (const RenderMeasurement& r : report.renders)
                    if (inFurnace(r) && r.method == method && r.multiscatter == multiscatter)
                        cells += " " + fixed(r.view(bin).renderMean, 4) + " |";
                if (!cells.empty()) md << "| " << method << " | " << (multiscatter ? "on" : "off") << " | " << viewBinName(bin) << " |" << cells << "\n";
            }
    }
}

void writeShRinging(std::ostream& md, const StressReport& report)
{
    md << "\n## SH9 ringing (minimum irradiance over the sphere / mean, worst channel; negative = ringing)\n\n"
          "| environment | plain SH9 | windowed SH9 | window width (bands) |\n|---|---|---|---|\n";
    for (const ShRinging& s : report.sh)
        md << "| " << s.environment << " | " << fixed(s.plainMinimum) << " | " << fixed(s.windowedMinimum) << " | " << fixed(s.windowWidth) << " |\n";
}

void writeSeams(std::ostream& md, const StressReport& report)
{
    md << "\n## Seams across cube faces (jump across edges / step inside faces)\n\n| environment |";
    std::vector<std::string> levels;
    for (const SeamReading& s : report.seams) {
        const std::string name = s.texture == SeamTexture::Irradiance ? "irradiance cube" : "mip " + std::to_string(s.level) + " (r " + fixed(s.roughness) + ")";
        if (std::find(levels.begin(), levels.end(), name) == levels.end()) levels.push_back(name);
    }
    for (const std::string& l : levels) md << " " << l << " |";
    md << "\n|---|";
    for (std::size_t i = 0; i < levels.size(); ++i) md << "---|";
    md << "\n";
    for (const EnvironmentSummary& e : report.environments) {
        md << "| " << e.name << " |";
        for (const SeamReading& s : report.seams)
            if (s.environment == e.name) md << " " << fixed(s.ratio) << " |";
        md << "\n";
    }
}

void writeLutPrecision(std::ostream& md, const StressReport& report)
{
    md << "\n## BRDF LUT precision (" << report.lut.geometry << ", " << report.lut.size << "^2, RGBA16F)\n\n"
       << "- max |baked - float CPU LUT| over A and B: " << fixed(report.lut.maxAbsVsCpu) << " (half-float rounding alone: "
       << fixed(report.lut.maxAbsQuantisation) << ")\n"
       << "- 8-bit display codes of a white metal under radiance 1 (ACES Hill, A + B), baked vs float: largest difference "
       << report.lut.maxDisplayStep << " code(s), at " << report.lut.texelsWithDisplayStep << " of " << report.lut.size * report.lut.size
       << " texels\n";
}

void writeWarningsAndFailures(std::ostream& md, const StressReport& report)
{
    std::vector<const Finding*> bad;
    for (const Finding& f : report.findings)
        if (f.verdict != Verdict::Pass) bad.push_back(&f);
    std::stable_sort(bad.begin(), bad.end(), [](const Finding* a, const Finding* b) { return severity(a->verdict) > severity(b->verdict); });
    md << "\n## Every warning and failure (" << bad.size() << ")\n\n| verdict | check | method | where | value | threshold |\n|---|---|---|---|---|---|\n";
    for (const Finding* f : bad)
        md << "| " << verdictCell(f->verdict) << " | " << stressCheckName(f->check) << " | " << (f->method.empty() ? "-" : f->method) << " | " << where(*f) << " | "
           << fixed(f->value) << " | " << f->threshold << " |\n";
    md << "\nThe image grid `stress.png`: rows = environments, columns = method x roughness (0, 0.05, 0.5, 1), tone-mapped (ACES Hill) "
          "with the exposure that puts each environment's mean radiance near mid-grey, black = background.\n";
}

} // namespace

std::string stressJsonText(const StressReport& report)
{
    ordered_json j;
    j["renderer"] = report.renderer;
    j["quick"] = report.options.quick;
    j["seconds"] = report.seconds;
    j["frame_size"] = report.options.frameSize;
    j["environment_width"] = report.options.environmentWidth;
    j["roughnesses"] = report.options.roughnesses;
    j["view_bins"] = {{"normal", "n.v >= " + fixed(kNormalMinNdotV)}, {"grazing", "n.v <= " + fixed(kGrazingMaxNdotV)}, {"all", "every sphere pixel"}};
    j["bake"] = ordered_json::parse(bake::toJsonText(report.options.bake));
    j["counts"] = {{"pass", report.count(Verdict::Pass)}, {"warn", report.count(Verdict::Warn)}, {"fail", report.count(Verdict::Fail)}};
    j["methods"] = report.methods;
    for (const EnvironmentSummary& e : report.environments)
        j["environments"].push_back({{"name", e.name},
                                     {"spec", e.spec},
                                     {"breaks", e.breaks},
                                     {"mean_luminance", number(e.meanLuminance)},
                                     {"peak_luminance", number(e.peakLuminance)},
                                     {"peak_to_mean", number(e.meanLuminance > 0.0 ? e.peakLuminance / e.meanLuminance : 0.0)},
                                     {"repair", e.repair},
                                     {"repaired_components", e.repairedComponents},
                                     {"bake_ms", e.bakeMilliseconds}});
    for (const RenderMeasurement& r : report.renders) {
        ordered_json views;
        for (const ViewReading& v : r.views)
            views[std::string(viewBinName(v.bin))] = {{"pixels", v.pixels},
                                                      {"render_max", number(v.renderMax)},
                                                      {"render_mean", number(v.renderMean)},
                                                      {"reference_max", number(v.referenceMax)},
                                                      {"reference_mean", number(v.referenceMean)},
                                                      {"firefly_ratio", number(v.fireflyRatio)},
                                                      {"energy_ratio", number(v.energyRatio)}};
        j["renders"].push_back({{"environment", r.environment},
                                {"method", r.method},
                                {"roughness", r.roughness},
                                {"multiscatter", r.multiscatter},
                                {"nan_components", r.nanComponents},
                                {"inf_components", r.infComponents},
                                {"negative_components", r.negativeComponents},
                                {"views", views}});
    }
    for (const ShRinging& s : report.sh)
        j["sh"].push_back({{"environment", s.environment},
                           {"mean_irradiance", number(s.meanIrradiance)},
                           {"plain_min_over_mean", number(s.plainMinimum)},
                           {"windowed_min_over_mean", number(s.windowedMinimum)},
                           {"window_width", s.windowWidth}});
    for (const SeamReading& s : report.seams)
        j["seams"].push_back({{"environment", s.environment},
                              {"texture", seamTextureName(s.texture)},
                              {"level", s.level},
                              {"roughness", s.roughness},
                              {"edge_jump", number(s.edgeJump)},
                              {"interior_step", number(s.interiorStep)},
                              {"mean_level", number(s.meanLevel)},
                              {"ratio", number(s.ratio)}});
    for (const BakeHealth& b : report.bakes)
        j["bakes"].push_back({{"environment", b.environment},
                              {"non_finite_components", b.nonFiniteTexels},
                              {"negative_components", b.negativeTexels},
                              {"energy_kept", number(b.energyKept)}});
    j["lut"] = {{"geometry", report.lut.geometry},
                {"size", report.lut.size},
                {"max_abs_vs_cpu", number(report.lut.maxAbsVsCpu)},
                {"max_abs_half_quantisation", number(report.lut.maxAbsQuantisation)},
                {"max_display_step", report.lut.maxDisplayStep},
                {"texels_with_display_step", report.lut.texelsWithDisplayStep}};
    j["findings"] = ordered_json::array();
    for (const Finding& f : report.findings)
        j["findings"].push_back({{"check", stressCheckName(f.check)},
                                 {"environment", f.environment},
                                 {"method", f.method},
                                 {"condition", f.condition},
                                 {"value", number(f.value)},
                                 {"threshold", f.threshold},
                                 {"verdict", std::string(verdictName(f.verdict))}});
    return j.dump(2);
}

std::string stressMarkdown(const StressReport& report)
{
    std::ostringstream md;
    writeSummary(md, report);
    writeWorstPerMethod(md, report);
    writeEnvironments(md, report);
    writeFurnace(md, report);
    writeShRinging(md, report);
    writeSeams(md, report);
    writeLutPrecision(md, report);
    writeWarningsAndFailures(md, report);
    return md.str();
}

} // namespace iblab::stress
