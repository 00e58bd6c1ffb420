// Exact discretised references against closed forms, and against two independent paths
// (the split-sum LUT integrator; a LearnOpenGL-style importance-sampled prefilter).
#include <algorithm>
#include <cmath>
#include <functional>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/brdf_lut.hpp"
#include "ibl/conventions.hpp"
#include "ibl/equirect.hpp"
#include "ibl/reference.hpp"
#include "ibl/sampling.hpp"

namespace {

using iblab::GeometryTerm;
using iblab::kPi;

const glm::dvec3 kNormals[] = {
    {0, 1, 0}, {0, -1, 0}, {1, 0, 0}, {0, 0, -1}, {0.48, 0.6, -0.64}, {-0.36, -0.48, 0.8}, {0.6, 0.0, 0.8},
};

// The light a map holds: each texel's radiance times its solid angle, summed.
glm::dvec3 equirectFlux(const iblab::ImageRGB32F& image)
{
    glm::dvec3 sum(0.0);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            sum += glm::dvec3(image.at(x, y)) * iblab::equirectTexelSolidAngle(y, image.width, image.height);
    return sum;
}

TEST(Reference, UniformIrradianceIsPiL)
{
    // integral max(0, n.w) dOmega = pi. The discrete sum is a midpoint rule whose error comes
    // from the cos curvature (~dtheta^2 / 24 relative, 4e-4 at 64x32) and from texels the
    // horizon cuts through (the clamp's kink): measured 1.2e-3 relative; tolerance 3e-3.
    const glm::vec3 L(0.5f, 1.0f, 2.0f);
    const auto env = iblab::paintEquirect(64, 32, [&](glm::dvec3) { return L; });
    for (glm::dvec3 n : kNormals) {
        const glm::dvec3 E = iblab::referenceIrradiance(env, glm::normalize(n));
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(E[c], kPi * L[c], 3e-3 * kPi * L[c]) << n.x << "," << n.y << "," << n.z;
    }
}

TEST(Reference, SkyOverGroundIrradiance)
{
    // Sky L = 1 for y > 0: E(n) = pi (1 + n.y) / 2 exactly. Same midpoint error budget as
    // above (128x64 halves dtheta; the step on the equator falls on a row boundary): measured
    // 3e-4 pi, tolerance 2e-3 pi.
    const auto env = iblab::paintEquirect(128, 64, [](glm::dvec3 d) { return glm::vec3(d.y > 0.0 ? 1.0f : 0.0f); });
    for (glm::dvec3 n : kNormals) {
        n = glm::normalize(n);
        EXPECT_NEAR(iblab::referenceIrradiance(env, n).x, kPi * (1.0 + n.y) / 2.0, 2e-3 * kPi);
    }
}

TEST(Reference, PrefilteredUniformIsTheConstant)
{
    // A normalised weighted mean of a constant is that constant, at every roughness
    // (roughness 0 takes the bilinear-lookup path).
    const glm::vec3 L(0.3f, 0.6f, 1.2f);
    const auto env = iblab::paintEquirect(64, 32, [&](glm::dvec3) { return L; });
    for (double r : {0.0, 0.1, 0.3, 0.6, 1.0})
        for (glm::dvec3 n : kNormals) {
            const glm::dvec3 p = iblab::referencePrefilteredRadiance(env, glm::normalize(n), r);
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(p[c], L[c], 1e-6 * L[c]) << "roughness " << r;
        }
}

TEST(Reference, PrefilteredSkyOverGroundHorizontalIsHalf)
{
    // For a horizontal n the weight D(normalize(n + w)) max(0, n.w) is mirror-symmetric about
    // the horizontal plane, so exactly half of it sees the sky: 0.5 at any roughness. The texel
    // rows are mirror-symmetric too, so only float rounding of the directions remains.
    const auto env = iblab::paintEquirect(128, 64, [](glm::dvec3 d) { return glm::vec3(d.y > 0.0 ? 1.0f : 0.0f); });
    for (double r : {0.3, 0.7, 1.0})
        EXPECT_NEAR(iblab::referencePrefilteredRadiance(env, {1, 0, 0}, r).x, 0.5, 1e-5);
    // Facing up, every direction with n.w > 0 is sky: exactly 1.
    EXPECT_NEAR(iblab::referencePrefilteredRadiance(env, {0, 1, 0}, 0.5).x, 1.0, 1e-12);
}

TEST(Reference, PrefilteredMatchesLearnOpenGlEstimator)
{
    // The second path: LearnOpenGL's prefilter loop written out here (GGX half vectors over a
    // Hammersley set, reflect n about h, weight by n.l, normalise by the weight sum), reading
    // the environment through the bilinear lookup. It converges to the reference's ratio of
    // integrals if the derivation in reference.cpp is right. Smooth environment so that the
    // bilinear vs texel-centre readings agree to ~1e-4; 16k QMC samples of a smooth integrand
    // converge to ~1e-4 as well: tolerance 2e-3 relative.
    const auto env = iblab::paintEquirect(128, 64, [](glm::dvec3 d) {
        return glm::vec3(float(1.0 + 0.5 * d.x + 0.3 * d.y * d.y), float(0.5 + 0.4 * d.z * d.x + 0.2 * d.y), 1.0f);
    });
    for (double r : {0.3, 0.6, 0.9})
        for (glm::dvec3 n : {glm::dvec3(0.48, 0.6, -0.64), glm::dvec3(0, 0, -1)}) {
            const iblab::Frame frame = iblab::tangentFrame(n);
            const double alpha = r * r;
            glm::dvec3 sum(0.0);
            double weight = 0.0;
            const std::uint32_t N = 16384;
            for (std::uint32_t i = 0; i < N; ++i) {
                const glm::dvec3 h = frame.toWorld(iblab::sampleGgxHalfVector(iblab::hammersley(i, N), alpha));
                const glm::dvec3 l = 2.0 * glm::dot(n, h) * h - n;
                const double nl = glm::dot(n, l);
                if (nl > 0.0) {
                    sum += glm::dvec3(iblab::sampleEquirectBilinear(env, l)) * nl;
                    weight += nl;
                }
            }
            const glm::dvec3 estimator = sum / weight;
            const glm::dvec3 ref = iblab::referencePrefilteredRadiance(env, n, r);
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(ref[c], estimator[c], 2e-3 * std::abs(estimator[c])) << "roughness " << r << " ch " << c;
        }
}

TEST(Reference, FullSpecularOfUniformEnvEqualsSplitSumAlbedo)
{
    // In a uniform environment L = 1 the full specular integral is the directional albedo
    // F0 A + B exactly (the split sum is exact when L is constant). Cross-check against the
    // LUT integrator, an independent path (importance sampling vs a sum over texels). The
    // texel sum at 256x128 (1.4 degree texels) resolves lobes with roughness >= 0.4, and 16k
    // Hammersley samples of these smooth integrands are good to ~1e-4: measured 1.5e-4 at
    // worst, tolerance 1e-3.
    const auto env = iblab::paintEquirect(256, 128, [](glm::dvec3) { return glm::vec3(1.0f); });
    const glm::dvec3 n = glm::normalize(glm::dvec3(0.2, 0.9, -0.3));
    const iblab::Frame frame = iblab::tangentFrame(n);
    for (GeometryTerm term : {GeometryTerm::HeightCorrelatedSmith, GeometryTerm::SchlickGGX})
        for (double r : {0.4, 0.7, 1.0})
            for (double nv : {0.3, 0.6, 0.95}) {
                const glm::dvec3 v = frame.toWorld({std::sqrt(1.0 - nv * nv), 0.0, nv});
                const glm::dvec3 AB = iblab::integrateSplitSumBrdf(nv, r, 16384, term);
                const glm::dvec3 white = iblab::referenceSpecular(env, n, v, r, glm::dvec3(1.0), term);
                EXPECT_NEAR(white.x, AB.z, 1e-3) << "r " << r << " nv " << nv;
                const glm::dvec3 F0(0.04, 0.5, 0.9);
                const glm::dvec3 coloured = iblab::referenceSpecular(env, n, v, r, F0, term);
                for (int c = 0; c < 3; ++c)
                    EXPECT_NEAR(coloured[c], F0[c] * AB.x + AB.y, 1e-3) << "r " << r << " nv " << nv;
            }
}

TEST(Reference, SpecularBelowHorizonIsZero)
{
    const auto env = iblab::paintEquirect(32, 16, [](glm::dvec3) { return glm::vec3(1.0f); });
    EXPECT_EQ(iblab::referenceSpecular(env, {0, 1, 0}, {0, -1, 0}, 0.5, glm::dvec3(1.0), GeometryTerm::SchlickGGX),
              glm::dvec3(0.0));
}

TEST(Reference, DownsamplePreservesPowerAndIrradiance)
{
    const auto env = iblab::paintEquirect(128, 64, [](glm::dvec3 d) {
        return glm::vec3(float(std::exp(4.0 * (d.x - 1.0))), float(d.y > 0 ? 1.0 : 0.1), float(0.5 + 0.5 * d.z));
    });
    const auto half = iblab::downsampleEquirect2x(env);
    ASSERT_EQ(half.width, 64);
    ASSERT_EQ(half.height, 32);
    // Power sum L dOmega: preserved up to float storage of the texels (~1e-7 relative).
    const glm::dvec3 p0 = equirectFlux(env), p1 = equirectFlux(half);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(p1[c], p0[c], 1e-6 * p0[c]);
    // Irradiance weights are smooth: the coarser texels change E by the midpoint error only.
    for (glm::dvec3 n : kNormals) {
        n = glm::normalize(n);
        const glm::dvec3 e0 = iblab::referenceIrradiance(env, n), e1 = iblab::referenceIrradiance(half, n);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(e1[c], e0[c], 5e-3 * std::max(e0[c], 0.1));
    }
    EXPECT_THROW(iblab::downsampleEquirect2x(iblab::ImageRGB32F(5, 4)), std::invalid_argument);
}

TEST(Reference, LargeEnvironmentUsesThreadsAndStaysExact)
{
    // 512x256 = 131k texels crosses the threading threshold (on a machine with >= 2 cores); the
    // row split must not lose or double rows: the error stays at the 256-row midpoint level
    // (measured 1e-5 pi).
    const auto env = iblab::paintEquirect(512, 256, [](glm::dvec3 d) { return glm::vec3(d.y > 0.0 ? 1.0f : 0.0f); });
    const glm::dvec3 n = glm::normalize(glm::dvec3(0.3, 0.5, 0.2));
    EXPECT_NEAR(iblab::referenceIrradiance(env, n).x, kPi * (1.0 + n.y) / 2.0, 1e-4 * kPi);
}

} // namespace

