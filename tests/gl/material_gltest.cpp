// Lit surfaces, checked against what is known without the code under test: the number of
// reflections N samples must show of a single light, the white furnace, and the symmetry
// between the two estimators where both are exact.
#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/glm.hpp>

#include "bake/bake_job.hpp"
#include "frame/camera.hpp"
#include "ibl/brdf_lut.hpp"
#include "io/environment.hpp"
#include "bake_test_support.hpp"
#include "renderer_fixture.hpp"

namespace iblab {
namespace {

// The bake tests' small settings, with the default preset's LUT: the furnace's answer is
// the LUT's A + B, which a 16^2 LUT would only give to a few percent.
bake::BakeSettings smallBake()
{
    bake::BakeSettings s = testing::smallBakeSettings();
    s.prefilter.faceSize = 32;
    s.lut = bake::defaultPreset().lut;
    return s;
}

class Material : public testing::RendererTest {
protected:
    void bake(const std::string& spec) { bakeEnvironment(spec, smallBake()); }
    FrameReadback render(FrameSettings& settings, int width, int height)
    {
        if (settings.camera.distance <= 0.0f) {
            const SceneInfo scene = renderer().sceneInfo(settings);
            frameBox(settings.camera, scene.centre, scene.halfExtents, float(width) / float(height));
        }
        renderer().renderFrame(settings, width, height);
        return renderer().readHdrFrame();
    }
};

float luminance(const FrameReadback& f, int x, int y)
{
    const float* p = &f.rgba[(std::size_t(y) * std::size_t(f.width) + std::size_t(x)) * 4];
    return 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
}

// 8-connected components of pixels brighter than threshold within columns [x0, x1).
int countBrightBlobs(const FrameReadback& f, int x0, int x1, float threshold)
{
    std::vector<int> label(std::size_t(f.width) * std::size_t(f.height), 0);
    int blobs = 0;
    std::vector<glm::ivec2> stack;
    for (int y = 0; y < f.height; ++y)
        for (int x = x0; x < x1; ++x) {
            const std::size_t i = std::size_t(y) * std::size_t(f.width) + std::size_t(x);
            if (label[i] || luminance(f, x, y) <= threshold) continue;
            ++blobs;
            stack.push_back({x, y});
            label[i] = blobs;
            while (!stack.empty()) {
                const glm::ivec2 p = stack.back();
                stack.pop_back();
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const glm::ivec2 q = p + glm::ivec2(dx, dy);
                        if (q.x < x0 || q.x >= x1 || q.y < 0 || q.y >= f.height) continue;
                        const std::size_t j = std::size_t(q.y) * std::size_t(f.width) + std::size_t(q.x);
                        if (label[j] || luminance(f, q.x, q.y) <= threshold) continue;
                        label[j] = blobs;
                        stack.push_back(q);
                    }
            }
        }
    return blobs;
}

FrameSettings countingStripSettings(float roughness)
{
    FrameSettings s;
    s.scene.kind = SceneKind::Counting;
    s.scene.countingSpheres = 8;
    s.sampling.method = ShadingMethod::Sampled;
    s.sampling.forcedMip = 0; // every sample reads the sharp source: one sample, one image of the light
    s.material.metallic = 1.0f;
    s.material.roughness = roughness;
    s.material.baseColor = glm::vec3(1.0f);
    s.environment.yawDegrees = 180.0f; // the light behind the camera, so spheres reflect it face-on
    s.camera.distance = 0.0f;
    // A wide strip seen with a 45 degree vertical field of view spans 138 degrees
    // horizontally, and the outer spheres stretch into ellipses; 10 degrees keeps the
    // projection close to orthographic, so each sphere stays inside its column band.
    s.camera.fovDegrees = 10.0f;
    return s;
}

// Column bands of the strip's spheres: from halfway to the left neighbour's projected centre
// to halfway to the right one's (sphere centres are 2.5 apart along +X, centred on 0).
std::vector<int> sphereBandEdges(const FrameSettings& s, int width, int height)
{
    const int k = s.scene.countingSpheres;
    const glm::mat4 viewProjection = cameraProjection(s.camera, float(width) / float(height)) * cameraView(s.camera);
    auto column = [&](float x) {
        const glm::vec4 clip = viewProjection * glm::vec4(x, 0.0f, 0.0f, 1.0f);
        return int(std::lround((clip.x / clip.w * 0.5f + 0.5f) * float(width)));
    };
    std::vector<int> edges;
    for (int i = 0; i <= k; ++i) edges.push_back(std::clamp(column((float(i) - 0.5f * float(k)) * 2.5f), 0, width));
    return edges;
}

// Threshold: a reflection of the light carries about 200 / N of radiance on a black
// background (less where the Fresnel-visibility weight drops); 0.5 separates it from the
// black with a wide margin even at N = 8.
constexpr float kBrightThreshold = 0.5f;

class CountingStrip : public Material {
protected:
    // Bright blobs on each sphere of the 8-sphere strip at the given roughness.
    std::vector<int> highlightsPerSphere(float roughness)
    {
        bake("builtin:lights?count=1&elevation=20&size=2&intensity=800&width=1024");
        constexpr int kWidth = 1280, kHeight = 200;
        FrameSettings settings = countingStripSettings(roughness);
        const FrameReadback frame = render(settings, kWidth, kHeight);
        const std::vector<int> edges = sphereBandEdges(settings, kWidth, kHeight);
        std::vector<int> counts;
        for (std::size_t i = 0; i + 1 < edges.size(); ++i) counts.push_back(countBrightBlobs(frame, edges[i], edges[i + 1], kBrightThreshold));
        return counts;
    }
};

TEST_F(CountingStrip, ShowsNReflectionsOnSphereN)
{
    EXPECT_EQ(highlightsPerSphere(0.5f), (std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8}));
}

