// Tone-mapping curves at fixed points, each expected value computed here from the published
// formula, and the typed C++ wrapper.
#include <algorithm>
#include <array>
#include <cmath>

#include <gtest/gtest.h>

#include "ibl/tonemap.hpp"

namespace {

using iblab::ToneMapOperator;

// The shared file runs in float: ~1e-6 absolute on values in [0, 1].
constexpr float kTol = 2e-6f;

glm::vec3 grey(float v)
{
    return glm::vec3(v);
}

TEST(ToneMap, IdsNamesAndParse)
{
    EXPECT_EQ(int(ToneMapOperator::None), 0);
    EXPECT_EQ(int(ToneMapOperator::PbrNeutral), 5);
    EXPECT_EQ(int(ToneMapOperator::Agx), 6);
    for (int id = 0; id < iblab::kToneMapOperatorCount; ++id) {
        const auto op = ToneMapOperator(id);
        EXPECT_EQ(iblab::parseEnum<ToneMapOperator>(iblab::enumName(op)), op);
    }
    EXPECT_EQ(iblab::enumName(ToneMapOperator::AcesHill), "aces-hill");
    EXPECT_EQ(iblab::parseEnum<ToneMapOperator>("hable"), ToneMapOperator::Hable);
    EXPECT_FALSE(iblab::parseEnum<ToneMapOperator>("ACES").has_value());
    EXPECT_FALSE(iblab::parseEnum<ToneMapOperator>("").has_value());
}

TEST(ToneMap, NoneClamps)
{
    const glm::vec3 r = iblab::toneMap(glm::vec3(-0.5f, 0.25f, 3.0f), ToneMapOperator::None);
    EXPECT_EQ(r, glm::vec3(0.0f, 0.25f, 1.0f));
}

TEST(ToneMap, Reinhard)
{
    EXPECT_NEAR(iblab::toneMap(grey(1.0f), ToneMapOperator::Reinhard).x, 0.5f, kTol);
    EXPECT_NEAR(iblab::toneMap(grey(3.0f), ToneMapOperator::Reinhard).x, 0.75f, kTol);
    // Negative input is clamped to 0 before any operator.
    EXPECT_EQ(iblab::toneMap(grey(-1.0f), ToneMapOperator::Reinhard).x, 0.0f);
}

TEST(ToneMap, AcesNarkowicz)
{
    // x = 1: (2.51 + 0.03) / (2.43 + 0.59 + 0.14) = 2.54 / 3.16 = 0.80380.
    EXPECT_NEAR(iblab::toneMap(grey(1.0f), ToneMapOperator::AcesNarkowicz).x, 2.54f / 3.16f, kTol);
    // x = 0.18 (mid grey): 0.18 (2.51 0.18 + 0.03) / (0.18 (2.43 0.18 + 0.59) + 0.14).
    const double x = 0.18, expected = x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14);
    EXPECT_NEAR(iblab::toneMap(grey(0.18f), ToneMapOperator::AcesNarkowicz).x, float(expected), kTol);
    // Saturates to exactly 1 (2.51 / 2.43 > 1, clamped).
    EXPECT_EQ(iblab::toneMap(grey(1000.0f), ToneMapOperator::AcesNarkowicz).x, 1.0f);
}

TEST(ToneMap, AcesHillMatrixOrderAndCurve)
{
    // Hill's matrices by ROWS (BakingLab ACES.hlsl), applied here as row . vector by hand: a
    // transposed matrix in the shared file (the column-major trap) would fail this.
    const double in[3][3] = {{0.59719, 0.35458, 0.04823}, {0.07600, 0.90834, 0.01566}, {0.02840, 0.13383, 0.83777}};
    const double out[3][3] = {
        {1.60475, -0.53108, -0.07367}, {-0.10208, 1.10813, -0.00605}, {-0.00327, -0.07276, 1.07602}};
    auto fit = [](double v) { return (v * (v + 0.0245786) - 0.000090537) / (v * (0.983729 * v + 0.4329510) + 0.238081); };
    const double c[3] = {0.8, 0.3, 0.05}; // saturated, so that off-diagonal terms matter
    double a[3], b[3];
    for (int i = 0; i < 3; ++i)
        a[i] = fit(in[i][0] * c[0] + in[i][1] * c[1] + in[i][2] * c[2]);
    for (int i = 0; i < 3; ++i)
        b[i] = std::clamp(out[i][0] * a[0] + out[i][1] * a[1] + out[i][2] * a[2], 0.0, 1.0);
    const glm::vec3 r = iblab::toneMap(glm::vec3(0.8f, 0.3f, 0.05f), ToneMapOperator::AcesHill);
    EXPECT_NEAR(r.x, b[0], 1e-5);
    EXPECT_NEAR(r.y, b[1], 1e-5);
    EXPECT_NEAR(r.z, b[2], 1e-5);
    // A grey stays (nearly) grey: the rows of each matrix sum to ~1.
    const glm::vec3 g = iblab::toneMap(grey(0.5f), ToneMapOperator::AcesHill);
    EXPECT_NEAR(g.x, g.z, 2e-3);
}

