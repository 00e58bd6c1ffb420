// The auto quality mode's selection (renderer/bench/auto_quality.hpp) on hand-made points:
// the cheapest candidate within the target, the most accurate when none is (with how far the
// target is out of reach), presets and unmeasured points never chosen; and the pruning of the
// candidate space by the environment's dynamic range, the scene's roughness and metallic
// ranges, with the reasons it gives; and the reference width rule it shares with the bench.
#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "lab/auto_quality.hpp"

namespace iblab::bench {
namespace {

BenchPoint point(const std::string& label, double cost, double p99Steps, SweepFamily family = SweepFamily::SplitSum)
{
    BenchPoint p;
    p.environment = "env";
    p.setting.family = family;
    p.setting.label = label;
    p.costMilliseconds = cost;
    p.display.p99Steps = p99Steps;
    p.display.pixels = 1000;
    return p;
}

bool anyReasonContains(const AutoChoice& c, const std::string& text)
{
    return std::any_of(c.reasons.begin(), c.reasons.end(), [&](const std::string& r) { return r.find(text) != std::string::npos; });
}

TEST(AutoQuality, ChoosesTheCheapestCandidateWithinTheTarget)
{
    const std::vector<BenchPoint> measured{
        point("cheap but coarse", 10.0, 3.0),
        point("within, dearer", 30.0, 0.5),
        point("within, cheapest", 20.0, 0.9),
        point("exactly at the target", 25.0, 1.0),
        point("preset, cheaper and better", 5.0, 0.1, SweepFamily::Preset), // not a candidate
    };
    const AutoChoice c = chooseAuto(measured, 1.0, {"pruned: nothing"});
    ASSERT_TRUE(c.found);
    EXPECT_TRUE(c.meetsTarget);
    EXPECT_EQ(c.chosen.setting.label, "within, cheapest");
    EXPECT_EQ(c.candidates, 4u);
    EXPECT_EQ(c.meeting, 3u);
    ASSERT_FALSE(c.reasons.empty());
    EXPECT_EQ(c.reasons.front(), "pruned: nothing");
    EXPECT_TRUE(anyReasonContains(c, "cheap but coarse")) << "says what the cheaper candidate misses by";
    EXPECT_TRUE(anyReasonContains(c, "within, dearer")) << "names the most accurate one";

    // A tighter target moves the choice to the more accurate, dearer candidate.
    EXPECT_EQ(chooseAuto(measured, 0.6, {}).chosen.setting.label, "within, dearer");
}

TEST(AutoQuality, OutOfReachTakesTheMostAccurateAndSaysByHowMuch)
{
    const std::vector<BenchPoint> measured{point("a", 10.0, 6.0), point("b", 40.0, 2.5), point("c", 20.0, 4.0)};
    const AutoChoice c = chooseAuto(measured, 1.0, {});
    ASSERT_TRUE(c.found);
    EXPECT_FALSE(c.meetsTarget);
    EXPECT_EQ(c.meeting, 0u);
    EXPECT_EQ(c.chosen.setting.label, "b");
    EXPECT_TRUE(anyReasonContains(c, "out of reach")) << c.reasons.back();
    EXPECT_TRUE(anyReasonContains(c, "2.5x the target")) << c.reasons.back();
}

TEST(AutoQuality, PointsWithoutMeasuredPixelsAreNoEvidence)
{
    std::vector<BenchPoint> measured{point("unmeasured, cheap", 1.0, 0.0), point("measured", 10.0, 0.5)};
    measured[0].display.pixels = 0;
    EXPECT_EQ(chooseAuto(measured, 1.0, {}).chosen.setting.label, "measured");
    measured[1].display.pixels = 0;
    const AutoChoice none = chooseAuto(measured, 1.0, {});
    EXPECT_FALSE(none.found);
    EXPECT_FALSE(none.meetsTarget);
    EXPECT_EQ(none.chosen.environment, "env");
    EXPECT_TRUE(anyReasonContains(none, "nothing to choose"));
}

SceneFacts grid(double dynamicRange)
{
    SceneFacts f;
    f.dynamicRange = dynamicRange;
    f.surfaces = "grid";
    return f;
}

bool pdfFiltered(const SweepPoint& p) { return p.sampling.method == ShadingMethod::Sampled ? p.sampling.pdfMipFiltering : p.bake.prefilter.mipFiltering; }

TEST(AutoQuality, HighDynamicRangeKeepsOnlyUnfilteredCandidatesWithEnoughSamples)
{
    const AutoCandidates low = autoCandidates(/*quick=*/false, grid(2.0));
    const AutoCandidates high = autoCandidates(/*quick=*/false, grid(100.0));
    const auto unfiltered = [](const AutoCandidates& c) {
        return std::count_if(c.points.begin(), c.points.end(), [](const SweepPoint& p) { return !pdfFiltered(p); });
    };
    EXPECT_GT(unfiltered(low), 0);
    EXPECT_LT(unfiltered(high), unfiltered(low));
    for (const SweepPoint& p : high.points) {
        if (pdfFiltered(p)) continue;
        const int samples = p.sampling.method == ShadingMethod::Sampled ? p.sampling.samples : p.bake.prefilter.samples;
        EXPECT_GE(samples * 3, 100) << p.label << ": one sample on a peak 100x the mean would be a firefly";
    }
    // Filtered candidates are never pruned by the dynamic range.
    const auto filtered = [](const AutoCandidates& c) { return std::count_if(c.points.begin(), c.points.end(), pdfFiltered); };
    EXPECT_EQ(filtered(high), filtered(low));
    EXPECT_TRUE(std::any_of(high.reasons.begin(), high.reasons.end(), [](const std::string& r) { return r.find("firefly") != std::string::npos; }));
}

int largestFace(const AutoCandidates& c)
{
    int face = 0;
    for (const SweepPoint& p : c.points)
        if (p.sampling.method == ShadingMethod::SplitSum) face = std::max(face, p.bake.prefilter.faceSize);
    return face;
}

TEST(AutoQuality, RoughScenesDropFacesOnlySmoothSurfacesResolve)
{
    SceneFacts rough = grid(2.0);
    rough.minRoughness = rough.maxRoughness = 0.9;
    const AutoCandidates smooth = autoCandidates(false, grid(2.0));
    const AutoCandidates pruned = autoCandidates(false, rough);
    EXPECT_EQ(largestFace(smooth), 128) << "a mirror reads mip 0: every face is kept";
    EXPECT_EQ(largestFace(pruned), 64);
    EXPECT_LT(pruned.points.size(), smooth.points.size());
    EXPECT_TRUE(std::any_of(pruned.reasons.begin(), pruned.reasons.end(), [](const std::string& r) { return r.find("larger faces dropped") != std::string::npos; }));
    // The sampled method reads the environment cube, not the prefilter: untouched.
    const auto sampled = [](const AutoCandidates& c) {
        return std::count_if(c.points.begin(), c.points.end(), [](const SweepPoint& p) { return p.sampling.method == ShadingMethod::Sampled; });
    };
    EXPECT_EQ(sampled(pruned), sampled(smooth));
}

TEST(AutoQuality, OffersTheSpecularReadsAsCandidatesAndAppliesThem)
{
    const AutoCandidates c = autoCandidates(/*quick=*/true, grid(2.0));
    for (const auto& [method, direction] : {std::pair{ShadingMethod::SplitSum, SpecularDirection::Frostbite},
                                            std::pair{ShadingMethod::SplitSum, SpecularDirection::Filament},
                                            std::pair{ShadingMethod::FittedLobe, SpecularDirection::Reflection}}) {
        const auto found = std::find_if(c.points.begin(), c.points.end(), [&](const SweepPoint& p) {
            return p.family == SweepFamily::SpecularLobe && p.sampling.method == method && p.sampling.specularDirection == direction;
        });
        ASSERT_NE(found, c.points.end()) << enumName(method) << " " << enumName(direction);
        EXPECT_NE(found->label, describeSettings(SweepPoint{})) << "its label says where it reads";
        AutoChoice choice;
        choice.found = true;
        choice.chosen.setting = *found;
        const SamplingSettings applied = appliedSampling(choice, SamplingSettings{});
        EXPECT_EQ(applied.specularDirection, direction);
        EXPECT_EQ(applied.method, found->sampling.method);
        EXPECT_EQ(appliedBakeSettings(choice, bake::defaultPreset()).prefilter.faceSize, found->bake.prefilter.faceSize);
    }
}

TEST(AutoQuality, AllMetalScenesDropTheIrradianceCube)
{
    const auto cubes = [](const AutoCandidates& c) {
        return std::count_if(c.points.begin(), c.points.end(), [](const SweepPoint& p) { return p.sampling.diffuse == DiffuseSource::IrradianceCube; });
    };
    SceneFacts metal = grid(2.0);
    metal.minMetallic = metal.maxMetallic = 1.0;
    EXPECT_GT(cubes(autoCandidates(true, grid(2.0))), 0);
    EXPECT_EQ(cubes(autoCandidates(true, metal)), 0);
}

TEST(AutoQuality, TheReferenceIsAsWideAsTheSmoothestSurfaceNeeds)
{
    SceneFacts sphere = grid(2.0);
    sphere.minRoughness = sphere.maxRoughness = 0.5;
    EXPECT_EQ(autoCandidates(true, sphere).referenceWidth, 64); // resolves >= 0.38
    sphere.minRoughness = 0.3;
    EXPECT_EQ(autoCandidates(true, sphere).referenceWidth, 128); // resolves >= 0.27
    EXPECT_EQ(autoCandidates(true, grid(2.0)).referenceWidth, 128) << "capped in the quick run";
    // The reference sums over no more texels than the map has.
    sphere.environmentWidth = 64;
    EXPECT_EQ(autoCandidates(true, sphere).referenceWidth, 64);
}

// One rule widens the reference for the auto mode and the bench: the narrowest from 64 that
// resolves the smoothest surface, within the run's cap and the map. The bench's defaults
// leave the width to it (0) instead of fixing one that a smooth scene has nothing above.
TEST(AutoQuality, TheBenchAndTheAutoModeWidenTheReferenceByOneRule)
{
    EXPECT_EQ(referenceWidthFor(0.5, 4096), 64);
    EXPECT_EQ(referenceWidthFor(0.3, 4096), 128);
    EXPECT_EQ(referenceWidthFor(0.2, 4096), 256);
    EXPECT_EQ(referenceWidthFor(0.0, 512), 512) << "no width resolves a mirror: the widest allowed";
    EXPECT_EQ(referenceWidthFor(0.3, 32), 32) << "never past the map";
    for (const bool quick : {true, false})
        for (const double roughness : {0.0, 0.2, 0.3, 0.5}) {
            SceneFacts facts = grid(2.0);
            facts.minRoughness = roughness;
            EXPECT_EQ(autoCandidates(quick, facts).referenceWidth, referenceWidthFor(facts, quick)) << quick << " " << roughness;
            EXPECT_LE(referenceWidthFor(facts, quick), maxReferenceWidth(quick));
        }
    EXPECT_EQ(maxReferenceWidth(true), 128) << "the quick run resolves the default sphere (0.3)";
    EXPECT_EQ(defaultBenchOptions(true, "").referenceWidth, 0);
    EXPECT_EQ(defaultBenchOptions(false, "").referenceWidth, 0);
}

TEST(AutoQuality, ReasonsSayWhichSurfacesTheReferenceResolved)
{
    SceneFacts sphere = grid(2.0);
    sphere.minRoughness = sphere.maxRoughness = 0.3;
    const ReferenceSummary narrow{"env", 64, 0.38, 1.0}, wide{"env", 128, 0.27, 1.0};
    EXPECT_NE(referenceReason(sphere, narrow).find("measured: nothing"), std::string::npos) << referenceReason(sphere, narrow);
    EXPECT_NE(referenceReason(sphere, wide).find("measured: every surface"), std::string::npos) << referenceReason(sphere, wide);
    EXPECT_NE(referenceReason(grid(2.0), wide).find("not judged on them"), std::string::npos) << referenceReason(grid(2.0), wide);

    // The report's reference lands in the choice's reasons, after the pruning.
    BenchReport report;
    report.references = {narrow};
    report.points = {point("a", 1.0, 0.5)};
    AutoCandidates candidates;
    candidates.facts = sphere;
    candidates.reasons = {"pruned"};
    const AutoChoice c = chooseAuto(report, 1.0, candidates);
    ASSERT_GE(c.reasons.size(), 3u);
    EXPECT_EQ(c.reasons[0], "pruned");
    EXPECT_EQ(c.reasons[1], referenceReason(sphere, narrow));
}

TEST(AutoQuality, SceneFactsFollowTheSceneAndTheEnvironment)
{
    ImageRGB32F uniform(64, 32);
    std::fill(uniform.texels.begin(), uniform.texels.end(), 0.5f);
    EXPECT_NEAR(environmentDynamicRange(uniform), 1.0, 1e-9);
    ImageRGB32F sun = uniform;
    for (int c = 0; c < 3; ++c) sun.texels[sun.offset(10, 16) + std::size_t(c)] = 500.0f;
    // One texel of 1000x the rest: the mean rises by about its share of the sphere.
    const double range = environmentDynamicRange(sun);
    EXPECT_GT(range, 100.0);
    EXPECT_LT(range, 1000.0);
    EXPECT_EQ(environmentDynamicRange(ImageRGB32F(64, 32)), 1.0) << "black";

    FrameSettings frame;
    frame.scene.kind = SceneKind::Sphere;
    frame.material.roughness = 0.4f;
    frame.material.metallic = 1.0f;
    const SceneFacts sphere = sceneFacts(frame, sun);
    EXPECT_FLOAT_EQ(float(sphere.minRoughness), 0.4f);
    EXPECT_FLOAT_EQ(float(sphere.maxRoughness), 0.4f);
    EXPECT_EQ(sphere.minMetallic, 1.0);
    EXPECT_EQ(sphere.dynamicRange, range);
    frame.scene.kind = SceneKind::Grid;
    const SceneFacts all = sceneFacts(frame, sun);
    EXPECT_EQ(all.minRoughness, 0.0);
    EXPECT_EQ(all.maxRoughness, 1.0);
    EXPECT_EQ(all.minMetallic, 0.0);
    frame.scene.kind = SceneKind::None;
    EXPECT_FALSE(sceneFacts(frame, sun).hasSurfaces);
}

TEST(AutoQuality, ApplyingKeepsTheSessionsCubeAndLut)
{
    const AutoCandidates candidates = autoCandidates(true, grid(2.0));
    const auto cube = std::find_if(candidates.points.begin(), candidates.points.end(),
                                   [](const SweepPoint& p) { return p.sampling.diffuse == DiffuseSource::IrradianceCube && p.bake.prefilter.faceSize == 64; });
    ASSERT_NE(cube, candidates.points.end());
    AutoChoice choice;
    choice.found = true;
    choice.chosen.setting = *cube;
    bake::BakeSettings current = bake::tutorialPreset();
    const bake::BakeSettings applied = appliedBakeSettings(choice, current);
    EXPECT_EQ(applied.prefilter.faceSize, 64);
    EXPECT_EQ(applied.prefilter.levels, cube->bake.prefilter.levels);
    EXPECT_EQ(applied.prefilter.samples, cube->bake.prefilter.samples);
    EXPECT_EQ(applied.irradiance, bake::IrradianceMethod::Importance) << "the tutorial's Riemann cube is no longer read";
    EXPECT_EQ(applied.cube.faceSize, current.cube.faceSize);
    EXPECT_EQ(applied.lut.size, current.lut.size);
    SamplingSettings sampling;
    sampling.method = ShadingMethod::Sampled;
    const SamplingSettings shaded = appliedSampling(choice, sampling);
    EXPECT_EQ(shaded.method, ShadingMethod::SplitSum);
    EXPECT_EQ(shaded.diffuse, DiffuseSource::IrradianceCube);
}

} // namespace
} // namespace iblab::bench
