#pragma once
// The auto quality mode: the cheapest settings whose frame stays within a target error of
// the reference, as the viewer sees it (after tone mapping, in 8-bit steps).
//
// It measures rather than predicts: the candidates (prefilter face size, mip count and
// samples per mip, PDF source-mip filtering, where the prefiltered cube is read, runtime N for
// the sampled method, SH9 or the irradiance cube for diffuse) run as a bench sweep on the current environment and scene, so
// the scene's roughness range and the environment's dynamic range are what the measurement
// sees. Before measuring, both facts prune candidates that cannot be right for this scene:
//
//   SceneFacts facts = sceneFacts(frame, environment.image);
//   AutoCandidates c = autoCandidates(quick, facts);             // points + reasons
//   options.points = c.points; options.referenceWidth = c.referenceWidth;
//   ... run the BenchJob ...
//   AutoChoice choice = chooseAuto(report.points, target, c.reasons);
//
// No GL here: the selection is plain data, tested on hand-made points.
#include <string>
#include <vector>

#include "lab/bench_sweep.hpp"
#include "ibl/image.hpp"
#include "frame/settings.hpp"

namespace iblab::bench {

// 99% of the pixels within 20 of the 255 display levels (about 8%) of the reference after
// tone mapping: a difference seen side by side, not at a glance. A scene can meet it: the
// README's `bench --auto --auto-target 20` run meets it on both bundled maps (sunset with the
// fitted lobe at face 64, courtyard only with the sampled method at N = 256), where the
// former default of 1 step was out of reach for every candidate on every map tried.
inline constexpr double kDefaultAutoTargetSteps = 20.0;

// What the scene and environment ask of the settings.
struct SceneFacts {
    bool hasSurfaces = true;
    double minRoughness = 0.0, maxRoughness = 1.0; // perceptual
    double minMetallic = 0.0, maxMetallic = 1.0;
    std::string surfaces;      // where the ranges come from, in words ("the 7x7 grid: roughness 0..1, metallic 0..1")
    double dynamicRange = 1.0; // the environment's peak luminance over its solid-angle mean
    int environmentWidth = 0;  // texels; the reference sums over no more than the map has (0: unknown)
};

// Roughness and metallic ranges from the scene settings: the grid and the sweep span 0..1,
// the sphere and the counting strip show the material sliders, a model shows the sliders
// when they override it and is taken to span 0..1 otherwise (its own materials are not read).
SceneFacts sceneFacts(const FrameSettings& frame, const ImageRGB32F& environment);
// Peak over mean luminance (Rec. 709 weights), the mean weighted by each equirect row's solid
// angle; 1 for an empty or black map.
double environmentDynamicRange(const ImageRGB32F& environment);

// The widest reference a run affords. The reference costs texels x pixels and is a run's
// largest single step: the quick run (the Study panel, the tests) stops at 128, which keeps it
// in seconds on llvmpipe and still resolves roughness >= 0.27 (the material sliders' default
// sphere is 0.3); the full run at 512 (>= 0.14). A width given by hand is not capped.
int maxReferenceWidth(bool quick);
// The reference width for a scene whose smoothest surface has this roughness: from 64 (or
// `widest`, if narrower), doubled while referenceMinResolvedRoughness says it does not resolve
// that surface and the double stays within `widest`. So `widest` when no width within it
// resolves the surface (none resolves a mirror).
int referenceWidthFor(double smoothestRoughness, int widest);
// The same within the run's cap and the map's width: the width of the reference the auto
// quality mode, `iblab bench` and the Study panel's sweep measure against when none is given
// (BenchOptions::referenceWidth 0). Call it with sceneFacts(frame, map) to know it beforehand.
int referenceWidthFor(const SceneFacts& facts, bool quick);

struct AutoCandidates {
    SceneFacts facts;                 // what they were pruned by
    std::vector<SweepPoint> points;   // family SplitSum, SpecularLobe or Sampled; each a whole configuration
    int referenceWidth = 0;           // referenceWidthFor(facts, quick)
    std::vector<std::string> reasons; // what was pruned and why
};

// The candidate space (quick: small bakes for the GUI and tests) pruned by the facts:
//  - an unfiltered candidate (no PDF source-mip filtering) is dropped when one sample on the
//    environment's peak would make a firefly: dynamicRange > 3 x its samples (3x the
//    reference is the firefly threshold, common/error_metrics.glsl);
//  - prefilter faces larger than the smoothest surface's lobe needs are dropped: the mip that
//    roughness reads must have two texels across the lobe's half-maximum width, no more;
//  - the irradiance cube is dropped when every surface is metal (no diffuse term to improve).
AutoCandidates autoCandidates(bool quick, const SceneFacts& facts);

struct AutoChoice {
    bool found = false;       // a candidate had measured pixels
    bool meetsTarget = false;
    double targetSteps = kDefaultAutoTargetSteps;
    BenchPoint chosen;        // its settings (setting.bake, setting.sampling), cost and error
    std::size_t candidates = 0, meeting = 0;
    std::vector<std::string> reasons; // pruning first, then the choice
};

// The cheapest measured candidate whose display p99 is at most targetSteps; when none is,
// the one with the lowest p99, with a reason saying by how much the target is out of reach.
// Points of family Preset are not candidates. pruningReasons lead the returned reasons.
AutoChoice chooseAuto(const std::vector<BenchPoint>& measured, double targetSteps, std::vector<std::string> pruningReasons);
// The same on a bench run of the candidates, its reasons saying which surfaces the run's
// reference resolved (and so which the choice was judged on).
AutoChoice chooseAuto(const BenchReport& report, double targetSteps, const AutoCandidates& candidates);
// Which of the scene's surfaces a reference of this summary resolves, in words.
std::string referenceReason(const SceneFacts& facts, const ReferenceSummary& reference);

// Sets BenchPoint::chosen on the choice's point (same environment and setting) and clears it elsewhere.
void markChosen(std::vector<BenchPoint>& points, const AutoChoice& choice);

// The fixed presets measured beside the auto choice, family Preset: the tutorial's and the
// default bake with split-sum shading (the tutorial reading its Riemann irradiance cube). The
// quick run caps them like its candidates (environment cube 64, prefilter 64, cube faces 16);
// every point shares the bench's LUT.
std::vector<SweepPoint> presetPoints(bool quick);

// The settings the user's session should take: the chosen prefilter, irradiance cube and
// sampling on top of what the session has (so that its cube size and LUT stay its own).
bake::BakeSettings appliedBakeSettings(const AutoChoice& choice, bake::BakeSettings current);
SamplingSettings appliedSampling(const AutoChoice& choice, SamplingSettings current);

// A short description of the chosen settings ("split-sum, prefilter face 32, 5 mips, 16 samples, PDF mips, SH9").
std::string describeSettings(const SweepPoint& point);

// bench.md's and bench.json's auto section: per environment the choice, its reasons and the presets beside it.
std::string autoMarkdown(const BenchReport& report, const std::vector<AutoChoice>& choices);
std::string benchJsonTextWithAuto(const BenchReport& report, const std::vector<AutoChoice>& choices);

} // namespace iblab::bench