namespace {

// referenceMinResolvedRoughness's promise: at that roughness a reference over a coarse map
// agrees to a few percent with one over a map 8x finer (whose texels are far below the
// lobe's width), and well below it the coarse one does not. The map: three small bright discs over a dim
// sky, the high-contrast case where the midpoint rule suffers most.
TEST(Reference, MinResolvedRoughnessIsResolvedByTheCoarseMap)
{
    const glm::dvec3 lights[] = {glm::normalize(glm::dvec3(0.3, 0.8, -0.5)), glm::normalize(glm::dvec3(-0.7, 0.2, -0.6)), glm::dvec3(0.0, 0.1, -1.0)};
    const auto fine = iblab::paintEquirect(512, 256, [&](glm::dvec3 w) {
        float radiance = 0.2f;
        for (const glm::dvec3& light : lights) radiance += glm::dot(w, light) > std::cos(0.1) ? 20.0f : 0.0f;
        return glm::vec3(radiance);
    });
    const auto coarse = iblab::downsampleEquirectToWidth(fine, 64);
    ASSERT_EQ(coarse.width, 64);
    auto worstRelativeDifference = [&](double roughness) {
        double worst = 0.0;
        for (const glm::dvec3& n : {glm::normalize(glm::dvec3(0.2, 0.5, -1.0)), glm::normalize(glm::dvec3(-0.5, 0.3, -1.0)), glm::dvec3(0, 0, -1)}) {
            const glm::dvec3 v = glm::normalize(glm::dvec3(0.1, 0.0, -1.0));
            const double exact = iblab::referenceSpecular(fine, n, v, roughness, glm::dvec3(1.0), GeometryTerm::HeightCorrelatedSmith).x;
            const double approximate = iblab::referenceSpecular(coarse, n, v, roughness, glm::dvec3(1.0), GeometryTerm::HeightCorrelatedSmith).x;
            worst = std::max(worst, std::abs(approximate - exact) / exact);
        }
        return worst;
    };
    const double atBound = worstRelativeDifference(iblab::referenceMinResolvedRoughness(64));
    const double wellBelow = worstRelativeDifference(0.5 * iblab::referenceMinResolvedRoughness(64));
    // Measured: 1.9% at the bound and 18% at half of it; the discs are about one coarse
    // texel wide and 100x the sky, so smoother maps do better.
    EXPECT_LT(atBound, 0.03);
    EXPECT_GT(wellBelow, 3.0 * atBound);
}

// The upsample is the GPU sampler's bilinear read (wrapping in longitude, clamped at the
// poles) at each finer texel's centre, on a map whose every texel differs, seam and poles
// included: against the direction-based read, and at the seam and pole by hand.
// The upsample reads the map bilinearly, wrapping at the seam, with the rows' weights moved
// just enough that every source texel keeps its flux (fluxConservingRowBlends): a uniform map
// stays uniform, a texel alone at the pole keeps its light (the clamped bilinear read gave it
// 12.5% more by 2), and away from the poles it is the GPU sampler's read within a tenth of a
// row's weight, less the further from them.
TEST(Reference, UpsampleIsTheBilinearReadOfTheMapKeepingEachTexelsFlux)
{
    const auto coarse = iblab::paintEquirect(12, 6, [](glm::dvec3 w) { return glm::vec3(1.0 + w.x + 2.0 * w.z * w.z, 2.0 + w.y, 3.0 - w.x * w.y); });
    for (int factor : {2, 4}) {
        const auto fine = iblab::upsampleEquirectBilinear(coarse, factor);
        ASSERT_EQ(fine.width, 12 * factor);
        ASSERT_EQ(fine.height, 6 * factor);
        const std::vector<iblab::EquirectRowBlend> blends = iblab::fluxConservingRowBlends(6, factor);
        for (int y = 0; y < fine.height; ++y) {
            const iblab::EquirectRowBlend& b = blends[std::size_t(y)];
            // The bilinear read's rows, with a weight near its own.
            const double sourceRow = (y + 0.5) / factor - 0.5;
            EXPECT_EQ(b.first, std::clamp(int(std::floor(sourceRow)), 0, 5)) << factor << " " << y;
            EXPECT_EQ(b.second, std::clamp(int(std::floor(sourceRow)) + 1, 0, 5)) << factor << " " << y;
            if (b.first != b.second) {
                EXPECT_NEAR(b.weight, sourceRow - std::floor(sourceRow), 0.11) << factor << " " << y;
            }
            for (int x = 0; x < fine.width; ++x) {
                const double fx = (x + 0.5) / factor - 0.5;
                const glm::dvec3 expected = glm::dvec3(iblab::equirectBilinearAt(coarse, fx, b.first)) * (1.0 - b.weight) +
                                            glm::dvec3(iblab::equirectBilinearAt(coarse, fx, b.second)) * b.weight;
                for (int c = 0; c < 3; ++c) ASSERT_NEAR(fine.at(x, y)[c], expected[c], 1e-5) << factor << " " << x << "," << y;
            }
        }
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(equirectFlux(fine)[c], equirectFlux(coarse)[c], 1e-6 * equirectFlux(coarse)[c]) << factor;
        // One texel lit, at the pole and beside the equator: the upsample holds its light (to
        // the precision of float texels).
        for (int row : {0, 2, 5}) {
            iblab::ImageRGB32F one(12, 6);
            one.set(4, row, glm::vec3(1000.0f, 10.0f, 1.0f));
            const glm::dvec3 before = equirectFlux(one), after = equirectFlux(iblab::upsampleEquirectBilinear(one, factor));
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(after[c], before[c], 1e-6 * before[c]) << factor << " row " << row;
        }
        iblab::ImageRGB32F uniform(12, 6);
        for (float& v : uniform.texels) v = 2.5f;
        for (float v : iblab::upsampleEquirectBilinear(uniform, factor).texels) ASSERT_NEAR(v, 2.5f, 1e-5f);
    }
    // Factor 2: the first finer texel's centre is a quarter texel left of and above the first
    // coarse one's, so it weighs the last column (the seam) by 1/4 and clamps to row 0.
    const auto twice = iblab::upsampleEquirectBilinear(coarse, 2);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(twice.at(0, 0)[c], 0.75f * coarse.at(0, 0)[c] + 0.25f * coarse.at(11, 0)[c], 1e-5f);
    // Without the rows' weights moved, row 0 of a map lit only there gains 11% by 2 on this
    // 6-row map (12.5% on a fine one, whose polar rings grow as 1 : 3 : 5).
    iblab::ImageRGB32F cap(12, 6);
    for (int x = 0; x < 12; ++x) cap.set(x, 0, glm::vec3(1.0f));
    double bilinear = 0.0;
    for (int y = 0; y < 12; ++y)
        bilinear += std::clamp(1.0 - ((y + 0.5) / 2.0 - 0.5), 0.0, 1.0) * iblab::equirectTexelSolidAngle(y, 24, 12) * 24;
    EXPECT_NEAR(bilinear / equirectFlux(cap).x, 1.110, 1e-3);
    EXPECT_NEAR(equirectFlux(iblab::upsampleEquirectBilinear(cap, 2)).x / equirectFlux(cap).x, 1.0, 1e-6);
    EXPECT_THROW(iblab::upsampleEquirectBilinear(coarse, 0), std::invalid_argument);
    EXPECT_EQ(iblab::referenceUpsampleFactor(1024, 0.1, 16), 1);
    EXPECT_EQ(iblab::referenceUpsampleFactor(512, 0.1, 16), 2);
    EXPECT_EQ(iblab::referenceUpsampleFactor(64, 0.01, 16), 16);
}

} // namespace

