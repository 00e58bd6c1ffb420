// The reference renderer against the CPU's exact integrals (renderer/ibl/reference.hpp) at
// sample pixels, the white furnace, independence from the slicing, and the two views built
// on it: the error heatmap and the A/B split.
#include <chrono>
#include <cmath>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "bake/bake_job.hpp"
#include "bake_test_support.hpp"
#include "frame/camera.hpp"
#include "io/environment.hpp"
#include "ibl/equirect.hpp"
#include "ibl/error_metrics.hpp"
#include "ibl/reference.hpp"
#include "ibl/tonemap.hpp"
#include "reference_test_support.hpp"

namespace iblab {
namespace {

using testing::kSamplePixels;
using testing::pixelOf;
constexpr int kSize = testing::kReferenceFrameSize;
using Reference = testing::ReferenceTest;

// Every term of the shading model (pbr.frag's combineLobes) from the CPU references, with
// the surface (N, V, material) the mesh pass left in the G-buffer.
TEST_F(Reference, MatchesTheCpuIntegralsAtSamplePixels)
{
    const ImageRGB32F loaded = load("builtin:studio?width=128");
    const ImageRGB32F env = downsampleEquirect2x(loaded); // 64 x 32: what referenceWidth 64 sums over
    const ImageRGB32F white = paintEquirect(env.width, env.height, [](glm::dvec3) { return glm::vec3(1.0f); });
    // 0: single scattering; 1 and 2: each form of the compensation, against the CPU's.
    for (const int compensation : {0, 1, 2}) {
        const bool variant = compensation > 0;
        FrameSettings s = sphere(glm::vec3(0.8f, 0.5f, 0.3f), 0.5f, 0.6f);
        s.environment.yawDegrees = variant ? 40.0f : 0.0f;
        s.environment.intensityEv = variant ? 0.5f : 0.0f;
        s.sampling.geometry = variant ? GeometryTerm::SchlickGGX : GeometryTerm::HeightCorrelatedSmith;
        s.sampling.multiscatter = variant;
        s.sampling.multiscatterModel = compensation == 2 ? MultiscatterModel::FdezAguera : MultiscatterModel::Filament;
        const FrameReadback frame = reference(s);
        const FrameReadback normals = renderer().readReferenceLayer(ReferenceLayer::Normal);
        const FrameReadback views = renderer().readReferenceLayer(ReferenceLayer::View);
        for (const glm::ivec2 p : kSamplePixels) {
            ASSERT_EQ(pixelOf(normals, p.x, p.y).w, 1.0f) << "pixel " << p.x << "," << p.y << " is not on the sphere";
            const glm::dvec3 expected = testing::cpuReferencePixel(env, white, s, testing::surfaceAt(normals, views, p));
            const glm::vec4 got = pixelOf(frame, p.x, p.y);
            for (int c = 0; c < 3; ++c)
                // 1e-4 relative: the GPU sums 2048 texels in float (float directions and
                // solid angles) where the CPU uses double; both see the same texels, so
                // only rounding separates them (measured below 1e-5).
                EXPECT_NEAR(got[c], expected[c], 1e-4 * expected[c]) << "pixel " << p.x << "," << p.y << " channel " << c << " compensation " << compensation;
        }
    }
}

// In a uniform environment of radiance 1, a white metal with energy compensation reflects
// exactly 1 everywhere: the compensation divides by the very single-scattering albedo the
// reference sums alongside. Without it, a white dielectric's diffuse layer is
// kD E / pi = kD (E = pi up to the midpoint rule) on top of its specular reflection.
TEST_F(Reference, WhiteFurnace)
{
    const ImageRGB32F white = load("builtin:white?width=64");
    for (const float roughness : {0.3f, 0.8f}) {
        FrameSettings metal = sphere(glm::vec3(1.0f), 1.0f, roughness);
        metal.sampling.multiscatter = true;
        const FrameReadback frame = reference(metal);
        const FrameReadback normals = renderer().readReferenceLayer(ReferenceLayer::Normal);
        int surface = 0;
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                if (pixelOf(normals, x, y).w == 0.0f) continue;
                ++surface;
                ASSERT_NEAR(pixelOf(frame, x, y).g, 1.0f, 1e-4f) << "pixel " << x << "," << y << " roughness " << roughness;
            }
        EXPECT_GT(surface, 500);
    }

