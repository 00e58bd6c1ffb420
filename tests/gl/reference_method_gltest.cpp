// ShadingMethod::Reference: the frame shows the reference renderer's full integral, equal
// to the CPU's exact integrals at sample pixels; while the reference runs, its finished
// tiles over the split-sum preview; on either side of the A/B split; and a changed setting
// starts it over.
#include <chrono>
#include <cmath>
#include <string>

#include <glm/glm.hpp>

#include "frame/split_view.hpp"
#include "ibl/equirect.hpp"
#include "reference_test_support.hpp"

namespace iblab {
namespace {

using testing::kSamplePixels;
using testing::pixelOf;
constexpr int kSize = testing::kReferenceFrameSize;

// The frame is RGBA16F: a copy of the RGBA32F reference into it rounds each value to 11
// significant bits, 2^-11 = 4.9e-4 relative at most; 1e-3 leaves room for the GPU's own
// float sums (below 1e-5, reference_gltest).
constexpr float kHalfFloatRelative = 1e-3f;

bool nearRelative(glm::vec4 got, glm::vec4 expected, float relative)
{
    for (int c = 0; c < 4; ++c)
        if (std::abs(got[c] - expected[c]) > relative * std::abs(expected[c]) + 1e-6f) return false;
    return true;
}

class ReferenceMethod : public testing::ReferenceTest {
protected:
    static FrameSettings referenceSphere()
    {
        FrameSettings s = sphere(glm::vec3(0.8f, 0.5f, 0.3f), 0.5f, 0.6f);
        s.sampling.method = ShadingMethod::Reference;
        return s;
    }
    static FrameSettings withMethod(FrameSettings s, ShadingMethod method)
    {
        s.sampling.method = method;
        return s;
    }
    FrameReadback render(const FrameSettings& s, bool accumulate = false)
    {
        renderer().renderFrame(s, kSize, kSize, Renderer::Options{1.0f, accumulate});
        return renderer().readHdrFrame();
    }
};

// The frame of the reference method is the full integral: at sample pixels, what the CPU
// integrates over the same texels; and not what the split sum shows there, or the frame
// could be the preview and pass.
TEST_F(ReferenceMethod, ShowsTheCpuIntegralAtSamplePixels)
{
    const ImageRGB32F env = downsampleEquirect2x(load("builtin:studio?width=128")); // 64 x 32: what referenceWidth 64 sums over
    const ImageRGB32F white = paintEquirect(env.width, env.height, [](glm::dvec3) { return glm::vec3(1.0f); });
    const FrameSettings s = referenceSphere();
    ASSERT_TRUE(renderer().advanceReference(s, kSize, kSize, std::chrono::hours(1)).complete);
    const FrameReadback frame = render(s);
    const FrameReadback splitSum = render(withMethod(s, ShadingMethod::SplitSum));
    const FrameReadback normals = renderer().readReferenceLayer(ReferenceLayer::Normal);
    const FrameReadback views = renderer().readReferenceLayer(ReferenceLayer::View);
    int splitSumOff = 0;
    for (const glm::ivec2 p : kSamplePixels) {
        ASSERT_EQ(pixelOf(normals, p.x, p.y).w, 1.0f) << "pixel " << p.x << "," << p.y << " is not on the sphere";
        const glm::dvec3 expected = testing::cpuReferencePixel(env, white, s, testing::surfaceAt(normals, views, p));
        const glm::vec4 got = pixelOf(frame, p.x, p.y);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], kHalfFloatRelative * expected[c]) << "pixel " << p.x << "," << p.y << " channel " << c;
        EXPECT_EQ(got.w, 1.0f) << "coverage of a surface pixel";
        splitSumOff += !nearRelative(pixelOf(splitSum, p.x, p.y), glm::vec4(glm::vec3(expected), 1.0f), 0.01f);
    }
    EXPECT_GE(splitSumOff, 3) << "the split sum is more than 1% off the integral at most sample pixels of this rough half-metal";
}

// While the reference runs, each pixel shows either the split-sum preview or its final
// reference value, and both occur; a running mean waits until the reference is complete,
// since the side changes as tiles finish.
TEST_F(ReferenceMethod, ShowsFinishedTilesOverTheSplitSumPreview)
{
    load("builtin:studio?width=128");
    const FrameSettings s = referenceSphere();
    const FrameReadback preview = render(withMethod(s, ShadingMethod::SplitSum));
    const ReferenceSlicing slicing{16, 4}; // 9 tiles of 16 x 16 pixels, 8 bands of rows each
    ReferenceStatus status = renderer().advanceReference(s, kSize, kSize, std::chrono::seconds(0), slicing);
    for (int calls = 0; status.progress < 0.5f && calls < 1000; ++calls)
        status = renderer().advanceReference(s, kSize, kSize, std::chrono::microseconds(1), slicing);
    ASSERT_FALSE(status.complete);
    const FrameReadback partial = render(s, /*accumulate=*/true);
    render(s, /*accumulate=*/true);
    EXPECT_EQ(renderer().accumulatedFrames(), 1) << "no running mean of an unfinished reference";

    status = renderer().advanceReference(s, kSize, kSize, std::chrono::hours(1), slicing);
    ASSERT_TRUE(status.complete);
    const FrameReadback reference = renderer().readReferenceFrame();
    int fromPreview = 0, fromReference = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const glm::vec4 got = pixelOf(partial, x, y), early = pixelOf(preview, x, y), final = pixelOf(reference, x, y);
            if (nearRelative(early, final, 0.01f)) continue; // the two cannot be told apart here
            const bool isPreview = got == early, isReference = nearRelative(got, final, kHalfFloatRelative);
            ASSERT_TRUE(isPreview || isReference) << "pixel " << x << "," << y << " is neither the preview nor the reference";
            fromPreview += isPreview;
            fromReference += isReference;
        }
    EXPECT_GT(fromPreview, 50) << "unfinished tiles show the split sum";
    EXPECT_GT(fromReference, 50) << "finished tiles show the reference";
    render(s, /*accumulate=*/true);
    render(s, /*accumulate=*/true);
    EXPECT_EQ(renderer().accumulatedFrames(), 2) << "a complete reference accumulates like any frame";
}