TEST(ToneMap, HableWhitePoint)
{
    auto curve = [](double x) {
        const double A = 0.15, B = 0.50, C = 0.10, D = 0.20, E = 0.02, F = 0.30;
        return ((x * (A * x + C * B) + D * E) / (x * (A * x + B) + D * F)) - E / F;
    };
    // The exposure bias 2 is applied before the curve, W = 11.2 is the linear white: an input of
    // W / 2 reaches exactly 1.
    EXPECT_NEAR(iblab::toneMap(grey(11.2f / 2.0f), ToneMapOperator::Hable).x, 1.0f, 1e-5f);
    EXPECT_NEAR(iblab::toneMap(grey(0.18f), ToneMapOperator::Hable).x, float(curve(0.36) / curve(11.2)), 1e-6f);
    EXPECT_NEAR(iblab::toneMap(grey(0.0f), ToneMapOperator::Hable).x, 0.0f, 1e-6f); // curve(0) = DE/DF - E/F = 0
    EXPECT_EQ(iblab::toneMap(grey(100.0f), ToneMapOperator::Hable).x, 1.0f);
}

TEST(ToneMap, PbrNeutral)
{
    // Below startCompression = 0.8 - 0.04 = 0.76 (after the toe offset) only the offset
    // applies: for min channel >= 0.08 that is a flat -0.04, so grey 0.5 -> 0.46 and a colour
    // keeps its channel differences exactly.
    EXPECT_NEAR(iblab::toneMap(grey(0.5f), ToneMapOperator::PbrNeutral).x, 0.46f, kTol);
    const glm::vec3 c = iblab::toneMap(glm::vec3(0.7f, 0.4f, 0.1f), ToneMapOperator::PbrNeutral);
    EXPECT_NEAR(c.x, 0.66f, kTol);
    EXPECT_NEAR(c.y, 0.36f, kTol);
    EXPECT_NEAR(c.z, 0.06f, kTol);
    // Toe: min channel x < 0.08 subtracts x - 6.25 x^2 (grey 0.04 -> 6.25 * 0.0016 = 0.01).
    EXPECT_NEAR(iblab::toneMap(grey(0.04f), ToneMapOperator::PbrNeutral).x, 0.01f, kTol);
    // The toe meets the flat offset continuously at 0.08: 0.08 - 6.25 * 0.0064 = 0.04.
    // Above: grey 2.0 -> p = 1.96, d = 0.24, p_n = 1 - d^2 / (p + d - 0.76) = 1 - 0.0576 / 1.44
    // = 0.96; the desaturation mix of a grey with its own peak leaves p_n.
    EXPECT_NEAR(iblab::toneMap(grey(2.0f), ToneMapOperator::PbrNeutral).x, 0.96f, 1e-5f);
    // Colour above the knee: the spec's c_out = (c - f) p_n / p g + p_n (1 - g), g = 1/(K_d (p - p_n) + 1).
    {
        const double in[3] = {3.0, 1.0, 0.5};
        const double f = 0.04, p = 3.0 - f, pn = 1.0 - 0.24 * 0.24 / (p + 1.0 - 2.0 * 0.76);
        const double g = 1.0 / (0.15 * (p - pn) + 1.0);
        const glm::vec3 r = iblab::toneMap(glm::vec3(3.0f, 1.0f, 0.5f), ToneMapOperator::PbrNeutral);
        for (int i = 0; i < 3; ++i)
            EXPECT_NEAR(r[i], (in[i] - f) * pn / p * g + pn * (1.0 - g), 1e-5) << i;
    }
}

