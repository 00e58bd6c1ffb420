// What a frame is made of besides the shading: accumulation restarts when what the renderer
// was given changes, the counting strip keeps exactly N samples, the strips' captions, and
// MSAA (that it anti-aliases, and that the error against the single-sampled reference is
// measured over the same pixels as without it).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "bake_test_support.hpp"
#include "frame/camera.hpp"
#include "ibl/error_metrics.hpp"
#include "renderer_fixture.hpp"
#include "scene/gltf_model.hpp"

namespace iblab {
namespace {

constexpr int kSize = 48; // a sphere of ~1000 pixels, as in reference_gltest

class Frame : public testing::RendererTest {
protected:
    void bake(const std::string& spec) { bakeEnvironment(spec, testing::smallBakeSettings()); }
    // A copper-ish metal sphere framed to fill a square view.
    static FrameSettings sphere()
    {
        FrameSettings s;
        s.scene.kind = SceneKind::Sphere;
        s.material = {true, glm::vec3(0.9f, 0.6f, 0.4f), 1.0f, 0.4f, 1.0f, 0.5f};
        s.view.referenceWidth = 64;
        frameBox(s.camera, glm::vec3(0.0f), glm::vec3(1.0f), 1.0f);
        return s;
    }
    FrameReadback accumulate(const FrameSettings& s)
    {
        renderer().renderFrame(s, kSize, kSize, Renderer::Options{1.0f, true});
        return renderer().readHdrFrame();
    }
};

glm::vec4 pixelOf(const FrameReadback& f, int x, int y) { return glm::make_vec4(&f.rgba[(std::size_t(y) * std::size_t(f.width) + std::size_t(x)) * 4]); }
float coverageOf(const FrameReadback& f, std::size_t pixel) { return f.rgba[pixel * 4 + 3]; }

// The radius in pixels of the unit sphere's silhouette, centred in a kSize x kSize frame:
// its angular radius asin(1 / distance) about the view axis.
float silhouetteRadius(const CameraSettings& camera)
{
    const float tanHalfFov = std::tan(0.5f * glm::radians(camera.fovDegrees));
    return std::tan(std::asin(1.0f / camera.distance)) / tanHalfFov * 0.5f * float(kSize);
}

// Of pixel i of a kSize x kSize frame, from the frame's centre.
float distanceFromCentre(std::size_t i)
{
    return glm::length(glm::vec2(float(i % kSize) + 0.5f, float(i / kSize) + 0.5f) - glm::vec2(0.5f * kSize));
}

// The bug this guards against: the running mean was keyed on the settings alone, so a new
// environment (with its bake) was averaged with the frames of the old one.
TEST_F(Frame, AccumulationRestartsWhenTheEnvironmentChanges)
{
    bake("builtin:white?width=64");
    FrameSettings s = sphere();
    s.sampling.method = ShadingMethod::Sampled;
    s.sampling.samples = 4;
    for (int i = 0; i < 4; ++i) accumulate(s);
    ASSERT_EQ(renderer().accumulatedFrames(), 4);
    ASSERT_GT(pixelOf(renderer().readHdrFrame(), kSize / 2, kSize / 2).g, 0.5f) << "the white environment lights the sphere";

    bake("builtin:black?width=64");
    const FrameReadback dark = accumulate(s);
    EXPECT_EQ(renderer().accumulatedFrames(), 1);
    // Exactly 0: no light at all, and nothing left of the white frames (a mean with them
    // would be 4/5 of their brightness).
    EXPECT_EQ(glm::length(glm::vec3(pixelOf(dark, kSize / 2, kSize / 2))), 0.0f) << "the sphere";
    EXPECT_EQ(glm::length(glm::vec3(pixelOf(dark, 0, 0))), 0.0f) << "the sky";
}

// A shader edited while the GUI runs (hot reload) draws another image: the frames of the
// old one must leave the running mean, and the reference must start again. Reloading with
// nothing changed must keep both, or every frame would restart them.
TEST_F(Frame, AShaderReloadRestartsTheRunningMeanAndTheReference)
{
    const testing::TempDirectory shaders("frame-reload");
    std::filesystem::copy(shaderDirectory(), shaders.path(), std::filesystem::copy_options::recursive);
    Renderer renderer(shaders.path().string());
    const Environment environment = loadEnvironment("builtin:sky?width=64");
    renderer.setEnvironment(environment.image);
    bake::BakeJob job(renderer.shaders(), environment, testing::smallBakeSettings());
    renderer.setBake(std::make_shared<bake::BakeResult>(job.runToCompletion()));
    FrameSettings s = sphere();
    s.sampling.method = ShadingMethod::Sampled;
    s.sampling.samples = 4;
    auto accumulate = [&] { renderer.renderFrame(s, kSize, kSize, Renderer::Options{1.0f, true}); };
    const ReferenceStatus reference = renderer.advanceReference(s, kSize, kSize, std::chrono::hours(1));
    ASSERT_TRUE(reference.complete);
    for (int i = 0; i < 3; ++i) accumulate();
    ASSERT_EQ(renderer.accumulatedFrames(), 3);

    EXPECT_TRUE(renderer.reloadShaders().empty());
    accumulate();
    EXPECT_EQ(renderer.accumulatedFrames(), 4) << "nothing was edited";
    EXPECT_TRUE(renderer.referenceStatus(s, kSize, kSize).complete) << "nothing was edited";

    // Every program that draws the sphere includes ibl_lighting.glsl.
    const std::filesystem::path edited = shaders.path() / "common" / "ibl_lighting.glsl";
    std::filesystem::last_write_time(edited, std::filesystem::last_write_time(edited) + std::chrono::seconds(2));
    EXPECT_TRUE(renderer.reloadShaders().empty());
    accumulate();
    EXPECT_EQ(renderer.accumulatedFrames(), 1);
    EXPECT_FALSE(renderer.referenceStatus(s, kSize, kSize).current) << "the old shaders' reference";
    const ReferenceStatus again = renderer.advanceReference(s, kSize, kSize, std::chrono::hours(1));
    EXPECT_TRUE(again.complete);
    EXPECT_NE(again.run, reference.run);
}

TEST_F(Frame, EverySetterOfContentMovesTheRevision)
{
    const Environment environment = loadEnvironment("builtin:sky?width=64");
    const ModelData model = loadGltfModel(IBLAB_ASSET_DIR "/models/material_spheres.glb");
    std::uint64_t last = renderer().contentRevision();
    auto moved = [&] {
        const std::uint64_t now = renderer().contentRevision();
        const bool result = now > last;
        last = now;
        return result;
    };
    renderer().setEnvironment(environment.image);
    EXPECT_TRUE(moved()) << "setEnvironment";
    renderer().setBake(nullptr);
    EXPECT_TRUE(moved()) << "setBake";
    renderer().setFurnaceBake(nullptr);
    EXPECT_TRUE(moved()) << "setFurnaceBake";
    renderer().setModel(model, "material_spheres.glb");
    EXPECT_TRUE(moved()) << "setModel";
    FrameSettings s;
    renderer().renderFrame(s, 8, 8);
    EXPECT_FALSE(moved()) << "a frame shows the content; it does not change it";
}

// The counting strip shows N = i on sphere i: rotated sample sets added over frames would
// make it N = 2i, 3i, ... So does the freeze switch on any scene. Without it, accumulation
// goes on (or this test would prove nothing).
TEST_F(Frame, ExactSampleCountsAreNotAccumulated)
{
    bake("builtin:studio?width=128");
    FrameSettings counting;
    counting.scene.kind = SceneKind::Counting;
    counting.scene.countingSpheres = 3;
    const SceneInfo strip = renderer().sceneInfo(counting);
    frameBox(counting.camera, strip.centre, strip.halfExtents, 1.0f);
    FrameSettings frozen = sphere();
    frozen.sampling.method = ShadingMethod::Sampled;
    frozen.sampling.samples = 1;
    frozen.sampling.freezeSampleSet = true;
    for (const FrameSettings& s : {counting, frozen}) {
        SCOPED_TRACE(enumName(s.scene.kind));
        const FrameReadback first = accumulate(s);
        for (int i = 0; i < 2; ++i) {
            const FrameReadback again = accumulate(s);
            EXPECT_EQ(renderer().accumulatedFrames(), 1);
            EXPECT_TRUE(again.rgba == first.rgba) << "frame " << i + 2 << " differs from the first";
            EXPECT_FALSE(renderer().lastFrameWasSampled()) << "its first frame is final";
        }
    }

    FrameSettings rotating = frozen;
    rotating.sampling.freezeSampleSet = false;
    const FrameReadback first = accumulate(rotating);
    accumulate(rotating);
    const FrameReadback third = accumulate(rotating);
    EXPECT_EQ(renderer().accumulatedFrames(), 3);
    EXPECT_TRUE(renderer().lastFrameWasSampled());
    EXPECT_FALSE(third.rgba == first.rgba);
}

// With the split view, each side follows its own switch: the frozen side stays its first
// frame (up to the running mean's float rounding of equal values), the other refines.
TEST_F(Frame, SplitViewFreezesEachSideByItsOwnSettings)
{
    bake("builtin:studio?width=128");
    FrameSettings s = sphere();
    s.sampling.method = ShadingMethod::Sampled;
    s.sampling.samples = 1;
    s.sampling.freezeSampleSet = true;
    s.view.split = true;
    s.view.compare = s.sampling;
    s.view.compare.freezeSampleSet = false;
    const FrameReadback first = accumulate(s);
    accumulate(s);
    const FrameReadback third = accumulate(s);
    EXPECT_EQ(renderer().accumulatedFrames(), 3);
    const int divider = splitColumn(s.view, kSize);
    int changedRight = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const glm::vec4 a = pixelOf(first, x, y), b = pixelOf(third, x, y);
            // 1e-6 relative: averaging equal half floats in a float32 mean may round the last bits.
            if (x < divider)
                for (int c = 0; c < 3; ++c) ASSERT_NEAR(b[c], a[c], 1e-6f * std::abs(a[c])) << "pixel " << x << "," << y;
            else changedRight += glm::any(glm::greaterThan(glm::abs(a - b), glm::vec4(1e-3f)));
        }
    EXPECT_GT(changedRight, 50);
}

TEST_F(Frame, StripsCaptionEachSphereBelowIt)
{
    for (const SceneKind kind : {SceneKind::Counting, SceneKind::Sweep}) {
        SCOPED_TRACE(enumName(kind));
        FrameSettings s;
        s.scene.kind = kind;
        s.scene.countingSpheres = 5;
        const SceneInfo info = renderer().sceneInfo(s);
        constexpr int width = 640, height = 160;
        frameBox(s.camera, info.centre, info.halfExtents, float(width) / float(height));
        const std::vector<ScreenLabel> labels = renderer().sceneLabels(s, width, height);
        const std::vector<std::string> expected = kind == SceneKind::Counting
                                                      ? std::vector<std::string>{"N = 1", "N = 2", "N = 3", "N = 4", "N = 5"}
                                                      : std::vector<std::string>{"r = 0.00", "r = 0.25", "r = 0.50", "r = 0.75", "r = 1.00"};
        ASSERT_EQ(labels.size(), expected.size());
        const glm::mat4 viewProjection = cameraProjection(s.camera, float(width) / float(height)) * cameraView(s.camera);
        for (std::size_t i = 0; i < labels.size(); ++i) {
            EXPECT_EQ(labels[i].text, expected[i]);
            EXPECT_FALSE(labels[i].title);
            // Sphere i's centre (2.5 apart along +X, centred on 0), projected.
            const glm::vec4 clip = viewProjection * glm::vec4((float(i) - 2.0f) * 2.5f, 0.0f, 0.0f, 1.0f);
            const glm::vec2 centre = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(width, height);
            // Half a pixel: the caption is straight below the centre, so only the
            // perspective of its lower position can move it sideways.
            EXPECT_NEAR(labels[i].pixel.x, centre.x, 0.5f) << labels[i].text;
            EXPECT_LT(labels[i].pixel.y, centre.y) << labels[i].text << " is below its sphere (y up)";
            EXPECT_GT(labels[i].pixel.y, 0.0f) << labels[i].text << " is inside the framed view";
        }
    }
}

// Silhouette pixels are partly sphere and partly sky with 4 samples (their coverage, the
// frame's alpha, lies strictly between 0 and 1), and only there; single-sampled, every
// pixel is all one or the other.
TEST_F(Frame, MsaaAntiAliasesTheSilhouette)
{
    bake("builtin:studio?width=128");
    FrameSettings s = sphere();
    const float radiusPixels = silhouetteRadius(s.camera);
    for (const int samples : {1, 4}) {
        s.view.msaaSamples = samples;
        renderer().renderFrame(s, kSize, kSize);
        EXPECT_EQ(renderer().frameSamples(), samples);
        const FrameReadback frame = renderer().readHdrFrame();
        int partial = 0, full = 0;
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                const float coverage = pixelOf(frame, x, y).a;
                full += coverage == 1.0f;
                if (coverage == 0.0f || coverage == 1.0f) continue;
                ++partial;
                // 1 pixel: a pixel the silhouette crosses has its centre within
                // sqrt(2) / 2 of it, and the UV sphere's 64 segments bend the circle by
                // far less than a pixel at this size.
                EXPECT_NEAR(distanceFromCentre(std::size_t(y * kSize + x)), radiusPixels, 1.0f) << "partly covered pixel " << x << "," << y << " is off the silhouette";
            }
        EXPECT_GT(full, 800) << samples << " samples: the sphere's inside is covered";
        if (samples == 1) EXPECT_EQ(partial, 0);
        // The silhouette is ~2 pi r = 120 pixels long; most of them are partly covered.
        else EXPECT_GT(partial, 60);
    }
}

