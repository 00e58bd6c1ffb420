#include "lab/auto_quality.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <utility>

#include <nlohmann/json.hpp>

#include "ibl/luminance.hpp"
#include "ibl/prefilter_lod.hpp"
#include "ibl/reference.hpp"
#include "lab/format.hpp"

namespace iblab::bench {
namespace {

using lab::formatNumber;

constexpr double kPi = 3.14159265358979323846;
// Pixels more than this many times the reference are fireflies (common/error_metrics.glsl's isFirefly).
constexpr double kFireflyRatio = 3.0;
// The reflected GGX lobe's full width at half maximum, in radians per unit alpha (ibl/reference.hpp).
constexpr double kLobeWidthPerAlpha = 2.6;

struct CandidateSpace {
    std::vector<int> faces, levels, prefilterSamples, sampledN;
    int cubeSamples = 0; // the irradiance cube's cosine importance samples per texel
};

CandidateSpace candidateSpace(bool quick)
{
    // Quick: a few seconds on llvmpipe for the GUI and the tests. Levels 5 and 6 are
    // LearnOpenGL's and iblab's (Filament's quadratic layout over 6 levels) mip counts.
    if (quick) return {{32, 64}, {5, 6}, {4, 16}, {1, 4, 16, 64}, 64};
    return {{32, 64, 128}, {5, 6}, {4, 16, 64, 256}, {1, 4, 16, 64, 256}, 1024};
}

// The prefilter face whose mip, at the smoothest roughness the scene shows, has two texels
// across that mip's lobe (its half-maximum width); larger faces add texels no surface there
// resolves. Unbounded when the scene shows a mirror (mip 0 is read).
int largestUsefulFace(double minRoughness, int levels)
{
    const int mip = int(std::floor(prefilterMipFromRoughness(float(minRoughness), float(levels), int(bake::RoughnessLayout::Quadratic))));
    if (mip <= 0) return std::numeric_limits<int>::max();
    const double roughness = prefilterRoughnessFromMip(float(mip), float(levels), int(bake::RoughnessLayout::Quadratic));
    const double lobe = kLobeWidthPerAlpha * roughness * roughness;
    const double texelsAtMip0 = std::ldexp(2.0 * (kPi / 2.0) / lobe, mip); // a face spans pi/2
    int face = 1;
    while (face < texelsAtMip0) face *= 2;
    return face;
}

bool pdfFiltered(const SweepPoint& p) { return p.sampling.method == ShadingMethod::Sampled ? p.sampling.pdfMipFiltering : p.bake.prefilter.mipFiltering; }
int samplesOf(const SweepPoint& p) { return p.sampling.method == ShadingMethod::Sampled ? p.sampling.samples : p.bake.prefilter.samples; }
bool readsPrefiltered(const SweepPoint& p) { return readsPrefilteredCube(p.sampling.method); }
bool readsCube(const SweepPoint& p) { return readsPrefiltered(p) && p.sampling.diffuse == DiffuseSource::IrradianceCube; }

std::string pointSummary(const BenchPoint& p)
{
    return p.setting.label + ": cost " + formatNumber(p.costMilliseconds, "%.3g") + " ms, p99 " + formatNumber(p.display.p99Steps, "%.3g") + " steps";
}

} // namespace

double environmentDynamicRange(const ImageRGB32F& environment)
{
    double peak = 0.0, weighted = 0.0, weights = 0.0;
    for (int y = 0; y < environment.height; ++y) {
        const double rowSolidAngle = std::sin((double(y) + 0.5) / double(environment.height) * kPi);
        for (int x = 0; x < environment.width; ++x) {
            const float* t = &environment.texels[environment.offset(x, y)];
            const double luminance = iblab::luminance(t);
            peak = std::max(peak, luminance);
            weighted += rowSolidAngle * luminance;
            weights += rowSolidAngle;
        }
    }
    if (weights <= 0.0 || weighted <= 0.0) return 1.0;
    return std::max(1.0, peak / (weighted / weights));
}

SceneFacts sceneFacts(const FrameSettings& frame, const ImageRGB32F& environment)
{
    SceneFacts f;
    f.dynamicRange = environmentDynamicRange(environment);
    f.environmentWidth = environment.width;
    const MaterialSettings& m = frame.material;
    const auto fromSliders = [&](const std::string& what) {
        f.minRoughness = f.maxRoughness = m.roughness;
        f.minMetallic = f.maxMetallic = m.metallic;
        f.surfaces = what + ": roughness " + formatNumber(m.roughness, "%.3g") + ", metallic " + formatNumber(m.metallic, "%.3g") + " (the material sliders)";
    };
    switch (frame.scene.kind) {
    case SceneKind::Grid: f.surfaces = "the metallic x roughness grid: roughness 0..1, metallic 0..1"; break;
    case SceneKind::Sweep:
        f.minMetallic = f.maxMetallic = m.metallic;
        f.surfaces = "the roughness sweep: roughness 0..1, metallic " + formatNumber(m.metallic, "%.3g");
        break;
    case SceneKind::Sphere: fromSliders("the sphere"); break;
    case SceneKind::Counting: fromSliders("the counting strip"); break;
    case SceneKind::Model:
        if (m.overrideModel) fromSliders("the model, its material overridden");
        else f.surfaces = "the model's own materials (not read: taken as roughness 0..1, metallic 0..1)";
        break;
    case SceneKind::None:
        f.hasSurfaces = false;
        f.surfaces = "no surfaces (the environment alone)";
        break;
    }
    return f;
}

int maxReferenceWidth(bool quick) { return quick ? 128 : 512; }

int referenceWidthFor(double smoothestRoughness, int widest)
{
    int width = std::min(64, widest);
    while (width * 2 <= widest && referenceMinResolvedRoughness(width) > smoothestRoughness) width *= 2;
    return width;
}

int referenceWidthFor(const SceneFacts& facts, bool quick)
{
    const int cap = maxReferenceWidth(quick);
    return referenceWidthFor(facts.minRoughness, facts.environmentWidth > 0 ? std::min(cap, facts.environmentWidth) : cap);
}

std::string describeSettings(const SweepPoint& p)
{
    std::string text;
    if (p.sampling.method == ShadingMethod::Sampled)
        text = "sampled, N = " + std::to_string(p.sampling.samples);
    else
        text = specularReadName(p.sampling) + ", prefilter face " + std::to_string(p.bake.prefilter.faceSize) + ", " + std::to_string(p.bake.prefilter.levels) + " mips, " +
               std::to_string(p.bake.prefilter.samples) + " samples at mip 1 (x" + formatNumber(p.bake.prefilter.sampleGrowth, "%.3g") + " per mip" +
               (p.bake.prefilter.mipSampleScale.empty() ? "" : ", mip factors " + numberListText(p.bake.prefilter.mipSampleScale)) + ")";
    text += pdfFiltered(p) ? ", PDF mips" : ", no PDF mips";
    if (readsCube(p)) {
        if (p.bake.irradiance == bake::IrradianceMethod::Moments)
            text += ", moment irradiance cube " + std::to_string(p.bake.moments.faceSize) + "^2 over " +
                    std::to_string(p.bake.moments.sourceFaceSize) + "^2 groups per face";
        else if (p.bake.irradiance == bake::IrradianceMethod::Importance)
            text += ", irradiance cube " + std::to_string(p.bake.importance.faceSize) + "^2 x " + std::to_string(p.bake.importance.samples) + " samples";
        else text += ", Riemann irradiance cube " + std::to_string(p.bake.riemann.faceSize) + "^2, delta " + formatNumber(p.bake.riemann.sampleDelta, "%.3g");
    } else text += p.sampling.diffuse == DiffuseSource::Sh9Plain ? ", plain SH9" : ", SH9";
    return text;
}

AutoCandidates autoCandidates(bool quick, const SceneFacts& facts)
{
    const CandidateSpace space = candidateSpace(quick);
    const bake::BakeSettings base = benchBaseBake(quick);
    AutoCandidates out;
    out.facts = facts;

    std::vector<SweepPoint> all;
    const auto add = [&](SweepPoint p, const std::string& series) {
        p.series = series;
        p.scatter = true;
        p.label = describeSettings(p);
        all.push_back(std::move(p));
    };
    // A candidate that reads the prefilter of this face, mip count and samples.
    const auto prefiltered = [&](SweepFamily family, int face, int levels, int samples) {
        SweepPoint p;
        p.family = family;
        p.parameter = samples;
        p.bake = base;
        p.bake.prefilter.faceSize = face;
        p.bake.prefilter.levels = levels;
        p.bake.prefilter.samples = samples;
        return p;
    };
    for (bool cube : {false, true})
        for (int face : space.faces)
            for (int levels : space.levels)
                for (bool pdf : {true, false})
                    for (int samples : space.prefilterSamples) {
                        SweepPoint p = prefiltered(SweepFamily::SplitSum, face, levels, samples);
                        p.bake.prefilter.mipFiltering = pdf;
                        if (cube) {
                            p.bake.irradiance = bake::IrradianceMethod::Importance;
                            p.bake.importance.samples = space.cubeSamples;
                            p.sampling.diffuse = DiffuseSource::IrradianceCube;
                        }
                        add(p, std::string("split-sum, ") + (cube ? "irradiance cube" : "SH9"));
                    }
    // The reads that follow the true lobe (docs/accuracy-study.md: the dominant directions and
    // the fitted lobe) on the prefilters the split sum's candidates use, at the default's mip count.
    for (const auto& [method, direction] : {std::pair{ShadingMethod::SplitSum, SpecularDirection::Frostbite},
                                            std::pair{ShadingMethod::SplitSum, SpecularDirection::Filament},
                                            std::pair{ShadingMethod::FittedLobe, SpecularDirection::Reflection}})
        for (int face : space.faces)
            for (int samples : space.prefilterSamples) {
                SweepPoint p = prefiltered(SweepFamily::SpecularLobe, face, space.levels.back(), samples);
                p.sampling.method = method;
                p.sampling.specularDirection = direction;
                add(p, specularReadName(p.sampling) + ", SH9");
            }
    for (bool pdf : {true, false})
        for (int n : space.sampledN) {
            SweepPoint p;
            p.family = SweepFamily::Sampled;
            p.parameter = n;
            p.bake = base;
            p.sampling.method = ShadingMethod::Sampled;
            p.sampling.samples = n;
            p.sampling.pdfMipFiltering = pdf;
            add(p, "sampled");
        }

    out.reasons.push_back("scene: " + facts.surfaces);
    // Dynamic range: one unfiltered sample on the peak weighs peak / (N mean) against the
    // texel's expected value, a firefly once that passes the firefly ratio.
    const double fewestUnfiltered = facts.dynamicRange / kFireflyRatio;
    std::size_t droppedUnfiltered = 0;
    // Roughness: faces beyond what the smoothest lobe resolves.
    std::size_t droppedFaces = 0;
    int largestKept = 0;
    // Metallic: a metal has no diffuse term for the irradiance cube to improve.
    const bool allMetal = facts.minMetallic >= 1.0;
    std::size_t droppedCubes = 0;
    for (SweepPoint& p : all) {
        if (!pdfFiltered(p) && double(samplesOf(p)) < fewestUnfiltered) {
            ++droppedUnfiltered;
            continue;
        }
        if (readsPrefiltered(p) && p.bake.prefilter.faceSize > largestUsefulFace(facts.minRoughness, p.bake.prefilter.levels)) {
            ++droppedFaces;
            continue;
        }
        if (allMetal && readsCube(p)) {
            ++droppedCubes;
            continue;
        }
        if (readsPrefiltered(p)) largestKept = std::max(largestKept, p.bake.prefilter.faceSize);
        out.points.push_back(std::move(p));
    }

    out.reasons.push_back("environment: peak luminance " + formatNumber(facts.dynamicRange, "%.4g") + "x its mean; " +
                          (droppedUnfiltered ? std::to_string(droppedUnfiltered) + " candidates without PDF source-mip filtering and fewer than " +
                                                   formatNumber(std::ceil(fewestUnfiltered), "%.4g") +
                                                   " samples dropped (one sample on the peak would be a firefly, > 3x the reference)"
                                             : std::string("low enough that no unfiltered candidate risks fireflies")));
    if (droppedFaces)
        out.reasons.push_back("roughness: the smoothest surface (" + formatNumber(facts.minRoughness, "%.3g") + ") reads a mip that a face of " +
                              std::to_string(largestKept) + " already resolves; " + std::to_string(droppedFaces) + " candidates with larger faces dropped");
    else if (largestUsefulFace(facts.minRoughness, space.levels.front()) == std::numeric_limits<int>::max())
        out.reasons.push_back("roughness: the scene shows a mirror (roughness " + formatNumber(facts.minRoughness, "%.3g") +
                              "), which reads the prefilter's full-size mip 0: no face size dropped");
    else
        out.reasons.push_back("roughness: the smoothest surface (" + formatNumber(facts.minRoughness, "%.3g") + ") has two texels across its lobe only from a face of " +
                              std::to_string(largestUsefulFace(facts.minRoughness, space.levels.back())) + " (" + std::to_string(space.levels.back()) +
                              " mips) up: no candidate face is larger, none dropped");
    if (droppedCubes) out.reasons.push_back("metallic: every surface is metal, no diffuse term: " + std::to_string(droppedCubes) + " irradiance cube candidates dropped");

    out.referenceWidth = referenceWidthFor(facts, quick);
    return out;
}

AutoChoice chooseAuto(const std::vector<BenchPoint>& measured, double targetSteps, std::vector<std::string> pruningReasons)
{
    AutoChoice choice;
    choice.targetSteps = targetSteps;
    choice.reasons = std::move(pruningReasons);
    if (!measured.empty()) choice.chosen.environment = measured.front().environment;
    std::vector<const BenchPoint*> candidates;
    for (const BenchPoint& p : measured)
        if (p.setting.family != SweepFamily::Preset && p.display.pixels > 0) candidates.push_back(&p);
    choice.candidates = candidates.size();
    if (candidates.empty()) {
        choice.reasons.push_back("no candidate was measured on any surface pixel: nothing to choose from");
        return choice;
    }
    const auto cheaper = [](const BenchPoint* a, const BenchPoint* b) { return a->costMilliseconds < b->costMilliseconds; };
    const auto moreAccurate = [](const BenchPoint* a, const BenchPoint* b) { return a->display.p99Steps < b->display.p99Steps; };
    std::vector<const BenchPoint*> meeting;
    for (const BenchPoint* p : candidates)
        if (p->display.p99Steps <= targetSteps) meeting.push_back(p);
    choice.meeting = meeting.size();
    choice.found = true;
    choice.meetsTarget = !meeting.empty();
    const BenchPoint* best = *std::min_element(candidates.begin(), candidates.end(), moreAccurate);
    const BenchPoint* cheapest = *std::min_element(candidates.begin(), candidates.end(), cheaper);
    const std::string target = formatNumber(targetSteps, "%.3g") + " 8-bit steps";
    if (choice.meetsTarget) {
        const BenchPoint* chosen = *std::min_element(meeting.begin(), meeting.end(), cheaper);
        choice.chosen = *chosen;
        choice.reasons.push_back("chosen: " + std::to_string(meeting.size()) + " of " + std::to_string(candidates.size()) +
                                 " candidates have a 99th-percentile display error within " + target + "; the cheapest is " + pointSummary(*chosen));
        if (cheapest != chosen) choice.reasons.push_back("cheaper, but over the target: " + pointSummary(*cheapest));
        if (best != chosen)
            choice.reasons.push_back("most accurate: " + pointSummary(*best) + ", " + formatNumber(best->costMilliseconds / std::max(chosen->costMilliseconds, 1e-9), "%.2g") +
                                     "x the cost");
    } else {
        choice.chosen = *best;
        choice.reasons.push_back("target out of reach: no candidate is within " + target + "; the most accurate reaches " + formatNumber(best->display.p99Steps, "%.3g") +
                                 " steps, " + formatNumber(best->display.p99Steps / targetSteps, "%.2g") + "x the target: chosen " + pointSummary(*best));
    }
    return choice;
}

void markChosen(std::vector<BenchPoint>& points, const AutoChoice& choice)
{
    for (BenchPoint& p : points)
        p.chosen = choice.found && p.environment == choice.chosen.environment && p.setting.label == choice.chosen.setting.label;
}

std::string referenceReason(const SceneFacts& facts, const ReferenceSummary& reference)
{
    const std::string map = "the reference over a " + std::to_string(reference.environmentWidth) + "-wide map";
    const std::string floor = formatNumber(reference.minResolvedRoughness, "%.3g");
    if (reference.minResolvedRoughness > facts.maxRoughness) return "measured: nothing: " + map + " resolves roughness >= " + floor + " only, and no surface is that rough";
    if (reference.minResolvedRoughness > facts.minRoughness)
        return "measured: surfaces with roughness >= " + floor + " only: " + map + " resolves no smoother ones, so the choice is not judged on them";
    return "measured: every surface (" + map + " resolves roughness >= " + floor + ")";
}

AutoChoice chooseAuto(const BenchReport& report, double targetSteps, const AutoCandidates& candidates)
{
    std::vector<std::string> reasons = candidates.reasons;
    for (const ReferenceSummary& reference : report.references) reasons.push_back(referenceReason(candidates.facts, reference));
    return chooseAuto(report.points, targetSteps, std::move(reasons));
}

std::vector<SweepPoint> presetPoints(bool quick)
{
    const bake::BakeSettings base = benchBaseBake(quick);
    std::vector<SweepPoint> points;
    for (const bool tutorial : {true, false}) {
        SweepPoint p;
        p.family = SweepFamily::Preset;
        p.bake = tutorial ? bake::tutorialPreset() : bake::defaultPreset();
        p.bake.lut = base.lut; // shared, like every point's: it depends on no environment and is not in the cost
        if (quick) {
            p.bake.cube.maxFaceSize = base.cube.maxFaceSize;
            if (p.bake.cube.faceSize > 0) p.bake.cube.faceSize = std::min(p.bake.cube.faceSize, base.cube.maxFaceSize);
            p.bake.prefilter.faceSize = std::min(p.bake.prefilter.faceSize, 64);
            p.bake.riemann.faceSize = std::min(p.bake.riemann.faceSize, 16);
        }
        // Each preset as the lab shades it: the tutorial reads its Riemann irradiance cube, the
        // default its moment cube.
        p.sampling.diffuse = DiffuseSource::IrradianceCube;
        p.series = "presets";
        p.scatter = true;
        p.mark = tutorial ? "tutorial" : "default";
        p.label = std::string("preset ") + (tutorial ? "tutorial" : "default") + (quick ? " (quick caps)" : "") + ": " + describeSettings(p);
        points.push_back(std::move(p));
    }
    return points;
}

bake::BakeSettings appliedBakeSettings(const AutoChoice& choice, bake::BakeSettings current)
{
    const SweepPoint& p = choice.chosen.setting;
    current.preset = "auto";
    if (readsPrefiltered(p)) current.prefilter = p.bake.prefilter;
    // A cube the frame does not read is bake time for nothing.
    // Its candidates measure the importance-sampled cube; none when the frame reads SH9 (a
    // cube the frame does not read is bake time for nothing).
    current.irradiance = readsCube(p) ? bake::IrradianceMethod::Importance : bake::IrradianceMethod::None;
    current.importance = readsCube(p) ? p.bake.importance : current.importance;
    return current;
}

SamplingSettings appliedSampling(const AutoChoice& choice, SamplingSettings current)
{
    const SamplingSettings& chosen = choice.chosen.setting.sampling;
    current.method = chosen.method;
    current.samples = chosen.samples;
    current.pdfMipFiltering = chosen.pdfMipFiltering;
    current.diffuse = chosen.diffuse;
    current.specularDirection = chosen.specularDirection;
    return current;
}

std::string autoMarkdown(const BenchReport& report, const std::vector<AutoChoice>& choices)
{
    std::ostringstream out;
    out << "## Auto quality\n\nThe cheapest candidate whose 99th-percentile display error (after exposure and "
        << enumName(report.options.frame.toneMap.op) << " tone mapping, in 8-bit steps) is within the target, beside the fixed presets "
        << "measured the same way (cost as a multiple of the auto choice's).\n\n";
    for (const AutoChoice& c : choices) {
        const std::string environment = c.chosen.environment;
        out << "**" << environment << "**: target " << formatNumber(c.targetSteps, "%.3g") << " steps, "
            << (c.meetsTarget ? "met" : c.found ? "out of reach" : "nothing measured") << "\n\n";
        if (c.found) {
            out << "| setting | cost ms | cost / auto | display p99 (steps) | display RMS (steps) | relative RMSE |\n|---|---|---|---|---|---|\n";
            const double autoCost = std::max(c.chosen.costMilliseconds, 1e-9);
            const auto row = [&](const std::string& name, const BenchPoint& p) {
                out << "| " << name << " | " << formatNumber(p.costMilliseconds, "%.1f") << " | " << formatNumber(p.costMilliseconds / autoCost, "%.2f") << " | "
                    << formatNumber(p.display.p99Steps, "%.3g") << " | " << formatNumber(p.display.rmsSteps, "%.3g") << " | " << formatNumber(p.error.relativeRmse, "%.3g") << " |\n";
            };
            row("**auto**: " + describeSettings(c.chosen.setting), c.chosen);
            for (const BenchPoint& p : report.points)
                if (p.environment == environment && p.setting.family == SweepFamily::Preset) row(p.setting.label, p);
            out << "\n";
        }
        for (const std::string& reason : c.reasons) out << "- " << reason << "\n";
        out << "\n";
    }
    return out.str();
}

std::string benchJsonTextWithAuto(const BenchReport& report, const std::vector<AutoChoice>& choices)
{
    nlohmann::ordered_json j = nlohmann::ordered_json::parse(benchJsonText(report));
    j["auto"] = nlohmann::ordered_json::array();
    for (const AutoChoice& c : choices) {
        // Nothing chosen has no numbers: zeros would read as a free and exact choice.
        const auto chosen = [&](double value) { return c.found ? nlohmann::ordered_json(value) : nlohmann::ordered_json(nullptr); };
        j["auto"].push_back({{"environment", c.chosen.environment},
                             {"target_p99_steps", c.targetSteps},
                             {"found", c.found},
                             {"meets_target", c.meetsTarget},
                             {"candidates_measured", c.candidates},
                             {"candidates_meeting", c.meeting},
                             {"chosen", c.found ? c.chosen.setting.label : ""},
                             {"cost_ms", chosen(c.chosen.costMilliseconds)},
                             {"display_p99_steps", chosen(c.chosen.display.p99Steps)},
                             {"display_rms_steps", chosen(c.chosen.display.rmsSteps)},
                             {"relative_rmse", chosen(c.chosen.error.relativeRmse)},
                             {"reasons", c.reasons}});
    }
    return j.dump(2);
}

} // namespace iblab::bench