// AgX from its published pieces in double precision: Rec.2020 -> sRGB by rows (ITU-R
// BT.2407), Filament's inset matrix and its outset matrix's inverse as three.js lists them
// (columns), Wrensch's polynomial; the two inverses are computed here, independently of
// the values written into tonemap.glsl.
namespace agx_reference {
using Matrix = std::array<std::array<double, 3>, 3>; // [row][column]
using Vector = std::array<double, 3>;

Matrix inverse(const Matrix& m)
{
    const double a = m[0][0], b = m[0][1], c = m[0][2], d = m[1][0], e = m[1][1], f = m[1][2], g = m[2][0], h = m[2][1], i = m[2][2];
    const double det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g);
    return {{{(e * i - f * h) / det, (c * h - b * i) / det, (b * f - c * e) / det},
             {(f * g - d * i) / det, (a * i - c * g) / det, (c * d - a * f) / det},
             {(d * h - e * g) / det, (b * g - a * h) / det, (a * e - b * d) / det}}};
}

Matrix fromColumns(const Matrix& columns)
{
    Matrix m{};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) m[r][c] = columns[c][r];
    return m;
}

Vector multiply(const Matrix& m, const Vector& v)
{
    Vector out{};
    for (int r = 0; r < 3; ++r) out[r] = m[r][0] * v[0] + m[r][1] * v[1] + m[r][2] * v[2];
    return out;
}

const Matrix kRec2020ToSrgb = {{{1.6605, -0.5876, -0.0728}, {-0.1246, 1.1329, -0.0083}, {-0.0182, -0.1006, 1.1187}}};
const Matrix kInset = fromColumns({{{0.856627153315983, 0.137318972929847, 0.11189821299995},
                                    {0.0951212405381588, 0.761241990602591, 0.0767994186031903},
                                    {0.0482516061458583, 0.101439036467562, 0.811302368396859}}});
const Matrix kOutsetInverse = fromColumns({{{0.899796955911611, 0.11142098895748, 0.11142098895748},
                                            {0.0871996192028351, 0.875575586156966, 0.0871996192028349},
                                            {0.013003424885555, 0.0130034248855548, 0.801379391839686}}});

Vector agx(Vector c)
{
    const double minEv = -12.47393, maxEv = 4.026069;
    Vector v = multiply(inverse(kRec2020ToSrgb), c);
    for (double& x : v) x = std::max(x, 0.0);
    v = multiply(kInset, v);
    for (double& x : v) {
        x = std::clamp((std::log2(std::max(x, 1e-10)) - minEv) / (maxEv - minEv), 0.0, 1.0);
        x = 15.5 * std::pow(x, 6) - 40.14 * std::pow(x, 5) + 31.96 * std::pow(x, 4) - 6.868 * std::pow(x, 3) + 0.4298 * x * x + 0.1191 * x - 0.00232;
    }
    v = multiply(inverse(kOutsetInverse), v);
    for (double& x : v) x = std::pow(std::max(x, 0.0), 2.2);
    v = multiply(kRec2020ToSrgb, v);
    for (double& x : v) x = std::clamp(x, 0.0, 1.0);
    return v;
}
} // namespace agx_reference

TEST(ToneMap, AgxMatchesItsPublishedPieces)
{
    // The float shader against the double reference: the log encoding and the 6th-order
    // polynomial amplify float rounding to a few 1e-6.
    for (const glm::vec3 c : {grey(0.18f), grey(1.0f), glm::vec3(0.8f, 0.3f, 0.05f), glm::vec3(0.05f, 0.2f, 3.0f), grey(16.0f), grey(1e-3f)}) {
        const agx_reference::Vector expected = agx_reference::agx({c.x, c.y, c.z});
        const glm::vec3 r = iblab::toneMap(c, ToneMapOperator::Agx);
        for (int i = 0; i < 3; ++i) EXPECT_NEAR(r[i], expected[std::size_t(i)], 2e-5) << c.x << " " << c.y << " " << c.z << " channel " << i;
    }
    // AgX's anchor: scene mid grey 0.18 lands at display-encoded 0.50 (log position 0.606 of
    // its 16.5-stop range, where the sigmoid gives 0.497 before the 2.2 power).
    EXPECT_NEAR(iblab::displayEncode(grey(0.18f), 0.0f, ToneMapOperator::Agx).x, 0.50f, 0.01f);
    // Black stays black; a grey stays grey up to the rounding of BT.2407's matrix to four
    // decimals (its rows sum to 1 within 1e-4, which the curve's slope about doubles).
    EXPECT_EQ(iblab::toneMap(grey(0.0f), ToneMapOperator::Agx), glm::vec3(0.0f));
    const glm::vec3 g = iblab::toneMap(grey(2.0f), ToneMapOperator::Agx);
    EXPECT_NEAR(g.x, g.z, 3e-4f);
    // Highlights desaturate toward white instead of clipping per channel: a saturated red at
    // 64x its mid-grey level keeps green and blue well above zero.
    const glm::vec3 hot = iblab::toneMap(glm::vec3(12.0f, 1.0f, 1.0f), ToneMapOperator::Agx);
    EXPECT_GT(hot.y, 0.5f * hot.x);
}

