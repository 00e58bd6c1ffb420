#pragma once
// The speed-against-accuracy sweep behind `iblab bench` and the GUI's Study panel: for each
// environment, every sweep point (a method and its settings) is baked, rendered and timed,
// and its frame is compared with the reference renderer's full integral of the same scene
// and camera. One reference per environment serves every point: it depends on the scene,
// the camera and the shading model, not on the estimator (Renderer::referenceKeyFor).
//
// A job of small steps like BakeJob, so that the GUI runs a slice per frame and the CLI
// runs it to the end:
//
//   BenchJob job(renderer, options);
//   while (job.runFor(std::chrono::milliseconds(30))) drawChart(job.report());   // GUI
//   BenchReport report = BenchJob(renderer, options).runToCompletion();           // CLI
//
// The job runs on a lab::Harness (harness.hpp: the LUTs shared between bakes by its rule) and
// replaces the renderer's environment, bake and model: give it a renderer of its own when
// another one shows something else. Needs the context that was current when the
// job was made to be current at every call. Public header: no GL.
#include <array>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "bake/bake_settings.hpp"
#include "io/environment.hpp"
#include "ibl/error_metrics.hpp"
#include "frame/renderer.hpp"
#include "frame/settings.hpp"
#include "lab/harness.hpp"

namespace iblab::bench {

using lab::DisplayError;

struct BenchEnvironment {
    std::string name; // short key for tables, unique in a run: "courtyard", "builtin-sun-1e3"
    std::string spec; // a file or builtin spec
    // Already in memory (the GUI's current map): skips loading the spec again.
    std::shared_ptr<const Environment> loaded;
};

// What a sweep point varies: the split sum's prefilter, the sampled method's N, the diffuse
// source, (auto quality) a fixed preset measured beside the candidates, or where and how
// wide the prefiltered cube is read (R, the dominant directions, the fitted lobe: specular-lobe).
enum class SweepFamily { SplitSum, Sampled, Diffuse, Preset, SpecularLobe };
// The reports' spelling, in the enum's order.
inline constexpr std::array<std::string_view, 5> kSweepFamilyNames{"split-sum", "sampled", "diffuse", "preset", "specular-lobe"};
inline std::string_view sweepFamilyName(SweepFamily family) { return kSweepFamilyNames[std::size_t(family)]; }

// One method and its settings. `series` names the curve it belongs to on the chart (every
// setting but the swept one), `parameter` its place along that curve.
struct SweepPoint {
    SweepFamily family = SweepFamily::SplitSum;
    std::string series; // "split-sum 64 PDF", "sampled no mip filter", "Riemann cube"
    std::string label;  // the whole setting in words, for tooltips and tables
    double parameter = 0.0;
    // The split sum with windowed SH9 diffuse unless the point says otherwise: a specular point's error must not
    // depend on which irradiance cube its bake happens to have.
    SamplingSettings sampling = [] {
        SamplingSettings s;
        s.method = ShadingMethod::SplitSum; // the families that shade otherwise say so
        s.diffuse = DiffuseSource::Sh9;
        return s;
    }();
    bake::BakeSettings bake;
    bool scatter = false; // its series varies more than one setting: no curve joins its points
    std::string mark;     // drawn beside the point on the chart (a preset's name)
};

struct BenchOptions {
    bool quick = false;
    std::vector<BenchEnvironment> environments;
    // Scene, material and view of every frame (environment and sampling are the sweep's).
    FrameSettings frame;
    bool frameCamera = true; // fit the camera to the scene as `iblab render` does
    int width = 128;
    int height = 128;
    int repeats = 5;         // timed frames per point; the median is reported
    // The width of the map the reference sums over. 0: per environment, the narrowest that
    // resolves the scene's smoothest surface within the run's cap, referenceWidthFor(sceneFacts(
    // frame, map), quick) (auto_quality.hpp). Given: used as it is, uncapped.
    int referenceWidth = 0;
    // cost = bake + frames x frame: the time to this many frames after the environment changed.
    int costFrames = 1;
    std::vector<SweepPoint> points;
};

// The full sweep (split-sum over prefilter samples x PDF filtering x face sizes, sampled
// N = 1..256 with and without mip filtering, the diffuse sources, the specular reads) or the
// quick one (a few points of each family on small bakes, for tests and the Study panel).
std::vector<SweepPoint> sweepPoints(bool quick);
// How a point reads the prefiltered cube, in words: "split-sum" (at R), "split-sum, Frostbite
// direction", "fitted lobe"; empty for a method that does not read it.
std::string specularReadName(const SamplingSettings& sampling);
// The bake every sweep point starts from: the default preset without the irradiance cubes,
// only the default geometry term's LUT, and (quick) small enough for tens of milliseconds.
bake::BakeSettings benchBaseBake(bool quick);
// Defaults of `iblab bench`: the grid, the bundled maps and three stress environments, the
// reference width left to the scene (referenceWidth 0).
BenchOptions defaultBenchOptions(bool quick, const std::string& assetDirectory);

// The stress environments the default run adds (StressEnvironment::inBench), at `width`.
std::vector<BenchEnvironment> builtinBenchEnvironments(int width);

struct BenchPoint {
    std::string environment;
    SweepPoint setting;
    double bakeMilliseconds = 0.0;  // the phases the frame reads (see bakePhasesRead)
    double frameMilliseconds = 0.0; // median of the repeats, steady clock around glFinish
    double costMilliseconds = 0.0;  // bake + costFrames x frame
    // NaN where the reference resolved no surface pixel (measured() is false): not 0, which
    // would read as exact. The pixel counts are 0 then (lab::Harness::compareWithReference).
    ErrorMetrics error;             // linear HDR, resolved surface pixels (lab::measureResolvedError)
    DisplayError display;           // the same pixels after tone mapping (lab::measureResolvedDisplayError)
    bool dominated = false;
    bool chosen = false;            // the auto quality mode's pick (auto_quality.hpp)
};

struct ReferenceSummary {
    std::string environment;
    int environmentWidth = 0;
    double minResolvedRoughness = 0.0;
    double milliseconds = 0.0;
    // Why it resolves none of the frame's surface pixels, so that no point of the environment
    // has an error: the roughness it resolves, the roughest surface pixel, and the width that
    // would resolve it. Empty when it resolves some.
    std::string unmeasured = {};
};

struct BenchReport {
    std::string renderer; // GL renderer string
    BenchOptions options; // the points and environments it ran (preloaded maps dropped)
    std::vector<ReferenceSummary> references;
    std::vector<BenchPoint> points;
    double seconds = 0.0;
};

// False when the point has no error (NaN): its environment's reference resolved no surface
// pixel. It still has its cost.
bool measured(const BenchPoint& point);
// One line per environment whose points could not be measured, "courtyard: not measured: "
// and ReferenceSummary::unmeasured; there as soon as its reference is done, before its points.
std::vector<std::string> unmeasuredEnvironments(const BenchReport& report);

// The bake phases a frame of this setting reads: the upload and environment cube always,
// then the prefilter (split-sum), SH9 or the irradiance cube that was baked. Not the
// shaders (compiled once per process) nor the LUTs (no environment in them; cached).
std::vector<bake::BakePhase> bakePhasesRead(const SweepPoint& point);

// A point is dominated when another point of the same environment is both cheaper and
// more accurate (strictly: lower cost and lower relative RMSE). A point without an error
// (NaN) is neither dominated nor dominates.
void markDominated(std::vector<BenchPoint>& points);
// The same by another error (the auto quality chart's display p99).
void markDominated(std::vector<BenchPoint>& points, double (*error)(const BenchPoint&));

class BenchJob {
public:
    // Throws iblab::Error for options no sweep can use (no environment, no point, two
    // environments of one name).
    BenchJob(Renderer& renderer, BenchOptions options);
    ~BenchJob();
    BenchJob(const BenchJob&) = delete;
    BenchJob& operator=(const BenchJob&) = delete;

