// The lab's harness (renderer/lab/harness): the reference it keeps is the reference of the
// settings it was last advanced with. A frame of another BRDF must never be measured against
// the previous BRDF's reference (the conventions command compares four BRDFs on one map).
#include <chrono>

#include "frame/renderer.hpp"
#include "gl_test_fixture.hpp"
#include "lab/harness.hpp"

namespace iblab {
namespace {

using testing::GlTest;

class Harness : public GlTest {};

TEST_F(Harness, ReferenceFollowsTheBrdfItWasAdvancedWith)
{
    Renderer renderer(shaderDirectory());
    lab::Harness harness(renderer);
    harness.loadEnvironment("builtin:studio?width=64");
    bake::BakeSettings bakeSettings;
    bakeSettings.prefilter.faceSize = 32;
    harness.bake(bakeSettings);

    FrameSettings frame;
    frame.scene.kind = SceneKind::Sphere;
    frame.material.roughness = 0.5f;
    frame.view.referenceWidth = 64;
    constexpr int kSize = 32;
    auto complete = [&](const FrameSettings& settings) {
        const ReferenceStatus status = harness.advanceReference(settings, kSize, kSize, std::chrono::hours(1));
        EXPECT_TRUE(status.complete);
        return status;
    };

    frame.sampling.geometry = GeometryTerm::HeightCorrelatedSmith;
    const ReferenceStatus first = complete(frame);
    ASSERT_TRUE(harness.reference().complete());
    const FrameReadback correlated = harness.reference().frame;

    // The same settings again: the same reference, not read back or summed again.
    const double summedFor = harness.reference().milliseconds;
    EXPECT_EQ(complete(frame).run, first.run);
    EXPECT_EQ(harness.reference().frame.rgba, correlated.rgba);
    EXPECT_GE(harness.reference().milliseconds, summedFor);

    // Another geometry term: another integral, and the harness's copy follows it.
    frame.sampling.geometry = GeometryTerm::SchlickGGX;
    const ReferenceStatus second = complete(frame);
    EXPECT_NE(second.run, first.run);
    ASSERT_TRUE(harness.reference().complete());
    EXPECT_EQ(harness.reference().run, second.run);
    EXPECT_EQ(harness.reference().frame.rgba, renderer.readReferenceFrame().rgba);
    EXPECT_NE(harness.reference().frame.rgba, correlated.rgba) << "Schlick-GGX and height-correlated Smith give other integrals";
}

} // namespace
} // namespace iblab
