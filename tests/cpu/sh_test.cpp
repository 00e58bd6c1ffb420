// SH9 projection, evaluation, cosine convolution and windowing against closed forms.
#include <chrono>
#include <cmath>
#include <functional>
#include <string>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/conventions.hpp"
#include "ibl/equirect.hpp"
#include "ibl/sh.hpp"

namespace {

using iblab::kPi;

// Sloan 2008's table, typed in here (six-digit constants) so that the tests do not take the
// basis from the code under test.
double sloanBasis(int i, glm::dvec3 d)
{
    const double x = d.x, y = d.y, z = d.z;
    switch (i) {
    case 0: return 0.282095;
    case 1: return 0.488603 * y;
    case 2: return 0.488603 * z;
    case 3: return 0.488603 * x;
    case 4: return 1.092548 * x * y;
    case 5: return 1.092548 * y * z;
    case 6: return 0.315392 * (3.0 * z * z - 1.0);
    case 7: return 1.092548 * x * z;
    default: return 0.546274 * (x * x - y * y);
    }
}

const glm::dvec3 kProbeDirs[] = {
    {0, 1, 0}, {0, -1, 0}, {1, 0, 0}, {0, 0, -1}, {0.48, 0.6, -0.64}, {-0.36, -0.48, 0.8}, {0.6, 0.0, 0.8},
};

TEST(Sh, BasisMatchesSloanTable)
{
    for (glm::dvec3 d : kProbeDirs) {
        const auto Y = iblab::sh9Basis(d);
        for (int i = 0; i < 9; ++i)
            EXPECT_NEAR(Y[i], sloanBasis(i, d), 2e-6) << i; // the table's 6-digit rounding
    }
    EXPECT_NE(std::string(iblab::kSh9Convention).find("no Condon-Shortley"), std::string::npos);
}

TEST(Sh, ConstantProjectsOntoBandZeroOnly)
{
    // integral L Y00 dOmega = L * 0.282095 * 4 pi = L sqrt(4 pi): exact here because the texel
    // solid angles sum to exactly 4 pi.
    const glm::vec3 L(1.0f, 2.0f, 0.5f);
    const int H = 32;
    const iblab::SH9Color sh = iblab::projectEquirect(iblab::paintEquirect(2 * H, H, [&](glm::dvec3) { return L; }));
    const double s = std::sqrt(4.0 * kPi);
    for (int ch = 0; ch < 3; ++ch)
        EXPECT_NEAR(sh.c[0][ch], L[ch] * s, 1e-9);
    // Indices 1, 2, 3, 4, 5, 7 are odd in phi or mirror-odd about the equator: the texel
    // centres share those symmetries, so the sums cancel up to float rounding of the directions.
    for (int i : {1, 2, 3, 4, 5, 7})
        for (int ch = 0; ch < 3; ++ch)
            EXPECT_NEAR(sh.c[i][ch], 0.0, 1e-5) << i;
    // Indices 6 (3z^2 - 1) and 8 (x^2 - y^2) involve y^2 = cos^2(theta), whose row sums carry
    // the midpoint rule's error: with f = cos^2 and exact row solid angles, the leading term is
    //   eps = sum_rows f(theta_c) dOmega - integral f dOmega ~ 2 pi (dtheta^2 / 24) integral f'' sin
    //       = 2 pi (pi / H)^2 / 24 * 4/3 = pi^3 / (9 H^2)      (3.4e-3 at H = 32).
    // Since sum (x^2 + y^2 + z^2) dOmega = 4 pi exactly and x^2, z^2 split the rest evenly,
    // sum x^2 = sum z^2 = 4 pi / 3 - eps / 2, hence c6 = -1.5 eps 0.315392 L and
    // c8 = -1.5 eps 0.546274 L to leading order (10% left for the O(dtheta^4) terms).
    const double eps = std::pow(kPi, 3) / (9.0 * H * H);
    for (int ch = 0; ch < 3; ++ch) {
        const double c6 = -1.5 * eps * 0.315392 * L[ch], c8 = -1.5 * eps * 0.546274 * L[ch];
        EXPECT_NEAR(sh.c[6][ch], c6, 0.1 * std::abs(c6));
        EXPECT_NEAR(sh.c[8][ch], c8, 0.1 * std::abs(c8));
    }
}

TEST(Sh, ProjectingYGivesOnlyIndexOne)
{
    // L(w) = w.y = sqrt(4 pi / 3) Y_1,-1(w), so the coefficient of index 1 is sqrt(4 pi / 3)
    // = 2.0466 and the rest vanish. Negative radiance below the horizon is fine for the math.
    const iblab::SH9Color sh = iblab::projectEquirect(iblab::paintEquirect(128, 64, [](glm::dvec3 d) { return glm::vec3(float(d.y)); }));
    // Midpoint rule on cos^2(theta) over 64 rows: relative error ~ dtheta^2 / 12 ~ 2e-4.
    EXPECT_NEAR(sh.c[1].x, std::sqrt(4.0 * kPi / 3.0), 1e-3);
    for (int i = 0; i < 9; ++i) {
        if (i != 1) {
            EXPECT_NEAR(sh.c[i].x, 0.0, 1e-3) << i;
        }
    }
}

TEST(Sh, BasisFunctionsAreOrthonormal)
{
    // Project each basis function (from the typed-in table): the result must be the unit
    // vector e_j. In phi the discrete sums over 256 columns are exact for these harmonics of
    // order <= 2 (discrete Fourier orthogonality); in theta the midpoint rule over 128 rows has
    // error ~ dtheta^2 / 24 * |f''| with dtheta = pi / 128, i.e. ~1e-4: 1e-3 leaves margin.
    for (int j = 0; j < 9; ++j) {
        const iblab::SH9Color sh =
            iblab::projectEquirect(iblab::paintEquirect(256, 128, [&](glm::dvec3 d) { return glm::vec3(float(sloanBasis(j, d))); }));
        for (int i = 0; i < 9; ++i)
            EXPECT_NEAR(sh.c[i].x, i == j ? 1.0 : 0.0, 1e-3) << "basis " << j << " coefficient " << i;
    }
}

TEST(Sh, EvaluateReconstructsABandLimitedSignal)
{
    // A signal inside the SH9 space comes back exactly (up to the projection's ~1e-4).
    auto f = [](glm::dvec3 d) { return 0.7 + 0.3 * d.x - 0.2 * d.y * d.z + 0.5 * d.z * d.z; };
    const iblab::SH9Color sh = iblab::projectEquirect(iblab::paintEquirect(256, 128, [&](glm::dvec3 d) { return glm::vec3(float(f(d))); }));
    for (glm::dvec3 d : kProbeDirs)
        EXPECT_NEAR(iblab::evaluate(sh, d).x, f(glm::normalize(d)), 1e-3);
}

TEST(Sh, UniformEnvironmentIrradianceIsPiL)
{
    // E = integral L max(0, n.w) dOmega = pi L for constant L. Only band 0 carries it
    // (A-hat_0 = pi); the band-2 discretisation residual (~1e-4 of L, see above) times
    // A-hat_2 Y_20 <= 0.5 bounds the error.
    const glm::vec3 L(0.25f, 1.0f, 4.0f);
    const iblab::SH9Color E = iblab::convolveWithCosineLobe(iblab::projectEquirect(iblab::paintEquirect(128, 64, [&](glm::dvec3) { return L; })));
    for (glm::dvec3 n : kProbeDirs) {
        const glm::dvec3 e = iblab::evaluate(E, n);
        for (int ch = 0; ch < 3; ++ch)
            EXPECT_NEAR(e[ch], kPi * L[ch], 1e-3 * L[ch]);
    }
}

TEST(Sh, SkyOverBlackGroundIrradianceIsExactInSh9)
{
    // L = 1 above the horizon (y > 0), 0 below. Exactly E(n) = pi (1 + n.y) / 2 (a tilted plane
    // sees the sky dome's view factor (1 + cos)/2). Truncation bound: the step's zonal Legendre
    // coefficients (2l+1)/2 integral_0^1 P_l vanish for every even l >= 2, and the clamped
    // cosine's A-hat_l vanishes for every odd l >= 3; so the step's irradiance lives entirely in
    // bands 0 and 1 and SH9 truncation costs nothing (the bound is 0). What remains is the
    // projection's midpoint error (~1e-4 relative at 128x64, horizon on a row boundary):
    // tolerance 2e-3 pi.
    const iblab::SH9Color L = iblab::projectEquirect(iblab::paintEquirect(128, 64, [](glm::dvec3 d) { return glm::vec3(d.y > 0.0 ? 1.0f : 0.0f); }));
    const iblab::SH9Color E = iblab::convolveWithCosineLobe(L);
    for (glm::dvec3 n : kProbeDirs) {
        n = glm::normalize(n);
        EXPECT_NEAR(iblab::evaluate(E, n).x, kPi * (1.0 + n.y) / 2.0, 2e-3 * kPi) << n.x << "," << n.y << "," << n.z;
    }
    // The radiance coefficients, by contrast, are the step's truncated Legendre series
    // 1/2 + (3/4) y (band 2 is zero): 1.25 at the zenith and -0.25 at the nadir — ringing.
    EXPECT_NEAR(iblab::evaluate(L, {0, 1, 0}).x, 1.25, 2e-3);
    EXPECT_NEAR(iblab::evaluate(L, {0, -1, 0}).x, -0.25, 2e-3);
}

// A single bright texel of power P: L_lm = P Y_lm(d) exactly (one term of the sum), and the
// SH9 irradiance is E(n) = P g(cos gamma), g(x) = sum_l A-hat_l (2l+1)/(4 pi) P_l(x) =
// 1/4 + x/2 + (5/16) (3x^2 - 1)/2 (addition theorem). g has its minimum at x = -8/15 with
// g = 3/32 - 2/15 = -19/480: a point light's SH9 irradiance rings negative.
TEST(Sh, PointLightRingsAndFindMinimumFindsIt)
{
    iblab::ImageRGB32F img(64, 32);
    const int tx = 40, ty = 9;
    img.set(tx, ty, glm::vec3(1000.0f, 500.0f, 250.0f));
    const double P = 1000.0 * iblab::equirectTexelSolidAngle(ty, 64, 32);
    const glm::dvec3 d = iblab::equirectTexelDirection(tx, ty, 64, 32);

    const iblab::SH9Color E = iblab::convolveWithCosineLobe(iblab::projectEquirect(img));
    // The peak towards the light: g(1) = 1/4 + 1/2 + 5/16 = 17/16.
    EXPECT_NEAR(iblab::evaluate(E, d).x, P * 17.0 / 16.0, 1e-4 * P);

    const iblab::ShMinimum m = iblab::findMinimum(E);
    EXPECT_NEAR(m.value.x, -19.0 / 480.0 * P, 1e-6 * P);
    EXPECT_NEAR(m.value.y, -19.0 / 480.0 * P / 2.0, 1e-6 * P);
    EXPECT_NEAR(glm::dot(m.direction[0], d), -8.0 / 15.0, 1e-3);
}

// The window search only asks whether a minimum is negative: with a stop, each channel's
// search ends at its first value below it (a bright sun's took half a second to the minimum),
// a value that is still an upper bound of the true minimum.
TEST(Sh, FindMinimumStopsBelowItsStop)
{
    iblab::ImageRGB32F img(64, 32);
    img.set(40, 9, glm::vec3(1000.0f, 500.0f, 250.0f));
    const iblab::SH9Color E = iblab::convolveWithCosineLobe(iblab::projectEquirect(img));
    const iblab::ShMinimum full = iblab::findMinimum(E);
    const iblab::ShMinimum stopped = iblab::findMinimum(E, 0.0);
    for (int ch = 0; ch < 3; ++ch) {
        EXPECT_LT(stopped.value[ch], 0.0) << ch;
        EXPECT_GE(stopped.value[ch], full.value[ch]) << ch;
    }
    // A stop below the minimum changes nothing.
    const iblab::ShMinimum below = iblab::findMinimum(E, 2.0 * full.value.x);
    EXPECT_EQ(below.value.x, full.value.x);
}

TEST(Sh, WindowFactors)
{
    using iblab::ShWindow;
    EXPECT_EQ(iblab::shWindowFactor(ShWindow::Hanning, 0, 3.0), 1.0);
    EXPECT_NEAR(iblab::shWindowFactor(ShWindow::Hanning, 1, 3.0), 0.75, 1e-15); // (1 + cos 60)/2
    EXPECT_NEAR(iblab::shWindowFactor(ShWindow::Hanning, 2, 3.0), 0.25, 1e-15); // (1 + cos 120)/2
    EXPECT_EQ(iblab::shWindowFactor(ShWindow::Hanning, 2, 2.0), 0.0);
    EXPECT_NEAR(iblab::shWindowFactor(ShWindow::Lanczos, 1, 2.0), 2.0 / kPi, 1e-15); // sin(pi/2)/(pi/2)
    EXPECT_EQ(iblab::shWindowFactor(ShWindow::None, 2, 1.0), 1.0);
}

TEST(Sh, HanningWindowRemovesRingingAndIsTheGentlestThatDoes)
{
    iblab::ImageRGB32F img(64, 32);
    img.set(10, 20, glm::vec3(100.0f));
    const iblab::SH9Color E = iblab::convolveWithCosineLobe(iblab::projectEquirect(img));
    ASSERT_LT(iblab::findMinimum(E).value.x, 0.0);

    const double w = iblab::findNonNegativeWindowWidth(E, iblab::ShWindow::Hanning);
    // Independent check with the window written out here: the windowed kernel
    // g_w(x) = 1/4 + h1 x/2 + h2 (5/32)(3x^2 - 1), h_l = (1 + cos(pi l / w))/2, must be >= 0 on
    // [-1, 1] at w and dip below 0 slightly above w.
    auto minKernel = [](double width) {
        const double h1 = width > 1 ? 0.5 * (1 + std::cos(kPi / width)) : 0.0;
        const double h2 = width > 2 ? 0.5 * (1 + std::cos(2 * kPi / width)) : 0.0;
        double m = 1e9;
        for (int k = 0; k <= 200000; ++k) {
            const double x = -1.0 + 2.0 * k / 200000;
            m = std::min(m, 0.25 + h1 * x / 2 + h2 * (5.0 / 32.0) * (3 * x * x - 1));
        }
        return m;
    };
    EXPECT_GE(minKernel(w), -1e-7);
    EXPECT_LT(minKernel(w + 0.01), 0.0);
    EXPECT_GE(iblab::findMinimum(iblab::applyWindow(E, iblab::ShWindow::Hanning, w)).value.x, -1e-9);
    // Band 0 (the mean) is untouched by any window.
    EXPECT_EQ(iblab::applyWindow(E, iblab::ShWindow::Hanning, w).c[0], E.c[0]);
}

// builtin:texel?width=64 projected on the GPU (float sums): the windowed irradiance's
// minimum is a double root at the antipode, flat to rounding. The minimum search took 25 s
// here when it accepted rounding noise as progress; it must stay a few milliseconds.
TEST(Sh, WindowSearchOnAOneTexelLightIsQuick)
{
    const double radiance[9] = {26.884021759033203,  6.832430362701416, -34.12858200073242, 30.932340621948242, 10.148881912231445,
                                -11.197566032409668, 18.38197898864746, -50.694541931152344, 21.852571487426758};
    iblab::SH9Color L;
    for (int i = 0; i < 9; ++i)
        L.c[std::size_t(i)] = glm::dvec3(radiance[i]);
    const iblab::SH9Color E = iblab::convolveWithCosineLobe(L);
    const auto start = std::chrono::steady_clock::now();
    const double w = iblab::findNonNegativeWindowWidth(E, iblab::ShWindow::Hanning);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_LT(seconds, 1.0) << "41 minimum searches; about 1 ms each";
    // A point light needs band 2 removed and band 1 halved: Hanning width 2.
    EXPECT_NEAR(w, 2.0, 1e-6);
    EXPECT_GE(iblab::findMinimum(iblab::applyWindow(E, iblab::ShWindow::Hanning, w)).value.x, -1e-9 * E.c[0].x);
}

} // namespace