float luminanceOf(const FrameReadback& f, int x, int y) { return glm::dot(glm::vec3(pixelOf(f, x, y)), glm::vec3(0.2126f, 0.7152f, 0.0722f)); }

// A silhouette pixel with 4 samples is shaded once per triangle, for the samples the
// triangle covers; interpolated at the pixel centre, past the rim, its normal would face
// away from the viewer and reflect a grazing, Fresnel-brightened environment: a bright
// fringe. Its radiance mixes surface and sky, each like a neighbour's, so it must not
// stand out from them.
TEST_F(Frame, MsaaSilhouetteHasNoBrightFringe)
{
    bake("builtin:studio?width=128");
    FrameSettings s = sphere();
    s.view.msaaSamples = 4;
    renderer().renderFrame(s, kSize, kSize);
    const FrameReadback frame = renderer().readHdrFrame();
    float worst = 0.0f;
    int partial = 0;
    for (int y = 1; y + 1 < kSize; ++y)
        for (int x = 1; x + 1 < kSize; ++x) {
            const float coverage = pixelOf(frame, x, y).a;
            if (coverage == 0.0f || coverage == 1.0f) continue;
            ++partial;
            float brightestNeighbour = 0.0f;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    if (dx || dy) brightestNeighbour = std::max(brightestNeighbour, luminanceOf(frame, x + dx, y + dy));
            worst = std::max(worst, luminanceOf(frame, x, y) / brightestNeighbour);
        }
    ASSERT_GT(partial, 60);
    // 2: measured 1.35 (1.2 with centroid interpolation everywhere, 11.7 with the pixel
    // centre everywhere).
    EXPECT_LT(worst, 2.0f);
}