// Either side of the split can be the reference: that side's columns show its reference,
// the other side's columns its own method, pixel for pixel.
TEST_F(ReferenceMethod, IsEitherSideOfTheSplit)
{
    load("builtin:studio?width=128");
    const FrameSettings reference = referenceSphere();
    FrameSettings sampled = withMethod(reference, ShadingMethod::Sampled);
    sampled.sampling.samples = 1;
    for (const bool referenceOnTheLeft : {true, false}) {
        const FrameSettings& a = referenceOnTheLeft ? reference : sampled;
        const FrameSettings& b = referenceOnTheLeft ? sampled : reference;
        FrameSettings split = a;
        split.view.split = true;
        split.view.splitPosition = 0.5f;
        split.view.compare = b.sampling;
        ASSERT_TRUE(renderer().advanceReference(split, kSize, kSize, std::chrono::hours(1)).complete);
        const FrameReadback referenceFrame = renderer().readReferenceFrame();
        const FrameReadback other = render(sampled);
        const FrameReadback both = render(split);
        const int divider = splitColumn(split.view, kSize);
        ASSERT_EQ(divider, kSize / 2);
        int differing = 0;
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                const bool referenceSide = (x < divider) == referenceOnTheLeft;
                const glm::vec4 got = pixelOf(both, x, y);
                if (referenceSide)
                    ASSERT_TRUE(nearRelative(got, pixelOf(referenceFrame, x, y), kHalfFloatRelative)) << "pixel " << x << "," << y;
                else
                    ASSERT_EQ(got, pixelOf(other, x, y)) << "pixel " << x << "," << y;
                differing += referenceSide && !nearRelative(pixelOf(referenceFrame, x, y), pixelOf(other, x, y), 0.01f);
            }
        EXPECT_GT(differing, 50) << "the reference and one sample per pixel must differ for this to prove anything";
    }
}

// A changed material is another reference: the frame falls back to the split-sum preview
// until the new one is advanced, which then differs from the old.
TEST_F(ReferenceMethod, ASettingChangeStartsItOver)
{
    load("builtin:studio?width=128");
    const FrameSettings s = referenceSphere();
    ASSERT_TRUE(renderer().advanceReference(s, kSize, kSize, std::chrono::hours(1)).complete);
    const FrameReadback first = render(s);
    FrameSettings rougher = s;
    rougher.material.roughness = 0.9f;
    EXPECT_FALSE(renderer().referenceStatus(rougher, kSize, kSize).current);
    const FrameReadback preview = render(withMethod(rougher, ShadingMethod::SplitSum));
    const FrameReadback stale = render(rougher);
    EXPECT_EQ(stale.rgba, preview.rgba) << "the old reference never shows for new settings";
    ASSERT_TRUE(renderer().advanceReference(rougher, kSize, kSize, std::chrono::hours(1)).complete);
    const FrameReadback second = render(rougher);
    const glm::ivec2 centre = kSamplePixels[0];
    EXPECT_FALSE(nearRelative(pixelOf(second, centre.x, centre.y), pixelOf(first, centre.x, centre.y), 0.01f));
    EXPECT_TRUE(nearRelative(pixelOf(second, centre.x, centre.y), pixelOf(renderer().readReferenceFrame(), centre.x, centre.y), kHalfFloatRelative));
}

// Another environment's bake set before its pixels (the session shows a bake read from the
// cache while the file still decodes): the old map's finished tiles, lit by the old sky,
// never show over the new view (issue 30, item 4.5); the frame is the new bake's preview.
TEST_F(ReferenceMethod, AnotherEnvironmentsBakeDropsTheFinishedTiles)
{
    load("builtin:studio?width=128");
    const FrameSettings s = referenceSphere();
    ASSERT_TRUE(renderer().advanceReference(s, kSize, kSize, std::chrono::hours(1)).complete);
    const FrameReadback old = render(s);
    const Environment sky = loadEnvironment("builtin:sky?width=128");
    bake::BakeJob job(renderer().shaders(), sky, testing::smallBakeSettings());
    renderer().setBake(std::make_shared<bake::BakeResult>(job.runToCompletion()));
    EXPECT_FALSE(renderer().referenceStatus(s, kSize, kSize).current);
    const FrameReadback preview = render(withMethod(s, ShadingMethod::SplitSum));
    const FrameReadback shown = render(s);
    EXPECT_NE(preview.rgba, old.rgba) << "the two maps must light the sphere differently for this to prove anything";
    EXPECT_EQ(shown.rgba, preview.rgba) << "no tile of the old map's reference over the new bake";
}

} // namespace
} // namespace iblab