TEST_F(CountingStrip, ReflectionsMergeAtRoughnessZero)
{
    EXPECT_EQ(highlightsPerSphere(0.0f), std::vector<int>(8, 1));
}

// In a uniform environment of radiance 1, a white metal (F0 = 1) reflects exactly its
// directional albedo A + B, and with multiple-scattering compensation exactly 1 (that is
// what the compensation is for). Both methods must agree with that.
TEST_F(Material, WhiteFurnaceSplitSumAndSampled)
{
    bake("builtin:white?width=64");
    for (ShadingMethod method : {ShadingMethod::SplitSum, ShadingMethod::Sampled}) {
        for (float roughness : {0.2f, 0.6f, 1.0f}) {
            FrameSettings s;
            s.scene.kind = SceneKind::Sphere;
            s.material = {true, glm::vec3(1.0f), 1.0f, roughness, 1.0f, 0.5f};
            s.sampling.method = method;
            s.sampling.samples = 256;
            s.sampling.multiscatter = true;
            s.camera.distance = 0.0f;
            const FrameReadback frame = render(s, 64, 64);
            // The centre pixel sees the sphere face-on (n.v = 1).
            const float centre = luminance(frame, 32, 32);
            // 2%: the LUT is 128^2 half floats (its A + B is what compensation divides by),
            // and the sampled method's 256 Hammersley samples estimate that same A + B to
            // within about 1% (measured 0.99 at roughness 1, where the lobe is widest).
            EXPECT_NEAR(centre, 1.0f, 0.02f) << enumName(method) << " roughness " << roughness;
        }
    }
}

// Energy compensation is on by default, as the engines ship it (SamplingSettings): the
// default shading (the fitted lobe) and the split sum reflect all of a white furnace from a
// rough white metal, and --no-multiscatter gives back the single-scattering albedo E_ss,
// which the CPU core integrates independently of the GPU's LUT.
TEST_F(Material, WhiteFurnaceIsOneByDefaultAndTheSingleScatterAlbedoWithout)
{
    bake("builtin:white?width=64");
    // The centre pixel's n.v and roughness 1 both read the LUT's last texel centre (clamp to
    // edge); 4096 samples put the CPU's E_ss there within 1e-3 of exact.
    const double lastTexel = 1.0 - 0.5 / smallBake().lut.size;
    const double singleScatter = integrateSplitSumBrdf(lastTexel, lastTexel, 4096, GeometryTerm::HeightCorrelatedSmith).z;
    ASSERT_LT(singleScatter, 0.9) << "roughness 1 loses energy without compensation";
    for (ShadingMethod method : {ShadingMethod::FittedLobe, ShadingMethod::SplitSum}) {
        FrameSettings s;
        ASSERT_TRUE(s.sampling.multiscatter) << "the default";
        s.scene.kind = SceneKind::Sphere;
        s.material = {true, glm::vec3(1.0f), 1.0f, 1.0f, 1.0f, 0.5f};
        s.sampling.method = method;
        s.camera.distance = 0.0f;
        // 2%: the LUT is 128^2 half floats, read at the centre pixel's n.v (a little under 1).
        EXPECT_NEAR(luminance(render(s, 64, 64), 32, 32), 1.0f, 0.02f) << enumName(method);
        s.sampling.multiscatter = false;
        EXPECT_NEAR(luminance(render(s, 64, 64), 32, 32), singleScatter, 0.02) << enumName(method) << " without compensation";
    }
}