namespace {

// The batched zonal sums against the textbook form of each integrand, summed texel by texel
// here (D(normalize(n + w)) (n.w) and max(0, n.w)), on a map with small lights 100x their
// sky, where a wrong weight or a dropped row would show. Also: a query's result does not
// depend on the batch it is in, and the single-query functions are the batch.
class ZonalBatch : public testing::TestWithParam<std::pair<int, int>> {};

// A power-of-two width, and one that is not a whole number of vector lanes, with the seam
// at an odd texel.
INSTANTIATE_TEST_SUITE_P(Reference, ZonalBatch, testing::Values(std::pair(256, 128), std::pair(250, 125)));

TEST_P(ZonalBatch, EqualsTheTexelByTexelIntegrals)
{
    const glm::dvec3 lights[] = {glm::normalize(glm::dvec3(0.3, 0.8, -0.5)), glm::normalize(glm::dvec3(-0.7, -0.2, 0.6))};
    const auto env = iblab::paintEquirect(GetParam().first, GetParam().second, [&](glm::dvec3 w) {
        glm::vec3 radiance(0.2f, 0.3f, 0.4f);
        for (const glm::dvec3& light : lights) radiance += glm::dot(w, light) > std::cos(0.05) ? glm::vec3(20.0f, 15.0f, 10.0f) : glm::vec3(0.0f);
        return radiance;
    });
    auto textbook = [&](glm::dvec3 n, double roughness) {
        const double alpha = roughness * roughness;
        glm::dvec3 weighted(0.0), irradiance(0.0);
        double weight = 0.0;
        iblab::forEachEquirectTexel(env.width, env.height, [&](int x, int y, glm::dvec3 w, double dOmega) {
            const double NdotL = glm::dot(n, w);
            if (NdotL <= 0.0)
                return;
            const double D = iblab::ggxD(glm::dot(n, glm::normalize(n + w)), alpha);
            weighted += glm::dvec3(env.at(x, y)) * D * NdotL * dOmega;
            weight += D * NdotL * dOmega;
            irradiance += glm::dvec3(env.at(x, y)) * NdotL * dOmega;
        });
        return std::pair(weighted / weight, irradiance);
    };
    std::vector<iblab::ZonalReference::PrefilterQuery> queries;
    std::vector<glm::dvec3> normals;
    // kNormals and a spiral of directions, so that the arcs of n.w > 0 fall at every
    // position of a row, across the seam too.
    std::vector<glm::dvec3> directions(std::begin(kNormals), std::end(kNormals));
    for (int i = 0; i < 24; ++i) {
        const double y = 1.0 - (2.0 * i + 1.0) / 24.0, r = std::sqrt(1.0 - y * y), phi = 2.4 * i;
        directions.emplace_back(r * std::cos(phi), y, r * std::sin(phi));
    }
    for (glm::dvec3 n : directions)
        for (double roughness : {0.0, 0.05, 0.1, 0.3, 0.6, 1.0}) {
            queries.push_back({glm::normalize(n), roughness});
            normals.push_back(glm::normalize(n));
        }
    queries.push_back({lights[0], 0.08}); // a narrow lobe on a light: the largest dynamic range
    normals.push_back(lights[0]);
    const iblab::ZonalReference zonal(env);
    const std::vector<glm::dvec3> prefiltered = zonal.prefilteredRadiance(queries);
    const std::vector<glm::dvec3> irradiance = zonal.irradiance(normals);
    for (std::size_t i = 0; i < queries.size(); ++i) {
        const auto [n, roughness] = queries[i];
        SCOPED_TRACE(testing::Message() << "n " << n.x << " " << n.y << " " << n.z << " roughness " << roughness);
        const auto [expectedPrefiltered, expectedIrradiance] = textbook(n, roughness);
        for (int c = 0; c < 3; ++c) {
            if (roughness > 0.0) {
                EXPECT_NEAR(prefiltered[i][c], expectedPrefiltered[c], 1e-9 * expectedPrefiltered[c]);
            }
            EXPECT_NEAR(irradiance[i][c], expectedIrradiance[c], 1e-9 * expectedIrradiance[c]);
        }
        // Alone, through the single-query functions: bit for bit the batch's result (a few
        // of them: each builds the directions of every texel again).
        if (i % 9 == 0) {
            EXPECT_EQ(iblab::referencePrefilteredRadiance(env, n, roughness), prefiltered[i]);
            EXPECT_EQ(iblab::referenceIrradiance(env, n), irradiance[i]);
        }
    }
    // Roughness 0 is the bilinear lookup, as the single-query function documents.
    EXPECT_EQ(prefiltered[0], glm::dvec3(iblab::sampleEquirectBilinear(env, queries[0].direction)));
}

} // namespace
