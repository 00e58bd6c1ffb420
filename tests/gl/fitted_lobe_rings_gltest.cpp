// Rough spheres under the fitted lobe have no rings. The lobe table is read bilinearly between
// its (n.v, roughness) cells; where neighbouring cells hold lobes from different minima of the
// fit, the reads between them belong to neither, and a sphere, whose n.v falls from 1 at its
// centre to 0 at its rim, shows concentric rings (docs/accuracy-study.md, "The fit"). Measured
// on the frame the renderer draws: the sphere's luminance averaged over rings one pixel wide
// around its centre, and how much that profile bends back, compared with the split sum's,
// which reads one lobe per roughness and has no table.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "frame/camera.hpp"
#include "renderer_fixture.hpp"

namespace iblab {
namespace {

constexpr int kSize = 128; // a sphere 45 pixels in radius: 2 pixels or more per table column of n.v >= 0.5

// The default bake's layout (6 quadratic mips, which the table was fitted on) on small faces.
bake::BakeSettings roughBake()
{
    bake::BakeSettings s = bake::defaultPreset();
    s.irradiance = bake::IrradianceMethod::None; // the spheres are metal
    s.cube.maxFaceSize = 128;
    s.prefilter.faceSize = 64;
    s.prefilter.samples = 256;
    return s;
}

// The sphere's mean luminance per ring of one pixel around the frame's centre (where frameBox
// puts the sphere's), out to the last ring whose pixels are all inside the silhouette.
std::vector<double> radialProfile(const FrameReadback& frame)
{
    std::vector<double> sum(kSize, 0.0), count(kSize, 0.0);
    std::vector<bool> whole(kSize, true);
    for (int y = 0; y < frame.height; ++y)
        for (int x = 0; x < frame.width; ++x) {
            const float* p = &frame.rgba[(std::size_t(y) * std::size_t(frame.width) + std::size_t(x)) * 4];
            const int ring = int(std::hypot(x + 0.5 - 0.5 * frame.width, y + 0.5 - 0.5 * frame.height));
            if (ring >= kSize) continue;
            if (p[3] < 1.0f) {
                whole[std::size_t(ring)] = false;
                continue;
            }
            sum[std::size_t(ring)] += 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
            count[std::size_t(ring)] += 1.0;
        }
    std::vector<double> profile;
    for (std::size_t r = 0; r < sum.size() && whole[r] && count[r] > 0.0; ++r) profile.push_back(sum[r] / count[r]);
    return profile;
}

// How much a profile bends back: its second differences summed without their signs, less
// their sum, over its mean. A profile that bends one way all along (the fall-off towards the
// rim, however steep) scores 0; each ring adds twice its bend.
double bendingBack(const std::vector<double>& profile)
{
    double bends = 0.0, net = 0.0, mean = 0.0;
    for (std::size_t i = 1; i + 1 < profile.size(); ++i) {
        const double bend = profile[i - 1] - 2.0 * profile[i] + profile[i + 1];
        bends += std::abs(bend);
        net += bend;
    }
    for (double v : profile) mean += v / double(profile.size());
    return (bends - std::abs(net)) / mean;
}

class FittedLobeRings : public testing::RendererTest {
protected:
    std::vector<double> profile(ShadingMethod method, float roughness)
    {
        FrameSettings s;
        s.scene.kind = SceneKind::Sphere;
        s.material = {true, glm::vec3(0.95f, 0.64f, 0.54f), 1.0f, roughness, 1.0f, 0.5f};
        s.sampling.method = method;
        frameBox(s.camera, glm::vec3(0.0f), glm::vec3(1.0f), 1.0f);
        renderer().renderFrame(s, kSize, kSize);
        return radialProfile(renderer().readHdrFrame());
    }
};

// Copper at roughness 0.82-0.98, where the table fitted cell by cell jumped between minima
// (steps of up to 1.5 in a read's direction between neighbouring cells): on the courtyard the
// user sees by default and on two builtins, the fitted lobe's profile bends back at most 0.02
// (of its mean luminance) more than the split sum's. Measured: 0.0048-0.0579 against the
// split sum's 0.0081-0.0592 (at most 0.0084 more, builtin:studio at 0.88); the table fitted cell by cell bent back 0.043-0.457 and failed
// all 12 cases.
TEST_F(FittedLobeRings, RoughSpheresAreAsSmoothAsTheSplitSums)
{
    for (const std::string& env : {std::string(IBLAB_ASSET_DIR) + "/environments/courtyard.exr", std::string("builtin:studio"), std::string("builtin:sun")}) {
        bakeEnvironment(env, roughBake());
        for (const float roughness : {0.82f, 0.88f, 0.94f, 0.98f}) {
            const std::vector<double> fitted = profile(ShadingMethod::FittedLobe, roughness), split = profile(ShadingMethod::SplitSum, roughness);
            ASSERT_GT(fitted.size(), 40u) << env;
            const double fittedBends = bendingBack(fitted), splitBends = bendingBack(split);
            std::printf("%s, roughness %.2f: the profile bends back %.4f (split sum %.4f)\n", env.c_str(), roughness, fittedBends, splitBends);
            EXPECT_LE(fittedBends, splitBends + 0.02) << env << " roughness " << roughness;
        }
    }
}

} // namespace
} // namespace iblab