    // Runs the next step (loading an environment, one bake step, one slice of the
    // reference, or rendering and measuring one point); true while steps remain.
    bool step();
    bool runFor(std::chrono::steady_clock::duration budget);
    BenchReport runToCompletion();

    bool done() const;
    float progress() const; // 0..1, by points measured and bake progress
    std::string currentActivity() const;
    // The environment the next step works on; null when done.
    const BenchEnvironment* currentEnvironment() const;
    // The points measured so far, dominance marked among them.
    const BenchReport& report() const { return report_; }

private:
    struct State;
    std::unique_ptr<State> state_;
    BenchReport report_;
};

// CSV (one row per point, header first) and JSON (options, references, points). A point
// without an error has empty error fields in the CSV and nulls in the JSON (docs/bench.md).
std::string benchCsvText(const BenchReport& report);
std::string benchJsonText(const BenchReport& report);
// The CSV's column names, in order.
const std::vector<std::string>& benchCsvColumns();
// Markdown: a summary table (per environment, each family's lowest error and its cost), then
// per environment the points no other point dominates. Cost as a ratio to the environment's
// cheapest setting: ratios carry over to other machines, milliseconds do not. An environment
// that could not be measured has n/a in the table and its reason below it.
std::string benchMarkdown(const BenchReport& report);

} // namespace iblab::bench
