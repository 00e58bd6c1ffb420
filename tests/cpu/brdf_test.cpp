// BRDF terms against their definitions: normalisation, hand-computed values, the limits the
// formulas must reach, and the relation between the G and Vis forms.
#include <cmath>

#include <gtest/gtest.h>

#include "ibl/brdf.hpp"
#include "ibl/conventions.hpp"
#include "quadrature.hpp"

namespace {

using iblab::GeometryTerm;
using iblab::kPi;

using iblab::testing::integrateSymmetricHemisphere;

TEST(Brdf, GgxDIsNormalised)
{
    for (double alpha : {0.05, 0.1, 0.25, 0.5, 0.8, 1.0}) {
        const double integral = integrateSymmetricHemisphere([&](double t) { return iblab::ggxD(std::cos(t), alpha) * std::cos(t); });
        EXPECT_NEAR(integral, 1.0, 1e-5) << alpha;
    }
}

TEST(Brdf, GgxDKnownValues)
{
    // At the peak D = 1 / (pi alpha^2); at alpha = 1 GGX is uniform: D = 1 / pi everywhere.
    EXPECT_NEAR(iblab::ggxD(1.0, 0.5), 1.0 / (kPi * 0.25), 1e-12);
    EXPECT_NEAR(iblab::ggxD(0.3, 1.0), 1.0 / kPi, 1e-12);
    // alpha = 0.5, n.h = 0.8: a2 = 0.25, denom = (0.64 * (0.25 - 1) + 1)^2 = 0.52^2.
    EXPECT_NEAR(iblab::ggxD(0.8, 0.5), 0.25 / (kPi * 0.52 * 0.52), 1e-12);
    // The float version agrees with double near the peak of a sharp lobe, where the textbook
    // form 1 + NoH^2 (a2 - 1) would lose most of its digits in float.
    const double nh = 0.99995, a = 0.01;
    EXPECT_NEAR(iblab::ggxD(float(nh), float(a)) / iblab::ggxD(double(float(nh)), a), 1.0, 1e-4);
}

TEST(Brdf, SchlickGgxKnownPoints)
{
    // k = alpha / 2. alpha = 0.5 -> k = 0.25; G1(0.5) = 0.5 / (0.5 * 0.75 + 0.25) = 0.8.
    EXPECT_NEAR(iblab::schlickGgxG1(0.5, iblab::schlickGgxK(0.5)), 0.8, 1e-15);
    // G = G1(n.v) G1(n.l): with n.v = 0.5, n.l = 1: 0.8 * 1.
    EXPECT_NEAR(iblab::schlickGgxG(0.5, 1.0, 0.5), 0.8, 1e-15);
    // Grazing: G1(0) = 0; normal incidence: G1(1) = 1 for any k.
    EXPECT_EQ(iblab::schlickGgxG1(0.0, 0.3), 0.0);
    EXPECT_NEAR(iblab::schlickGgxG1(1.0, 0.3), 1.0, 1e-15);
    // Vis = G / (4 n.l n.v).
    const double nv = 0.4, nl = 0.7, alpha = 0.3;
    EXPECT_NEAR(iblab::schlickGgxVisibility(nv, nl, alpha), iblab::schlickGgxG(nv, nl, alpha) / (4.0 * nl * nv), 1e-14);
}

TEST(Brdf, HeightCorrelatedSmithKnownPoints)
{
    // n.v = n.l = 1: Vis = 0.5 / (1 + 1) = 0.25, i.e. G = 1 — no masking head-on.
    EXPECT_NEAR(iblab::smithGgxCorrelatedVisibility(1.0, 1.0, 0.7), 0.25, 1e-15);
    // alpha = 1 (a2 = 1): the square roots are 1, Vis = 0.5 / (n.l + n.v).
    EXPECT_NEAR(iblab::smithGgxCorrelatedVisibility(0.3, 0.6, 1.0), 0.5 / 0.9, 1e-15);
    // A generic point by hand: n.v = 0.5, n.l = 0.8, alpha = 0.5 (a2 = 0.25):
    //   lambdaV = 0.8 sqrt(0.25 * 0.75 + 0.25) = 0.8 sqrt(0.4375)
    //   lambdaL = 0.5 sqrt(0.64 * 0.75 + 0.25) = 0.5 sqrt(0.73)
    const double expected = 0.5 / (0.8 * std::sqrt(0.4375) + 0.5 * std::sqrt(0.73));
    EXPECT_NEAR(iblab::smithGgxCorrelatedVisibility(0.5, 0.8, 0.5), expected, 1e-15);
    // G = 4 Vis (n.l)(n.v).
    EXPECT_NEAR(iblab::geometryG(GeometryTerm::HeightCorrelatedSmith, 0.5, 0.8, 0.5), expected * 4.0 * 0.4, 1e-15);
    // Both cosines zero: defined as 0, not NaN.
    EXPECT_EQ(iblab::smithGgxCorrelatedVisibility(0.0, 0.0, 0.5), 0.0);
}

// Directional albedo integral D Vis (n.l) dOmega_l at v = n, integrated in the half-vector
// domain (dOmega_l = 4 (v.h) dOmega_h) so that sharp lobes are resolved by the theta_h grid:
// with v = n, l lies at 2 theta_h, n.l = cos(2 theta_h), v.h = n.h = cos(theta_h).
double headOnAlbedo(GeometryTerm term, double alpha)
{
    return integrateSymmetricHemisphere([&](double th) {
        const double nl = std::cos(2.0 * th);
        if (nl <= 0.0)
            return 0.0;
        const double nh = std::cos(th);
        return iblab::ggxSpecularBrdf(term, nh, 1.0, nl, alpha) * nl * 4.0 * nh;
    });
}

TEST(Brdf, WhiteFurnaceHeightCorrelatedSmoothIsOne)
{
    // For F = 1 the single-scattering albedo loses energy only to multiple scattering, which
    // vanishes as alpha -> 0 (Kulla & Conty 2017: E(mu) -> 1 for smooth surfaces). At normal
    // incidence the loss is 0.3% at alpha = 0.05 and ~1.2% at alpha = 0.1 (measured with the
    // LUT integrator as well), so alpha <= 0.05 must be within 0.5% of 1.
    for (double alpha : {0.01, 0.02, 0.05}) {
        const double albedo = headOnAlbedo(GeometryTerm::HeightCorrelatedSmith, alpha);
        EXPECT_NEAR(albedo, 1.0, 0.005) << alpha;
        EXPECT_LE(albedo, 1.0 + 1e-6) << "a single-scattering BRDF cannot create energy";
    }
    // And the loss grows with roughness.
    EXPECT_LT(headOnAlbedo(GeometryTerm::HeightCorrelatedSmith, 0.3),
              headOnAlbedo(GeometryTerm::HeightCorrelatedSmith, 0.1));
}

TEST(Brdf, WhiteFurnaceClosedFormAtAlphaOne)
{
    // alpha = 1: D = 1/pi, and height-correlated Vis = 0.5 / (n.l + n.v). At v = n:
    //   E = integral (1/pi) 0.5 mu / (1 + mu) dOmega = integral_0^1 mu / (1 + mu) dmu = 1 - ln 2.
    // Schlick-GGX with k = 1/2 has G1(mu) = 2 mu / (1 + mu), the exact Smith G1 at alpha = 1, and
    // the separable product gives the same value at v = n: 2 (1 - ln 2) / (1 + 1).
    EXPECT_NEAR(headOnAlbedo(GeometryTerm::HeightCorrelatedSmith, 1.0), 1.0 - std::log(2.0), 1e-6);
    EXPECT_NEAR(headOnAlbedo(GeometryTerm::SchlickGGX, 1.0), 1.0 - std::log(2.0), 1e-6);
}

TEST(Brdf, SpecularIsDTimesVis)
{
    const double nh = 0.9, nv = 0.6, nl = 0.7, alpha = 0.4;
    for (GeometryTerm term : {GeometryTerm::SchlickGGX, GeometryTerm::HeightCorrelatedSmith}) {
        const double G = iblab::geometryG(term, nv, nl, alpha);
        EXPECT_NEAR(iblab::ggxSpecularBrdf(term, nh, nv, nl, alpha), iblab::ggxD(nh, alpha) * G / (4.0 * nl * nv), 1e-13);
    }
}

TEST(Brdf, Fresnel)
{
    EXPECT_DOUBLE_EQ(iblab::fresnelSchlick(1.0, 0.04), 0.04);
    EXPECT_DOUBLE_EQ(iblab::fresnelSchlick(0.0, 0.04), 1.0);
    // cos = 0.5: F0 + (1 - F0) / 32.
    EXPECT_NEAR(iblab::fresnelSchlick(0.5, 0.04), 0.04 + 0.96 / 32.0, 1e-15);
    const glm::dvec3 F0(0.04, 0.5, 1.0);
    const glm::dvec3 head = iblab::fresnelSchlick(1.0, F0);
    const glm::dvec3 grazing = iblab::fresnelSchlick(0.0, F0);
    for (int c = 0; c < 3; ++c) {
        EXPECT_DOUBLE_EQ(head[c], F0[c]);
        EXPECT_DOUBLE_EQ(grazing[c], 1.0);
    }
    // Roughness variant: grazing value max(1 - roughness, F0); roughness 0 is plain Schlick.
    const glm::dvec3 r = iblab::fresnelSchlickRoughness(0.0, F0, 0.7);
    EXPECT_NEAR(r.x, 0.3, 1e-15);
    EXPECT_NEAR(r.y, 0.5, 1e-15);
    EXPECT_NEAR(r.z, 1.0, 1e-15);
    const glm::dvec3 r0 = iblab::fresnelSchlickRoughness(0.3, F0, 0.0);
    const glm::dvec3 s0 = iblab::fresnelSchlick(0.3, F0);
    EXPECT_NEAR(r0.x, s0.x, 1e-15);
    EXPECT_NEAR(iblab::fresnelSchlickRoughness(1.0, F0, 0.7).x, 0.04, 1e-15);
}

TEST(Brdf, CombineLobesWeightsTheDiffuseLayerByWhatFresnelLeaves)
{
    const glm::dvec3 irradiance = kPi * glm::dvec3(1.0, 2.0, 3.0); // E / pi = (1, 2, 3)
    const glm::dvec3 specular(0.1, 0.2, 0.3);
    // Roughness 1 caps the grazing Fresnel at F0: F = F0 = 0.04 at any n.v, so
    // kD = 0.96 (1 - 0.25) = 0.72, diffuse = 0.72 (0.5, 0.25, 1) (1, 2, 3) = (0.36, 0.36, 2.16),
    // and occlusion halves both layers.
    iblab::SurfaceMaterial m{.baseColor = {0.5, 0.25, 1.0}, .metallic = 0.25, .roughness = 1.0, .F0 = glm::dvec3(0.04), .occlusion = 0.5};
    const glm::dvec3 shaded = iblab::combineLobes(m, 0.3, irradiance, specular);
    EXPECT_NEAR(shaded.x, 0.23, 1e-12);
    EXPECT_NEAR(shaded.y, 0.28, 1e-12);
    EXPECT_NEAR(shaded.z, 1.23, 1e-12);
    // Grazing (n.v = 0) at roughness 0.3: F = max(1 - 0.3, F0) = 0.7 leaves kD = 0.3 (1 - 0.25).
    m.roughness = 0.3;
    m.occlusion = 1.0;
    EXPECT_NEAR(iblab::combineLobes(m, 0.0, irradiance, glm::dvec3(0.0)).x, 0.3 * 0.75 * 0.5, 1e-12);
    // A metal has no diffuse layer: the specular alone, whatever the irradiance.
    m.metallic = 1.0;
    const glm::dvec3 metal = iblab::combineLobes(m, 0.3, irradiance, specular);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(metal[c], specular[c]);
}

TEST(Brdf, GeometryTermNames)
{
    EXPECT_EQ(enumName(GeometryTerm::SchlickGGX), "schlick-ggx");
    EXPECT_EQ(enumName(GeometryTerm::HeightCorrelatedSmith), "height-correlated-smith");
}

} // namespace
