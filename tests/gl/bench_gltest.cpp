// The bench sweep (renderer/bench) on its quick run (a 64-wide sky, 48x48 grid, every
// family): errors are real measurements against the reference, more prefilter samples do
// not make a smooth environment worse, more runtime samples make it better, the error
// measure is zero for the reference itself and exact for a known bias. On a sphere: the
// reference is widened until it resolves it, and one it cannot resolve is reported as not
// measured, never as exact. Then, on hand-made points: dominance follows its definition, and
// the CSV and JSON say what the header promises. ctest runs every test in a process of its
// own, so the quick grid run (a few seconds) is made by one test only.
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "lab/bench_sweep.hpp"
#include "io/error.hpp"
#include "gl_test_fixture.hpp"
#include "frame/renderer.hpp"

namespace iblab {
namespace {

using testing::GlTest;
using namespace bench;
using namespace lab;

class Bench : public GlTest {};

// Splits one CSV line, honouring quoted fields with commas and doubled quotes.
std::vector<std::string> csvFields(const std::string& line)
{
    std::vector<std::string> fields(1);
    bool quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') fields.back() += '"', ++i;
        else if (c == '"') quoted = !quoted;
        else if (c == ',' && !quoted) fields.emplace_back();
        else fields.back() += c;
    }
    return fields;
}

TEST_F(Bench, QuickSweepMeasuresEveryPointAgainstTheReference)
{
    Renderer renderer(shaderDirectory());
    const BenchReport r = BenchJob(renderer, defaultBenchOptions(/*quick=*/true, IBLAB_ASSET_DIR)).runToCompletion();

    // Every point, with real numbers.
    ASSERT_EQ(r.points.size(), r.options.points.size() * r.options.environments.size());
    ASSERT_EQ(r.references.size(), r.options.environments.size());
    for (const BenchPoint& p : r.points) {
        SCOPED_TRACE(p.setting.label);
        EXPECT_TRUE(std::isfinite(p.error.relativeRmse));
        // No estimator in the sweep is exact: an error of 0 would mean the frame was the reference.
        EXPECT_GT(p.error.relativeRmse, 0.0);
        EXPECT_GT(p.error.pixels, 100u);
        EXPECT_GT(p.frameMilliseconds, 0.0);
        EXPECT_GT(p.bakeMilliseconds, 0.0);
        EXPECT_DOUBLE_EQ(p.costMilliseconds, p.bakeMilliseconds + r.options.costFrames * p.frameMilliseconds);
    }
    std::vector<BenchPoint> remarked = r.points;
    markDominated(remarked);
    for (std::size_t i = 0; i < remarked.size(); ++i) EXPECT_EQ(remarked[i].dominated, r.points[i].dominated) << i;
    EXPECT_TRUE(std::any_of(remarked.begin(), remarked.end(), [](const BenchPoint& p) { return !p.dominated; }));

    // The sky is smooth: past 4 samples the prefilter converges, and what is left is the
    // split sum's own bias. More samples may move the error a little either way around that
    // bias (5% of it), never by more.
    std::map<std::string, std::vector<const BenchPoint*>> bySeries;
    for (const BenchPoint& p : r.points)
        if (p.setting.family == SweepFamily::SplitSum) bySeries[p.setting.series].push_back(&p);
    ASSERT_GE(bySeries.size(), 2u);
    for (auto& [series, points] : bySeries) {
        std::sort(points.begin(), points.end(), [](auto* a, auto* b) { return a->setting.parameter < b->setting.parameter; });
        ASSERT_GE(points.size(), 3u) << series;
        for (std::size_t i = 1; i < points.size(); ++i)
            EXPECT_LE(points[i]->error.relativeRmse, points[i - 1]->error.relativeRmse * 1.05) << points[i]->setting.label;
    }

    // N = 16 against N = 1, same mip filtering: the estimator's variance falls as 1/N.
    std::map<std::string, std::map<int, double>> errors;
    for (const BenchPoint& p : r.points)
        if (p.setting.family == SweepFamily::Sampled) errors[p.setting.series][p.setting.sampling.samples] = p.error.relativeRmse;
    ASSERT_EQ(errors.size(), 2u);
    for (auto& [series, byN] : errors) {
        ASSERT_TRUE(byN.count(1) && byN.count(16)) << series;
        EXPECT_LT(byN[16], byN[1]) << series;
    }

    // The error measure, on the reference the renderer still holds: 0 against itself, 0.1
    // everywhere for a frame 10% too bright, and the roughness floor leaves out the grid's
    // smooth columns but not everything.
    const FrameReadback reference = renderer.readReferenceFrame();
    const FrameReadback normal = renderer.readReferenceLayer(ReferenceLayer::Normal);
    const FrameReadback view = renderer.readReferenceLayer(ReferenceLayer::View);
    ASSERT_FALSE(reference.rgba.empty());
    const ErrorMetrics self = measureResolvedError(reference, reference, normal, view, 0.0);
    EXPECT_GT(self.pixels, 100u);
    EXPECT_EQ(self.relativeRmse, 0.0);
    EXPECT_EQ(self.maxRelative, 0.0);
    FrameReadback brighter = reference;
    for (std::size_t i = 0; i < brighter.rgba.size(); ++i)
        if (i % 4 != 3) brighter.rgba[i] *= 1.1f; // radiance only: alpha is coverage
    const ErrorMetrics biased = measureResolvedError(brighter, reference, normal, view, 0.0);
    EXPECT_NEAR(biased.relativeRmse, 0.1, 1e-4);
    EXPECT_NEAR(biased.meanRelative, 0.1, 1e-4);
    const ErrorMetrics rough = measureResolvedError(reference, reference, normal, view, r.references.front().minResolvedRoughness);
    // The sweep measured over those of these pixels that its (MSAA) frames cover wholly.
    // Every point draws the same grid from the same camera, so the last point's frame, still
    // in the renderer, covers the same pixels as the first's.
    const ErrorMetrics swept = measureResolvedError(renderer.readHdrFrame(), reference, normal, view, r.references.front().minResolvedRoughness);
    EXPECT_EQ(swept.pixels, r.points.front().error.pixels);
    EXPECT_LE(swept.pixels, rough.pixels);

    // In display space: 0 steps against itself; a frame 10% too bright is off by some steps
    // where the tone curve is steep, never more than 10% of the 255 steps of the whole range,
    // and what the sweep recorded for its points is measured over the same pixels.
    const ToneMapSettings toneMap = r.options.frame.toneMap;
    const DisplayError displaySelf = measureResolvedDisplayError(reference, reference, normal, view, 0.0, toneMap);
    EXPECT_EQ(displaySelf.pixels, self.pixels);
    EXPECT_EQ(displaySelf.maxSteps, 0.0);
    const DisplayError displayBiased = measureResolvedDisplayError(brighter, reference, normal, view, 0.0, toneMap);
    EXPECT_GT(displayBiased.p99Steps, 1.0);
    EXPECT_LE(displayBiased.maxSteps, 0.1 * 255.0);
    EXPECT_LE(displayBiased.rmsSteps, displayBiased.maxSteps);
    EXPECT_EQ(r.points.front().display.pixels, swept.pixels);
    for (const BenchPoint& p : r.points) EXPECT_GT(p.display.rmsSteps, 0.0) << p.setting.label;
    EXPECT_LT(rough.pixels, self.pixels);
    EXPECT_GT(rough.pixels, self.pixels / 4);
}

// The Study panel's quick sweep on its default scene, a copper sphere of roughness 0.3, on a
// map wide enough: the reference is widened until it resolves the sphere (128, where the quick
// grid's sky gets 64), so every point is measured on the sphere's pixels, with an error.
TEST_F(Bench, QuickSweepOnASmoothSphereMeasuresEveryPoint)
{
    BenchOptions options = defaultBenchOptions(/*quick=*/true, IBLAB_ASSET_DIR);
    options.environments = {{"sky", "builtin:sky?width=256", nullptr}};
    options.frame.scene.kind = SceneKind::Sphere;
    options.frame.material.roughness = 0.3f;
    Renderer renderer(shaderDirectory());
    const BenchReport r = BenchJob(renderer, options).runToCompletion();

    ASSERT_EQ(r.references.size(), 1u);
    EXPECT_EQ(r.references.front().environmentWidth, 128);
    EXPECT_LE(r.references.front().minResolvedRoughness, 0.3);
    ASSERT_EQ(r.points.size(), options.points.size());
    for (const BenchPoint& p : r.points) {
        SCOPED_TRACE(p.setting.label);
        EXPECT_GT(p.error.pixels, 100u);
        EXPECT_TRUE(std::isfinite(p.error.relativeRmse));
        EXPECT_GT(p.error.relativeRmse, 0.0);
        EXPECT_EQ(p.display.pixels, p.error.pixels);
        EXPECT_TRUE(std::isfinite(p.display.p99Steps));
    }
}

// A mirror sphere against a 64-wide reference given by hand (used as given, not widened):
// no pixel can be measured. Every point keeps its cost but has no error (NaN, never the 0
// that reads as exact); the report says why as soon as the reference is done; the CSV, the
// JSON and the markdown show the error as missing.
TEST_F(Bench, AnUnmeasurableSceneHasNoErrorAndSaysWhy)
{
    BenchOptions options = defaultBenchOptions(/*quick=*/true, IBLAB_ASSET_DIR);
    options.environments = {{"sky", "builtin:sky?width=256", nullptr}};
    options.frame.scene.kind = SceneKind::Sphere;
    options.frame.material.roughness = 0.0f;
    options.referenceWidth = 64;
    options.points = {options.points.front(), options.points.back()};
    options.repeats = 1;
    Renderer renderer(shaderDirectory());
    BenchJob job(renderer, options);
    while (job.report().references.empty() && job.step()) {
    }
    ASSERT_EQ(job.report().references.size(), 1u);
    const std::vector<std::string> why = unmeasuredEnvironments(job.report());
    ASSERT_EQ(why.size(), 1u) << "before any point is measured";
    EXPECT_TRUE(job.report().points.empty());
    EXPECT_EQ(why.front().rfind("sky: not measured: no surface pixel has roughness >= 0.384, the smallest the 64-wide reference resolves; the roughest is 0 ", 0), 0u)
        << why.front();
    EXPECT_NE(why.front().find("no reference over the 256-wide map resolves"), std::string::npos) << why.front();

    const BenchReport r = job.runToCompletion();
    EXPECT_EQ(r.references.front().environmentWidth, 64);
    ASSERT_EQ(r.points.size(), 2u);
    for (const BenchPoint& p : r.points) {
        SCOPED_TRACE(p.setting.label);
        EXPECT_FALSE(measured(p));
        EXPECT_EQ(p.error.pixels, 0u);
        EXPECT_TRUE(std::isnan(p.error.relativeRmse));
        EXPECT_TRUE(std::isnan(p.error.p99Relative));
        EXPECT_TRUE(std::isnan(p.display.p99Steps));
        EXPECT_GT(p.costMilliseconds, 0.0);
        EXPECT_FALSE(p.dominated);
    }

    std::istringstream csv(benchCsvText(r));
    std::string line;
    ASSERT_TRUE(std::getline(csv, line));
    const auto& columns = benchCsvColumns();
    const auto column = [&](const std::string& name) { return std::size_t(std::find(columns.begin(), columns.end(), name) - columns.begin()); };
    while (std::getline(csv, line)) {
        const std::vector<std::string> fields = csvFields(line);
        ASSERT_EQ(fields.size(), columns.size()) << line;
        for (const char* name : {"relative_rmse", "p99_relative", "fireflies", "display_p99_steps"}) EXPECT_EQ(fields[column(name)], "") << name;
        EXPECT_EQ(fields[column("pixels")], "0");
    }
    const nlohmann::json j = nlohmann::json::parse(benchJsonText(r));
    for (const nlohmann::json& p : j.at("points")) {
        EXPECT_TRUE(p.at("error").at("relative_rmse").is_null());
        EXPECT_TRUE(p.at("display_error").at("p99_steps").is_null());
    }
    EXPECT_EQ(j.at("references").at(0).at("not_measured"), r.references.front().unmeasured);
    const std::string markdown = benchMarkdown(r);
    EXPECT_NE(markdown.find("| sky | not measured | n/a | n/a | n/a |"), std::string::npos) << markdown;
    EXPECT_NE(markdown.find("**sky**: not measured: " + r.references.front().unmeasured), std::string::npos) << markdown;
}

TEST_F(Bench, DominanceIsCheaperAndMoreAccurateWithinOneEnvironment)
{
    const auto point = [](std::string env, double cost, double error) {
        BenchPoint p;
        p.environment = std::move(env);
        p.costMilliseconds = cost;
        p.error.relativeRmse = error;
        return p;
    };
    std::vector<BenchPoint> points{
        point("a", 1.0, 1.0),  // front: cheapest of those at least this accurate
        point("a", 2.0, 0.5),  // front
        point("a", 3.0, 0.6),  // dominated by (2, 0.5)
        point("a", 0.5, 2.0),  // front: the cheapest
        point("a", 1.0, 1.5),  // same cost as (1, 1): not strictly cheaper, so not dominated by it
        point("a", 4.0, 0.5),  // same error as (2, 0.5): not strictly better
        point("b", 10.0, 10.0) // another environment: (1, 1) of "a" does not count
    };
    markDominated(points);
    const std::vector<bool> expected{false, false, true, false, false, false, false};
    for (std::size_t i = 0; i < points.size(); ++i) EXPECT_EQ(points[i].dominated, expected[i]) << i;
}

TEST_F(Bench, EnvironmentsAreToldApartByName)
{
    // The full default run: the bundled studio.exr and the builtin studio must not share a
    // name, or their points would be compared with each other.
    const BenchOptions full = defaultBenchOptions(/*quick=*/false, IBLAB_ASSET_DIR);
    ASSERT_GT(full.environments.size(), 3u);
    std::set<std::string> names;
    for (const BenchEnvironment& e : full.environments) EXPECT_TRUE(names.insert(e.name).second) << e.name;

    BenchOptions twice = defaultBenchOptions(/*quick=*/true, IBLAB_ASSET_DIR);
    twice.environments.push_back(twice.environments.front());
    Renderer renderer(shaderDirectory());
    EXPECT_THROW(BenchJob(renderer, twice), Error);
}

TEST_F(Bench, CsvAndJsonParseBackWithTheExpectedColumns)
{
    // Every quick sweep point (labels with commas, every family's columns) with made-up numbers.
    BenchReport r;
    r.options = defaultBenchOptions(/*quick=*/true, IBLAB_ASSET_DIR);
    r.references.push_back({"sky", 64, 0.38, 12.0});
    for (std::size_t i = 0; i < r.options.points.size(); ++i) {
        BenchPoint p;
        p.environment = "sky";
        p.setting = r.options.points[i];
        p.bakeMilliseconds = 10.0 + double(i);
        p.frameMilliseconds = 2.5;
        p.costMilliseconds = p.bakeMilliseconds + p.frameMilliseconds;
        p.error.relativeRmse = 1.0 / (1.0 + double(i));
        p.error.pixels = 321;
        r.points.push_back(p);
    }
    markDominated(r.points);
    std::istringstream csv(benchCsvText(r));
    std::string line;
    ASSERT_TRUE(std::getline(csv, line));
    EXPECT_EQ(csvFields(line), benchCsvColumns());
    const auto column = [](const std::string& name) {
        const auto& c = benchCsvColumns();
        return std::size_t(std::find(c.begin(), c.end(), name) - c.begin());
    };
    std::size_t rows = 0;
    while (std::getline(csv, line)) {
        const std::vector<std::string> fields = csvFields(line);
        ASSERT_EQ(fields.size(), benchCsvColumns().size()) << line;
        const BenchPoint& p = r.points[rows];
        EXPECT_EQ(fields[column("label")], p.setting.label);
        EXPECT_NEAR(std::stod(fields[column("relative_rmse")]), p.error.relativeRmse, 1e-5 * p.error.relativeRmse);
        EXPECT_NEAR(std::stod(fields[column("cost_ms")]), p.costMilliseconds, 1e-3);
        EXPECT_EQ(fields[column("dominated")], p.dominated ? "1" : "0");
        ++rows;
    }
    EXPECT_EQ(rows, r.points.size());

    const nlohmann::json j = nlohmann::json::parse(benchJsonText(r));
    ASSERT_EQ(j.at("points").size(), r.points.size());
    for (std::size_t i = 0; i < r.points.size(); ++i) {
        const nlohmann::json& p = j["points"][i];
        EXPECT_EQ(p.at("label"), r.points[i].setting.label);
        EXPECT_EQ(p.at("error").at("relative_rmse").get<double>(), r.points[i].error.relativeRmse);
        EXPECT_EQ(p.at("dominated").get<bool>(), r.points[i].dominated);
        EXPECT_FALSE(p.at("bake_phases").empty());
    }
    EXPECT_EQ(j.at("references").size(), r.options.environments.size());
}

} // namespace
} // namespace iblab