// The two forms of the compensation agree for a white metal and differ for a coloured one:
// a rough grey metal (F0 = 0.5) at n.v = 1 reflects (F0 A + B) (1 + F0 (1 / E_ss - 1)) with
// Filament's and Fdez-Aguera's F0 A + B + Fms E_ms (the glTF Sample Viewer's) with the
// other, each as the CPU core computes it from its own A and B at the LUT texel the centre
// pixel reads (n.v and roughness 1 both clamp to the last texel centre).
TEST_F(Material, FurnaceFollowsTheMultiscatterModel)
{
    bake("builtin:white?width=64");
    const double lastTexel = 1.0 - 0.5 / smallBake().lut.size;
    const glm::dvec3 ab = integrateSplitSumBrdf(lastTexel, lastTexel, 4096, GeometryTerm::HeightCorrelatedSmith);
    const glm::dvec3 F0(0.5);
    const double filament = ((F0 * ab.x + ab.y) * specularEnergyCompensation(F0, ab.z)).x;
    const double fdezAguera = fdezAgueraSpecularAlbedo(F0, ab.x, ab.y).x;
    // E_ss is about 0.3 here, and the forms differ by a third.
    ASSERT_GT(std::abs(filament / fdezAguera - 1.0), 0.1) << "the forms must differ here for the test to tell them apart";
    for (MultiscatterModel model : {MultiscatterModel::Filament, MultiscatterModel::FdezAguera}) {
        FrameSettings s;
        s.scene.kind = SceneKind::Sphere;
        s.material = {true, glm::vec3(0.5f), 1.0f, 1.0f, 1.0f, 0.5f};
        s.sampling.method = ShadingMethod::SplitSum;
        s.sampling.multiscatterModel = model;
        s.camera.distance = 0.0f;
        const double expected = model == MultiscatterModel::Filament ? filament : fdezAguera;
        // 0.5%: the LUT's half floats and its 2048 samples against the CPU's 4096.
        EXPECT_NEAR(luminance(render(s, 64, 64), 32, 32) / expected, 1.0, 0.005) << enumName(model);
    }
}

// Dividing by the samples above the horizon instead of by N can only raise the estimate,
// and at roughness 1, where many half-vectors reflect below the horizon near the
// silhouette, it must raise it visibly.
TEST_F(Material, NormalizingByAcceptedSamplesBrightensGrazingAngles)
{
    bake("builtin:white?width=64");
    FrameSettings s;
    s.scene.kind = SceneKind::Sphere;
    s.material = {true, glm::vec3(1.0f), 1.0f, 1.0f, 1.0f, 0.5f};
    s.sampling.method = ShadingMethod::Sampled;
    s.sampling.samples = 64;
    s.camera.distance = 0.0f;
    const FrameReadback unbiased = render(s, 48, 48);
    s.sampling.normalizeByAccepted = true;
    const FrameReadback accepted = render(s, 48, 48);
    double gain = 0.0;
    for (std::size_t i = 0; i < unbiased.rgba.size(); i += 4) {
        ASSERT_GE(accepted.rgba[i] + 1e-3f, unbiased.rgba[i]) << "pixel " << i / 4;
        gain += double(accepted.rgba[i]) - double(unbiased.rgba[i]);
    }
    // More than 1% of the frame's pixels' worth of radiance: a switch that changed nothing
    // (or only rounding) would fail here.
    EXPECT_GT(gain, 0.01 * double(unbiased.rgba.size() / 4));
}

double meanAbsoluteDifference(const FrameReadback& a, const FrameReadback& b)
{
    double sum = 0.0;
    for (std::size_t i = 0; i < a.rgba.size(); i += 4) sum += std::abs(double(a.rgba[i]) - double(b.rgba[i]));
    return sum / double(a.rgba.size() / 4);
}

// Progressive refinement: 16 accumulated frames of N = 4 (rotated sample sets) must be much
// closer to a converged N = 512 image than one frame of N = 4. Independent sets average
// the error down roughly as 1/sqrt(16) = 1/4; 1/2 leaves margin for the correlation
// between rotated Hammersley sets.
TEST_F(Material, AccumulationConverges)
{
    bake("builtin:studio?width=256");
    FrameSettings s;
    s.scene.kind = SceneKind::Sphere;
    s.material = {true, glm::vec3(0.9f), 1.0f, 0.4f, 1.0f, 0.5f};
    s.sampling.method = ShadingMethod::Sampled;
    // PDF mip filtering picks blurrier source mips for smaller N, so N = 4 converges to a
    // different (blurrier) image than N = 512; reading mip 0 makes both estimate the same.
    s.sampling.pdfMipFiltering = false;
    s.camera.distance = 0.0f;
    s.sampling.samples = 512;
    const FrameReadback reference = render(s, 48, 48);
    s.sampling.samples = 4;
    const FrameReadback single = render(s, 48, 48);
    for (int i = 0; i < 16; ++i) renderer().renderFrame(s, 48, 48, Renderer::Options{1.0f, true});
    EXPECT_EQ(renderer().accumulatedFrames(), 16);
    const FrameReadback accumulated = renderer().readHdrFrame();
    const double errorSingle = meanAbsoluteDifference(single, reference);
    const double errorAccumulated = meanAbsoluteDifference(accumulated, reference);
    EXPECT_GT(errorSingle, 0.0);
    EXPECT_LT(errorAccumulated, 0.5 * errorSingle) << "single " << errorSingle << ", accumulated " << errorAccumulated;
}

// Reduced resolution renders fewer pixels; the display image has the reduced size.
TEST_F(Material, ResolutionScaleRendersFewerPixels)
{
    bake("builtin:sky?width=64");
    FrameSettings s;
    s.camera.distance = 3.0f;
    renderer().renderFrame(s, 200, 100, Renderer::Options{0.5f, false});
    const FrameReadback frame = renderer().readHdrFrame();
    EXPECT_EQ(frame.width, 100);
    EXPECT_EQ(frame.height, 50);
}

} // namespace
} // namespace iblab