// The reference shades pixel centres, single-sampled. With MSAA the error is measured over
// the pixels the frame covers wholly, which leaves out the silhouette. There every triangle
// that covers samples shades once, interpolated at the pixel centre (pbr.frag), so the
// resolve is nearly the single-sampled shading: exactly where one triangle covers the
// pixel; where several small ones share it, those whose plane misses the centre
// extrapolate to it, which moves the result where the normal turns fast, near the rim.
TEST_F(Frame, MsaaErrorMeasuresTheSingleSampledPixels)
{
    bake("builtin:studio?width=128");
    FrameSettings s = sphere();
    // The split sum, on which the tolerances below were measured (the fitted lobe's narrower
    // reads vary more within a pixel: 1.04e-2 inside). What is tested is the MSAA pixel rule.
    s.sampling.method = ShadingMethod::SplitSum;
    s.view.mode = ViewMode::Error;
    ASSERT_TRUE(renderer().advanceReference(s, kSize, kSize, std::chrono::hours(1)).complete);
    const FrameReadback reference = renderer().readReferenceFrame();
    FrameReadback frames[2];
    ErrorMetrics metrics[2];
    DisplayReadback shown[2];
    for (const int i : {0, 1}) {
        s.view.msaaSamples = i == 0 ? 1 : 4;
        renderer().renderFrame(s, kSize, kSize);
        const ErrorReport report = renderer().measureError(s);
        ASSERT_TRUE(report.valid) << "the reference does not depend on the MSAA samples";
        frames[i] = renderer().readHdrFrame();
        metrics[i] = report.left;
        shown[i] = renderer().readDisplayImage();
    }
    const ErrorMetrics& single = metrics[0];
    const ErrorMetrics& msaa = metrics[1];
    EXPECT_LT(msaa.pixels, single.pixels) << "silhouette pixels are left out";
    EXPECT_GT(msaa.pixels, single.pixels * 9 / 10) << "only those: silhouette pixels with their centre on the sphere, ~50 of ~900";

    const FrameReadback normals = renderer().readReferenceLayer(ReferenceLayer::Normal);
    const float rim = silhouetteRadius(s.camera) - 2.5f;
    std::vector<std::uint8_t> include(reference.rgba.size() / 4);
    float largestInside = 0.0f, largestNearRim = 0.0f;
    for (std::size_t i = 0; i < include.size(); ++i) {
        include[i] = isMeasuredPixel(coverageOf(frames[1], i), normals.rgba[i * 4 + 3]);
        if (!include[i]) continue;
        const float e = relativeError(glm::make_vec3(&frames[1].rgba[i * 4]), glm::make_vec3(&frames[0].rgba[i * 4]));
        float& largest = distanceFromCentre(i) < rim ? largestInside : largestNearRim;
        largest = std::max(largest, e);
    }
    // Per pixel, on studio's small bright softboxes at roughness 0.4 (a shading that varies
    // a lot within a pixel): 1e-2 more than 2.5 pixels inside the silhouette (measured
    // 0.5e-2; half floats alone are 1e-3), 0.25 within them (measured 0.10).
    EXPECT_LT(largestInside, 1e-2f);
    EXPECT_LT(largestNearRim, 0.25f);
    // The summary over the same pixels: within 2% (measured 0.6%, the rim band's share).
    const ErrorMetrics singleOverMsaaPixels = computeErrorMetrics(frames[0].rgba, reference.rgba, include);
    ASSERT_EQ(singleOverMsaaPixels.pixels, msaa.pixels);
    EXPECT_NEAR(msaa.relativeRmse, singleOverMsaaPixels.relativeRmse, 2e-2 * singleOverMsaaPixels.relativeRmse);
    EXPECT_NEAR(msaa.meanRelative, singleOverMsaaPixels.meanRelative, 2e-2 * singleOverMsaaPixels.meanRelative);

    // The error view shows what measureError measures: a silhouette pixel that the
    // single-sampled view colours is grey (background) with MSAA.
    int greyed = 0;
    for (std::size_t i = 0; i < include.size(); ++i) {
        const float coverage = coverageOf(frames[1], i);
        if (coverage == 0.0f || coverage == 1.0f || normals.rgba[i * 4 + 3] == 0.0f) continue;
        const std::uint8_t* before = &shown[0].rgba[i * 4];
        const std::uint8_t* after = &shown[1].rgba[i * 4];
        EXPECT_TRUE(after[0] == after[1] && after[1] == after[2]) << "partly covered pixel " << i << " is shown in false colour";
        greyed += !(before[0] == before[1] && before[1] == before[2]);
    }
    EXPECT_GT(greyed, 10);
}

} // namespace
} // namespace iblab