    FrameSettings dielectric = sphere(glm::vec3(1.0f), 0.0f, 0.5f);
    dielectric.sampling.multiscatter = false; // the single-scattering layers, checked term by term
    const FrameReadback frame = reference(dielectric);
    const FrameReadback normals = renderer().readReferenceLayer(ReferenceLayer::Normal);
    const glm::dvec3 n = glm::normalize(glm::dvec3(glm::vec3(pixelOf(normals, 24, 24))));
    const glm::dvec3 v = glm::normalize(glm::dvec3(glm::vec3(pixelOf(renderer().readReferenceLayer(ReferenceLayer::View), 24, 24))));
    const double F0 = 0.04;
    const double specular = referenceSpecular(white, n, v, 0.5, glm::dvec3(F0), GeometryTerm::HeightCorrelatedSmith).x;
    const double kD = 1.0 - fresnelSchlickRoughness(glm::dot(n, v), glm::dvec3(F0), 0.5).x;
    // 2e-3: E / pi of a white map is 1 only up to the midpoint rule's error on the cosine
    // lobe with 64 x 32 texels.
    EXPECT_NEAR(pixelOf(frame, 24, 24).g - specular, kD, 2e-3);
}

// Slicing decides when the work happens, never the result: every pixel adds the rows in
// the same order whatever the tile and band sizes.
TEST_F(Reference, DoesNotDependOnTheSlicing)
{
    load("builtin:studio?width=128");
    const FrameSettings s = sphere(glm::vec3(0.9f, 0.6f, 0.4f), 0.3f, 0.5f);
    const FrameReadback whole = reference(s, {64, 0});
    const FrameReadback small = reference(s, {8, 1});
    const FrameReadback odd = reference(s, {5, 3}); // tiles that do not divide the frame
    ASSERT_GT(pixelOf(whole, 24, 24).g, 0.01f) << "a lit sphere at the centre";
    for (std::size_t i = 0; i < whole.rgba.size(); ++i) {
        ASSERT_NEAR(small.rgba[i], whole.rgba[i], 1e-6f * std::abs(whole.rgba[i])) << "float " << i;
        ASSERT_NEAR(odd.rgba[i], whole.rgba[i], 1e-6f * std::abs(whole.rgba[i])) << "float " << i;
    }
}

// A zero budget starts the reference without integrating; small budgets advance it slice
// by slice, with progress rising to completion.
TEST_F(Reference, AdvancesInBudgetedSlices)
{
    load("builtin:studio?width=128");
    const FrameSettings s = sphere(glm::vec3(0.5f), 0.0f, 0.5f);
    const ReferenceSlicing slicing{16, 4};
    ReferenceStatus status = renderer().advanceReference(s, kSize, kSize, std::chrono::seconds(0), slicing);
    EXPECT_TRUE(status.current);
    EXPECT_FALSE(status.complete);
    EXPECT_EQ(status.progress, 0.0f);
    EXPECT_EQ(status.environmentWidth, 64);
    int calls = 0;
    float previous = 0.0f;
    while (!status.complete && calls < 10000) {
        status = renderer().advanceReference(s, kSize, kSize, std::chrono::microseconds(1), slicing);
        EXPECT_GE(status.progress, previous);
        previous = status.progress;
        ++calls;
    }
    EXPECT_TRUE(status.complete);
    EXPECT_GT(calls, 2);
    // Changing the material makes it a different reference.
    FrameSettings other = s;
    other.material.roughness = 0.7f;
    EXPECT_FALSE(renderer().referenceStatus(other, kSize, kSize).current);
    // The tone map does not change the reference.
    other = s;
    other.toneMap.exposureEv = 3.0f;
    EXPECT_TRUE(renderer().referenceStatus(other, kSize, kSize).complete);
}

// The heatmap's pixels are falseColour(relativeError / scale) of the frame and the
// reference, as the C++ side of error_metrics.glsl computes it; the background is grey.
TEST_F(Reference, ErrorViewShowsTheRelativeErrorInFalseColour)
{
    load("builtin:studio?width=128");
    FrameSettings s = sphere(glm::vec3(0.9f, 0.6f, 0.4f), 1.0f, 0.4f);
    s.view.mode = ViewMode::Error;
    s.view.errorScale = 0.2f;
    for (const ErrorSpace space : {ErrorSpace::Linear, ErrorSpace::Display}) {
        s.view.errorSpace = space;
        reference(s);
        renderer().renderFrame(s, kSize, kSize);
        const FrameReadback frame = renderer().readHdrFrame();
        const FrameReadback ref = renderer().readReferenceFrame();
        const DisplayReadback shown = renderer().readDisplayImage();
        for (const glm::ivec2 p : kSamplePixels) {
            glm::vec3 value(pixelOf(frame, p.x, p.y)), expected(pixelOf(ref, p.x, p.y));
            if (space == ErrorSpace::Display) {
                value = displayEncode(value, s.toneMap.exposureEv, s.toneMap.op);
                expected = displayEncode(expected, s.toneMap.exposureEv, s.toneMap.op);
            }
            const glm::vec3 colour = falseColour(relativeError(value, expected) / s.view.errorScale);
            for (int c = 0; c < 3; ++c)
                // 2/255: 8-bit rounding, and a half-float frame read back as float on both sides.
                EXPECT_NEAR(float(shown.rgba[(std::size_t(p.y) * kSize + std::size_t(p.x)) * 4 + std::size_t(c)]) / 255.0f, colour[c], 2.0f / 255.0f)
                    << enumName(space) << " pixel " << p.x << "," << p.y;
        }
        const std::uint8_t* corner = &shown.rgba[0];
        EXPECT_EQ(corner[0], corner[1]);
        EXPECT_EQ(corner[1], corner[2]);
        const ErrorReport report = renderer().measureError(s);
        ASSERT_TRUE(report.valid);
        EXPECT_GT(report.left.pixels, 500u);
        EXPECT_GT(report.left.relativeRmse, 0.0);
        EXPECT_FALSE(report.right);
    }
    // A frame of other settings is not compared against this reference.
    FrameSettings other = s;
    other.material.roughness = 0.9f;
    renderer().renderFrame(other, kSize, kSize);
    EXPECT_FALSE(renderer().measureError(other).valid);
}

// Left of the divider the split frame is A's frame, from it on B's, pixel for pixel; and
// the two differ there, or the test would prove nothing.
TEST_F(Reference, SplitViewShowsAOnTheLeftAndBOnTheRight)
{
    load("builtin:studio?width=128");
    FrameSettings a = sphere(glm::vec3(0.9f, 0.6f, 0.4f), 1.0f, 0.4f);
    a.sampling.method = ShadingMethod::SplitSum;
    FrameSettings b = a;
    b.sampling.method = ShadingMethod::Sampled;
    b.sampling.samples = 1;
    FrameSettings split = a;
    split.view.split = true;
    split.view.splitPosition = 0.5f;
    split.view.compare = b.sampling;
    renderer().renderFrame(a, kSize, kSize);
    const FrameReadback left = renderer().readHdrFrame();
    renderer().renderFrame(b, kSize, kSize);
    const FrameReadback right = renderer().readHdrFrame();
    renderer().renderFrame(split, kSize, kSize);
    const FrameReadback both = renderer().readHdrFrame();
    const int divider = splitColumn(split.view, kSize);
    ASSERT_EQ(divider, kSize / 2);
    int differing = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const glm::vec4 expected = pixelOf(x < divider ? left : right, x, y);
            ASSERT_EQ(pixelOf(both, x, y), expected) << "pixel " << x << "," << y;
            differing += x >= divider && glm::any(glm::greaterThan(glm::abs(pixelOf(left, x, y) - pixelOf(right, x, y)), glm::vec4(1e-3f)));
        }
    EXPECT_GT(differing, 50);

    // The error view measures each side against the same reference.
    split.view.mode = ViewMode::Error;
    reference(split);
    renderer().renderFrame(split, kSize, kSize);
    const ErrorReport report = renderer().measureError(split);
    ASSERT_TRUE(report.valid);
    ASSERT_TRUE(report.right);
    EXPECT_GT(report.left.pixels, 200u);
    EXPECT_GT(report.right->pixels, 200u);
}

} // namespace
} // namespace iblab
