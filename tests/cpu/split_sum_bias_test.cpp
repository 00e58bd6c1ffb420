// The split sum's own error, with the CPU core alone (no GL, no bake): on the bundled
// courtyard, the N = V = R prefiltered radiance times the LUT's (F0 A + B) against the full
// specular integral, both summed over every texel of the same 256 x 128 map. This is the bias
// that makes `iblab bench` find split-sum's error flat in every prefilter setting (docs/results.md;
// docs/bake.md): at normal incidence the two agree to about 10%, but where the view
// grazes and the lobe's stretched footprint sees darker surroundings than its N = V = R
// circle, the split sum is more than twice the integral.
#include <cmath>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "io/environment.hpp"
#include "ibl/brdf_lut.hpp"
#include "ibl/reference.hpp"

namespace iblab {
namespace {

double splitSumOverFull(const ImageRGB32F& env, double tiltDegrees, double azimuthDegrees, double roughness)
{
    const glm::dvec3 F0(0.95, 0.64, 0.54); // the lab's default copper
    const glm::dvec3 v(0.0, 0.0, 1.0);
    const double tilt = glm::radians(tiltDegrees), azimuth = glm::radians(azimuthDegrees);
    const glm::dvec3 n(std::sin(tilt) * std::cos(azimuth), std::sin(tilt) * std::sin(azimuth), std::cos(tilt));
    const glm::dvec3 ab = integrateSplitSumBrdf(glm::dot(n, v), roughness, 4096, GeometryTerm::HeightCorrelatedSmith);
    const glm::dvec3 split = referencePrefilteredRadiance(env, glm::reflect(-v, n), roughness) * (F0 * ab.x + ab.y);
    const glm::dvec3 full = referenceSpecular(env, n, v, roughness, F0, GeometryTerm::HeightCorrelatedSmith);
    return split.g / full.g;
}

TEST(SplitSumBias, TwiceTheFullIntegralAtGrazingViewsOfTheCourtyard)
{
    const Environment courtyard = loadEnvironment(IBLAB_SOURCE_DIR "/assets/environments/courtyard.exr");
    const ImageRGB32F env = downsampleEquirectToWidth(courtyard.image, 256);
    const double normal = splitSumOverFull(env, 0.0, 0.0, 0.5);
    EXPECT_NEAR(normal, 1.0, 0.15) << "n.v = 1";
    // n.v = 0.64 and 0.34: measured 2.46 and 2.55.
    const double grazing50 = splitSumOverFull(env, 50.0, 90.0, 0.5);
    const double grazing70 = splitSumOverFull(env, 70.0, 0.0, 0.5);
    EXPECT_GT(grazing50, 2.0) << "n.v = 0.64";
    EXPECT_GT(grazing70, 2.0) << "n.v = 0.34";
    EXPECT_LT(grazing70, 3.0);
}

} // namespace
} // namespace iblab
