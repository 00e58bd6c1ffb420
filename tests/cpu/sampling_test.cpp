// Sampler triplets: sample -> invert round trips, pdfs that integrate to one, and the
// low-discrepancy sequence's defining values.
#include <cmath>
#include <functional>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/brdf.hpp"
#include "ibl/conventions.hpp"
#include "ibl/sampling.hpp"
#include "quadrature.hpp"

namespace {

using iblab::kPi;

// Interior grid of the unit square (avoiding u = 0 and 1, where phi wraps and the pole
// makes phi undefined).
template <typename Fn>
void forGrid(int n, Fn&& fn)
{
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            fn(glm::dvec2((i + 0.5) / n, (j + 0.5) / n));
}

using iblab::testing::integrateSymmetricHemisphere;

TEST(Sampling, RadicalInverseKnownValues)
{
    EXPECT_EQ(iblab::radicalInverseVdC(0), 0.0);
    EXPECT_EQ(iblab::radicalInverseVdC(1), 0.5);  // 0.1b
    EXPECT_EQ(iblab::radicalInverseVdC(2), 0.25); // 0.01b
    EXPECT_EQ(iblab::radicalInverseVdC(3), 0.75); // 0.11b
    EXPECT_EQ(iblab::radicalInverseVdC(4), 0.125);
    EXPECT_EQ(iblab::radicalInverseVdC(6), 0.375); // 110 -> 0.011b
    EXPECT_EQ(iblab::radicalInverseVdC(0x80000000u), 0x1p-32);
    EXPECT_EQ(iblab::radicalInverseVdC(0xFFFFFFFFu), 1.0 - 0x1p-32);
    const glm::dvec2 h = iblab::hammersley(3, 8);
    EXPECT_EQ(h.x, 0.375);
    EXPECT_EQ(h.y, 0.75);
}

TEST(Sampling, GgxRoundTrip)
{
    for (double alpha : {0.05, 0.25, 0.5, 1.0})
        forGrid(40, [&](glm::dvec2 u) {
            const glm::dvec3 h = iblab::sampleGgxHalfVector(u, alpha);
            EXPECT_NEAR(glm::length(h), 1.0, 1e-12);
            EXPECT_GT(h.z, 0.0);
            const glm::dvec2 back = iblab::invertGgxHalfVector(h, alpha);
            EXPECT_NEAR(back.x, u.x, 1e-9) << alpha;
            EXPECT_NEAR(back.y, u.y, 1e-9) << alpha;
        });
}

TEST(Sampling, GgxPdfIntegratesToOne)
{
    // integral D(h) cos(theta_h) dOmega_h = 1: the microfacet projected-area normalisation.
    // Midpoint-rule error with 8e-6 rad steps is < 1e-6 even for the alpha = 0.05 spike.
    for (double alpha : {0.05, 0.1, 0.3, 0.6, 1.0}) {
        const double integral = integrateSymmetricHemisphere([&](double theta) {
            return iblab::pdfGgxHalfVector({std::sin(theta), 0.0, std::cos(theta)}, alpha);
        });
        EXPECT_NEAR(integral, 1.0, 1e-5) << "alpha " << alpha;
    }
}

TEST(Sampling, GgxPdfMatchesSampleDensity)
{
    // The pdf must be the density the warp actually produces: the fraction of a uniform grid
    // of u landing within theta_h < t equals integral_0^t pdf dOmega, which for GGX is
    // u.y(t) = invert's u.y at that angle. Compare the numerical integral with the inverse CDF.
    const double alpha = 0.3;
    for (double t : {0.1, 0.3, 0.6, 1.0, 1.4}) {
        const double cdf = integrateSymmetricHemisphere(
            [&](double theta) {
                return theta < t ? iblab::pdfGgxHalfVector({std::sin(theta), 0.0, std::cos(theta)}, alpha) : 0.0;
            });
        const double uy = iblab::invertGgxHalfVector({std::sin(t), 0.0, std::cos(t)}, alpha).y;
        EXPECT_NEAR(cdf, uy, 1e-4) << t; // step discontinuity at t costs one step: ~1e-5
    }
}

TEST(Sampling, ReflectedPdfJacobian)
{
    // The reflection l = reflect(-v, h) maps a patch dOmega_h to dOmega_l = 4 (v.h) dOmega_h,
    // so pdf_l = pdf_h / (4 v.h) must integrate to exactly 1 over the whole sphere of l (the
    // part below the horizon included: every h maps to some l).
    const double alpha = 0.5;
    // Integrate pdf_l over l in spherical coordinates around v = n. Then h = normalize(v + l)
    // is at half the angle of l, n.h = v.h = cos(theta_l / 2).
    const int steps = 200000;
    const double dt = kPi / steps;
    double sum = 0.0;
    for (int k = 0; k < steps; ++k) {
        const double thetaL = (k + 0.5) * dt;
        const double c = std::cos(0.5 * thetaL);
        const double pdfH = iblab::pdfGgxHalfVector({std::sin(0.5 * thetaL), 0.0, c}, alpha);
        sum += iblab::pdfGgxReflected(pdfH, c) * std::sin(thetaL);
    }
    EXPECT_NEAR(2.0 * kPi * sum * dt, 1.0, 1e-6);
}

TEST(Sampling, CosineHemisphere)
{
    forGrid(40, [&](glm::dvec2 u) {
        const glm::dvec3 w = iblab::sampleCosineHemisphere(u);
        EXPECT_NEAR(glm::length(w), 1.0, 1e-12);
        EXPECT_GE(w.z, 0.0);
        const glm::dvec2 back = iblab::invertCosineHemisphere(w);
        EXPECT_NEAR(back.x, u.x, 1e-9);
        EXPECT_NEAR(back.y, u.y, 1e-9);
        EXPECT_NEAR(iblab::pdfCosineHemisphere(w), w.z / kPi, 1e-15);
    });
    const double integral = integrateSymmetricHemisphere(
        [](double theta) { return iblab::pdfCosineHemisphere({std::sin(theta), 0.0, std::cos(theta)}); }, 20000);
    EXPECT_NEAR(integral, 1.0, 1e-8);
    // Half the samples (u.y < 0.5) lie within 45 degrees: sin^2(45) = 0.5.
    EXPECT_NEAR(iblab::sampleCosineHemisphere({0.3, 0.5}).z, std::sqrt(0.5), 1e-12);
}

TEST(Sampling, UniformSphere)
{
    forGrid(40, [&](glm::dvec2 u) {
        const glm::dvec3 w = iblab::sampleUniformSphere(u);
        EXPECT_NEAR(glm::length(w), 1.0, 1e-12);
        const glm::dvec2 back = iblab::invertUniformSphere(w);
        EXPECT_NEAR(back.x, u.x, 1e-9);
        EXPECT_NEAR(back.y, u.y, 1e-9);
    });
    EXPECT_DOUBLE_EQ(iblab::pdfUniformSphere() * 4.0 * kPi, 1.0);
    // Area-preserving: the mean of z over a stratified grid is 0, of z^2 is 1/3.
    double mz = 0.0, mz2 = 0.0;
    forGrid(100, [&](glm::dvec2 u) {
        const glm::dvec3 w = iblab::sampleUniformSphere(u);
        mz += w.z;
        mz2 += w.z * w.z;
    });
    EXPECT_NEAR(mz / 1e4, 0.0, 1e-9);
    EXPECT_NEAR(mz2 / 1e4, 1.0 / 3.0, 1e-4); // midpoint rule on z^2 with 100 strata: 1/(3*100^2)
}

TEST(Sampling, TangentFrameIsOrthonormalAndRightHanded)
{
    forGrid(30, [&](glm::dvec2 u) {
        const glm::dvec3 n = iblab::sampleUniformSphere(u);
        const iblab::Frame f = iblab::tangentFrame(n);
        EXPECT_NEAR(glm::length(f.t), 1.0, 1e-12);
        EXPECT_NEAR(glm::length(f.b), 1.0, 1e-12);
        EXPECT_NEAR(glm::dot(f.t, f.b), 0.0, 1e-12);
        EXPECT_NEAR(glm::dot(f.t, n), 0.0, 1e-12);
        EXPECT_NEAR(glm::dot(f.b, n), 0.0, 1e-12);
        const glm::dvec3 c = glm::cross(f.t, f.b);
        EXPECT_NEAR(glm::distance(c, n), 0.0, 1e-12);
        const glm::dvec3 local(0.2, -0.3, 0.9);
        EXPECT_NEAR(glm::distance(f.toLocal(f.toWorld(local)), local), 0.0, 1e-12);
    });
    // The poles, where Frisvad's original method divides by zero.
    for (double z : {1.0, -1.0}) {
        const iblab::Frame f = iblab::tangentFrame({0.0, 0.0, z});
        EXPECT_NEAR(glm::distance(glm::cross(f.t, f.b), glm::dvec3(0, 0, z)), 0.0, 1e-15);
    }
}

} // namespace