TEST(ToneMap, AgxInverseMatricesAreInverses)
{
    // The inverses written into tonemap.glsl, against the published matrices they invert.
    const glm::mat3 toRec2020 = iblab::shared::agxSrgbToRec2020(), toSrgb = iblab::shared::agxRec2020ToSrgb();
    const glm::mat3 outset = iblab::shared::agxOutsetMatrix();
    const agx_reference::Matrix& outsetInverse = agx_reference::kOutsetInverse;
    glm::mat3 outsetInverseGlm;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) outsetInverseGlm[c][r] = float(outsetInverse[std::size_t(r)][std::size_t(c)]);
    for (const glm::mat3 product : {toRec2020 * toSrgb, outset * outsetInverseGlm})
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(product[c][r], r == c ? 1.0f : 0.0f, 2e-6f) << r << " " << c;
}

TEST(ToneMap, SrgbOetf)
{
    EXPECT_EQ(iblab::srgbOetf(0.0f), 0.0f);
    EXPECT_NEAR(iblab::srgbOetf(1.0f), 1.0f, 1e-6f);
    // The two pieces meet at 0.0031308 -> 0.04045 (12.92 * 0.0031308 = 0.0404499).
    const float below = iblab::srgbOetf(0.0031308f);
    const float above = iblab::srgbOetf(std::nextafter(0.0031308f, 1.0f));
    EXPECT_NEAR(below, 0.04045f, 1e-6f);
    EXPECT_NEAR(above, below, 1e-6f);
    // Mid grey 0.18 -> 1.055 * 0.18^(1/2.4) - 0.055 = 0.46135.
    EXPECT_NEAR(iblab::srgbOetf(0.18f), float(1.055 * std::pow(0.18, 1.0 / 2.4) - 0.055), 1e-6f);
}

TEST(ToneMap, ExposureAndDisplayEncode)
{
    EXPECT_NEAR(iblab::applyExposure(grey(0.3f), 1.0f).x, 0.6f, 1e-7f);
    EXPECT_NEAR(iblab::applyExposure(grey(0.3f), -2.0f).x, 0.075f, 1e-7f);
    // displayEncode = sRGB(toneMap(hdr * 2^EV)): Reinhard of 0.5 * 2 = 1 is 0.5, sRGB(0.5).
    const float expected = float(1.055 * std::pow(0.5, 1.0 / 2.4) - 0.055);
    EXPECT_NEAR(iblab::displayEncode(grey(0.5f), 1.0f, ToneMapOperator::Reinhard).x, expected, 1e-6f);
    EXPECT_NEAR(iblab::shared::displayEncode(grey(0.5f), 1.0f, iblab::shared::IBL_TONEMAP_REINHARD).x, expected, 1e-6f);
    // Every operator maps into [0, 1] over a wide range.
    for (int id = 0; id < iblab::kToneMapOperatorCount; ++id)
        for (float v : {0.0f, 1e-4f, 0.18f, 1.0f, 16.0f, 1e4f}) {
            const glm::vec3 r = iblab::toneMap(glm::vec3(v, 0.5f * v, 0.1f * v), ToneMapOperator(id));
            for (int ch = 0; ch < 3; ++ch) {
                EXPECT_GE(r[ch], 0.0f) << id << " " << v;
                EXPECT_LE(r[ch], 1.0f + 1e-6f) << id << " " << v;
            }
        }
}

} // namespace
