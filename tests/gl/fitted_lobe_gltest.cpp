// The fitted lobe as the mesh pass shades it (ShadingMethod::FittedLobe, issue #14): closer
// than the split sum to the CPU's full integral on a map of this test's own, which the fit
// never saw, and exactly as energy-neutral in the white furnace. Its table is the CPU core's
// fittedLobeTable() and its formulas common/specular_lobe.glsl, the study's own.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "bake/bake_job.hpp"
#include "frame/camera.hpp"
#include "ibl/equirect.hpp"
#include "ibl/error_metrics.hpp"
#include "ibl/reference.hpp"
#include "ibl/specular_approximations.hpp"
#include "lobe_test_environment.hpp"
#include "io/environment.hpp"
#include "renderer_fixture.hpp"

namespace iblab {
namespace {

constexpr int kSize = 64; // frame width and height: a sphere of about 1600 surface pixels

// The map of this test's own (testing::lobeTestEnvironment).
ImageRGB32F testEnvironment(int width) { return testing::lobeTestEnvironment(width); }

// The default preset's prefilter layout (6 quadratic mips, which the table was fitted on)
// and LUT, on faces small enough for llvmpipe; no irradiance cube (the spheres are metal).
bake::BakeSettings lobeBake()
{
    bake::BakeSettings s = bake::defaultPreset();
    s.irradiance = bake::IrradianceMethod::None;
    s.cube.maxFaceSize = 128;
    s.prefilter.faceSize = 64;
    s.prefilter.samples = 256;
    s.lut.schlickGgx = false;
    return s;
}

glm::vec4 pixelOf(const FrameReadback& f, int x, int y) { return glm::make_vec4(&f.rgba[(std::size_t(y) * std::size_t(f.width) + std::size_t(x)) * 4]); }

class FittedLobe : public testing::RendererTest {
protected:
    void light(const ImageRGB32F& image)
    {
        Environment environment;
        environment.source = "fitted-lobe-test";
        environment.image = image;
        environment.contentHash = contentHash(image);
        renderer().setEnvironment(image);
        bake::BakeJob job(renderer().shaders(), environment, lobeBake());
        renderer().setBake(std::make_shared<bake::BakeResult>(job.runToCompletion()));
    }
    static FrameSettings sphere(ShadingMethod method, glm::vec3 baseColor, float roughness)
    {
        FrameSettings s;
        s.scene.kind = SceneKind::Sphere;
        s.material = {true, baseColor, 1.0f, roughness, 1.0f, 0.5f};
        s.sampling.method = method;
        s.view.msaaSamples = 1; // each pixel shaded at its centre, where the G-buffer's N and V are
        frameBox(s.camera, glm::vec3(0.0f), glm::vec3(1.0f), 1.0f);
        return s;
    }
    FrameReadback render(const FrameSettings& s)
    {
        renderer().renderFrame(s, kSize, kSize);
        return renderer().readHdrFrame();
    }
    // Every `step`-th sphere pixel each way (the rim included) with the G-buffer's N and V
    // there: the reference renderer's own, over a tiny map.
    struct SurfacePixel {
        int x, y;
        glm::dvec3 n, v;
    };
    std::vector<SurfacePixel> surfacePixels(FrameSettings s, int step)
    {
        s.view.referenceWidth = 8;
        EXPECT_TRUE(renderer().advanceReference(s, kSize, kSize, std::chrono::hours(1)).complete);
        const FrameReadback normals = renderer().readReferenceLayer(ReferenceLayer::Normal);
        const FrameReadback views = renderer().readReferenceLayer(ReferenceLayer::View);
        std::vector<SurfacePixel> pixels;
        for (int y = 1; y < kSize; y += step)
            for (int x = 1; x < kSize; x += step)
                if (pixelOf(normals, x, y).w != 0.0f)
                    pixels.push_back({x, y, glm::normalize(glm::dvec3(glm::vec3(pixelOf(normals, x, y)))),
                                      glm::normalize(glm::dvec3(glm::vec3(pixelOf(views, x, y))))});
        return pixels;
    }
};

TEST_F(FittedLobe, CloserToTheCpuFullIntegralThanTheSplitSum)
{
    const ImageRGB32F env = testEnvironment(128);
    light(env);
    const ReferenceSums sums(env);
    const glm::dvec3 F0(0.95, 0.64, 0.54); // copper: metallic 1, F0 = base colour
    double splitSquares = 0.0, fittedSquares = 0.0;
    int pixels = 0;
    // Roughness the 128-wide map resolves (>= 0.27, referenceMinResolvedRoughness).
    for (const float roughness : {0.3f, 0.5f, 0.8f}) {
        FrameSettings s = sphere(ShadingMethod::SplitSum, glm::vec3(F0), roughness);
        // The lobe's reads against the single-scattering integral `full` below: without the
        // compensation (on by default), which would scale both frames but not `full`.
        s.sampling.multiscatter = false;
        const std::vector<SurfacePixel> surface = surfacePixels(s, 3);
        const FrameReadback split = render(s);
        s.sampling.method = ShadingMethod::FittedLobe;
        const FrameReadback fitted = render(s);
        for (const SurfacePixel& p : surface) {
            const glm::vec3 full(sums.evaluate(p.n, p.v, roughness, s.sampling.geometry, false).specular(F0));
            const double splitError = relativeError(glm::vec3(pixelOf(split, p.x, p.y)), full);
            const double fittedError = relativeError(glm::vec3(pixelOf(fitted, p.x, p.y)), full);
            splitSquares += splitError * splitError;
            fittedSquares += fittedError * fittedError;
            ++pixels;
        }
    }
    ASSERT_GT(pixels, 300);
    const double splitRmse = std::sqrt(splitSquares / pixels), fittedRmse = std::sqrt(fittedSquares / pixels);
    std::printf("GPU, %d sphere pixels: relative RMSE fitted lobe %.3f, split sum %.3f (%.2fx)\n", pixels, fittedRmse, splitRmse, fittedRmse / splitRmse);
    // Measured on llvmpipe with the committed table: fitted 0.133, split sum 0.533 over 525
    // pixels (0.25x; the CPU study's emulation of the same map gives 0.21x). The study's bar
    // is half the split sum's.
    EXPECT_LT(fittedRmse, 0.5 * splitRmse) << "fitted " << fittedRmse << " split sum " << splitRmse;
}

// A 0.5 degree sun of 1e4 over a dim sky: the light dominates every highlight, and no read of
// the prefiltered cube has its shape (ibl/shading_lights.hpp). With the bake's shading lights
// summed exactly the fitted lobe is several times closer to the full integral than without,
// and well inside half the split sum's error.
TEST_F(FittedLobe, ShadingLightsMakeASunExact)
{
    const ImageRGB32F env = loadEnvironment("builtin:sun?width=512&size=0.5&intensity=1e4&sky=0.2&elevation=35&azimuth=30").image;
    light(env);
    const ReferenceSums sums(downsampleEquirectToWidth(env, 256));
    const glm::dvec3 F0(0.95, 0.64, 0.54);
    double squares[3] = {0.0, 0.0, 0.0}; // split sum, fitted lobe without lights, with
    int pixels = 0;
    for (const float roughness : {0.3f, 0.5f}) {
        FrameSettings s = sphere(ShadingMethod::SplitSum, glm::vec3(F0), roughness);
        s.sampling.multiscatter = false;
        const std::vector<SurfacePixel> surface = surfacePixels(s, 2);
        FrameReadback frames[3];
        frames[0] = render(s);
        s.sampling.method = ShadingMethod::FittedLobe;
        s.sampling.shadingLights = false;
        frames[1] = render(s);
        s.sampling.shadingLights = true;
        frames[2] = render(s);
        for (const SurfacePixel& p : surface) {
            const glm::vec3 full(sums.evaluate(p.n, p.v, roughness, s.sampling.geometry, false).specular(F0));
            for (int m = 0; m < 3; ++m) {
                const double e = relativeError(glm::vec3(pixelOf(frames[m], p.x, p.y)), full);
                squares[m] += e * e;
            }
            ++pixels;
        }
    }
    ASSERT_GT(pixels, 500);
    const double split = std::sqrt(squares[0] / pixels), without = std::sqrt(squares[1] / pixels), with = std::sqrt(squares[2] / pixels);
    std::printf("GPU, %d sphere pixels: relative RMSE split sum %.3f, fitted lobe %.3f, with shading lights %.3f\n", pixels, split, without, with);
    EXPECT_LT(with, 0.5 * without) << "split sum " << split << " fitted lobe " << without << " with lights " << with;
    EXPECT_LT(with, 0.2 * split) << "split sum " << split << " with lights " << with;
}

// In a uniform environment every read of the prefiltered cube returns its radiance, so the
// fitted lobe's two reads carry F0 A and B exactly as the split sum's one read does: with
// the multiple-scattering compensation a white metal reflects what the split sum reflects
// (1, up to the LUT's precision), within 0.1% at every surface pixel.
TEST_F(FittedLobe, WhiteFurnaceWithCompensationMatchesTheSplitSum)
{
    light(loadEnvironment("builtin:white?width=64").image);
    for (const float roughness : {0.2f, 0.6f, 1.0f}) {
        FrameSettings s = sphere(ShadingMethod::SplitSum, glm::vec3(1.0f), roughness);
        s.sampling.multiscatter = true;
        const FrameReadback split = render(s);
        s.sampling.method = ShadingMethod::FittedLobe;
        const FrameReadback fitted = render(s);
        int surface = 0;
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                const glm::vec4 a = pixelOf(split, x, y), b = pixelOf(fitted, x, y);
                if (a.w == 0.0f) continue;
                ++surface;
                for (int c = 0; c < 3; ++c) ASSERT_NEAR(b[c], a[c], 1e-3f * a[c]) << "pixel " << x << "," << y << " roughness " << roughness;
            }
        EXPECT_GT(surface, 1000);
        // The centre sees the sphere face-on; 2%: the LUT's half floats (material_gltest).
        EXPECT_NEAR(pixelOf(fitted, kSize / 2, kSize / 2).g, 1.0f, 0.02f) << "roughness " << roughness;
    }
}

} // namespace
} // namespace iblab
