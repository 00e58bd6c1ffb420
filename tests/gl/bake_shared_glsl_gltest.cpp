// The shared GLSL the bake (and later the material shading) is built from, evaluated on the
// GPU and compared with the C++ core of renderer/ibl, which has its own CPU tests: a typo in
// a GLSL formula, a swapped argument or a different constant shows up here, not as a
// slightly-off bake. Tolerances are float rounding: the GPU evaluates in float what the
// core evaluates in double.
#include <cmath>

#include <glm/glm.hpp>

#include "ibl/prefilter_lod.hpp"
#include "compute_probe.hpp"
#include "gl_test_fixture.hpp"
#include "ibl/brdf.hpp"
#include "ibl/luminance.hpp"
#include "ibl/sampling.hpp"
#include "ibl/sh.hpp"

namespace iblab {
namespace {

using testing::GlTest;
using testing::runComputeProbe;

gl::ShaderLibrary probeLibrary() { return gl::ShaderLibrary(gl::ShaderSearchPath{IBLAB_TEST_SHADER_DIR, IBLAB_SHADER_DIR}); }

std::vector<glm::vec4> probe(gl::ShaderLibrary& library, int mode, const std::vector<glm::vec4>& inputs)
{
    return runComputeProbe(library, "bake_shared_probe.comp", inputs, {{"MODE", std::to_string(mode)}});
}

// |a - b| <= tolerance * max(1, |b|): relative for large values, absolute near 0.
void expectClose(double gpu, double cpu, double tolerance, const std::string& what)
{
    EXPECT_LE(std::abs(gpu - cpu), tolerance * std::max(1.0, std::abs(cpu))) << what << ": gpu " << gpu << " cpu " << cpu;
}

TEST_F(GlTest, BrdfTermsAgreeWithCore)
{
    auto library = probeLibrary();
    std::vector<glm::vec4> inputs;
    for (float NdotV : {0.02f, 0.3f, 0.7f, 1.0f})
        for (float NdotL : {0.05f, 0.5f, 0.95f})
            for (float NdotH : {0.2f, 0.9f, 0.999f, 1.0f})
                for (float alpha : {0.01f, 0.0625f, 0.36f, 1.0f})
                    inputs.emplace_back(NdotV, NdotL, NdotH, alpha);
    const auto gpu = probe(library, 0, inputs);
    for (std::size_t i = 0; i < inputs.size(); ++i) {
        const glm::dvec4 v(inputs[i]);
        const std::string at = "inputs " + std::to_string(i);
        // D reaches 1 / (pi alpha^2) = 3183 at n.h = 1, alpha = 0.01: relative 1e-5 is a few
        // float ulps of the float evaluation, with the core's cancellation-free denominator.
        expectClose(gpu[i].x, ggxD(v.z, v.w), 1e-5, "ggxD " + at);
        expectClose(gpu[i].y, schlickGgxVisibility(v.x, v.y, v.w), 1e-5, "schlickGgxVisibility " + at);
        expectClose(gpu[i].z, smithGgxCorrelatedVisibility(v.x, v.y, v.w), 1e-5, "smithGgxCorrelatedVisibility " + at);
        expectClose(gpu[i].w, schlickGgxG(v.x, v.y, v.w), 1e-5, "schlickGgxG " + at);
    }
}

// The prefilter's kernel, which the bake's bright texels and exact sums and the shading
// lights' residual weigh with: from the lobe's peak (1 - c given exactly, as |n - l|^2 / 2
// gives it) out to its tail, at alpha^2 from mip 1's to 1. The peak value is 1 / alpha^4
// (6.5e7 at mip 1), so the bound is relative.
TEST_F(GlTest, PrefilterWeightAgreesWithCore)
{
    auto library = probeLibrary();
    std::vector<glm::vec4> inputs;
    for (float oneMinusC : {0.0f, 1e-6f, 1e-4f, 0.01f, 0.5f, 1.0f, 1.5f})
        for (float alpha2 : {1.24e-4f, 0.0025f, 0.13f, 1.0f})
            inputs.emplace_back(1.0f - oneMinusC, oneMinusC, alpha2, 0.0f);
    const auto gpu = probe(library, 7, inputs);
    for (std::size_t i = 0; i < inputs.size(); ++i) {
        const glm::dvec4 v(inputs[i]);
        const double cpu = ggxPrefilterWeight(v.x, v.y, v.z);
        EXPECT_LE(std::abs(gpu[i].x - cpu), 1e-5 * std::max(1e-30, cpu)) << "inputs " << i << ": gpu " << gpu[i].x << " cpu " << cpu;
        if (v.x > 0.0) {
            EXPECT_GT(cpu, 0.0) << "inputs " << i;
        } else {
            EXPECT_EQ(gpu[i].x, 0.0f) << "the far side weighs nothing, inputs " << i;
        }
    }
    // 1 / alpha^4 at the peak (t = alpha^2).
    EXPECT_NEAR(ggxPrefilterWeight(1.0, 0.0, 0.01), 1e4, 1e-6);
}

// The GLSL's luminance (the bake's bright-texel clamp, the irradiance moments, the error
// view) weighs colour as ibl/luminance.hpp does: a changed weight on either side fails here.
TEST_F(GlTest, LuminanceAgreesWithCore)
{
    auto library = probeLibrary();
    const std::vector<glm::vec4> inputs = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0.3f, 2.5f, 1e4f, 0}, {1, 1, 1, 0}};
    const auto gpu = probe(library, 8, inputs);
    for (std::size_t i = 0; i < inputs.size(); ++i) {
        const double cpu = luminance(glm::dvec3(inputs[i]));
        EXPECT_LE(std::abs(gpu[i].x - cpu), 1e-6 * std::max(1.0, cpu)) << "inputs " << i << ": gpu " << gpu[i].x << " cpu " << cpu;
    }
    for (int c = 0; c < 3; ++c)
        EXPECT_FLOAT_EQ(gpu[0][1 + c], float(kLuminanceWeights[c])) << "weight " << c;
}

TEST_F(GlTest, FresnelAgreesWithCore)
{
    auto library = probeLibrary();
    std::vector<glm::vec4> inputs;
    for (float c : {0.0f, 0.1f, 0.5f, 0.9f, 1.0f})
        for (float roughness : {0.0f, 0.3f, 1.0f})
            inputs.emplace_back(c, 0.04f, 0.9f, roughness);
    const auto gpu = probe(library, 1, inputs);
    for (std::size_t i = 0; i < inputs.size(); ++i) {
        const glm::dvec3 F0(inputs[i].y, inputs[i].z, 0.5);
        const glm::dvec3 f = fresnelSchlick(double(inputs[i].x), F0);
        const glm::dvec3 fr = fresnelSchlickRoughness(double(inputs[i].x), F0, double(inputs[i].w));
        expectClose(gpu[i].x, f.x, 1e-6, "fresnelSchlick r");
        expectClose(gpu[i].y, f.y, 1e-6, "fresnelSchlick g");
        expectClose(gpu[i].z, fr.x, 1e-6, "fresnelSchlickRoughness r");
        expectClose(gpu[i].w, fr.y, 1e-6, "fresnelSchlickRoughness g");
    }
}

TEST_F(GlTest, GgxAndCosineSamplesAgreeWithCore)
{
    auto library = probeLibrary();
    constexpr std::uint32_t kCount = 256;
    std::vector<glm::vec4> ggxInputs;
    std::vector<glm::vec4> cosineInputs;
    for (float alpha : {0.0625f, 0.5f, 1.0f})
        for (std::uint32_t i = 0; i < kCount; ++i)
            ggxInputs.emplace_back(float(i), float(kCount), alpha, 0.0f);
    for (std::uint32_t i = 0; i < kCount; ++i)
        cosineInputs.emplace_back(float(i), float(kCount), 0.0f, 0.0f);
    const auto ggx = probe(library, 2, ggxInputs);
    const auto cosine = probe(library, 3, cosineInputs);
    for (std::size_t k = 0; k < ggxInputs.size(); ++k) {
        const auto i = std::uint32_t(ggxInputs[k].x);
        const glm::dvec3 h = sampleGgxHalfVector(hammersley(i, kCount), ggxInputs[k].z);
        // The radical inverse is exact in both (bits / 2^32, rounded to float on the GPU).
        EXPECT_NEAR(ggx[k].w, radicalInverseVdC(i), 1e-7) << "radical inverse of " << i;
        // 2e-5: float sqrt/sin/cos of the same point; a swapped u.x / u.y would be O(1).
        EXPECT_LT(glm::length(glm::dvec3(glm::vec3(ggx[k])) - h), 2e-5) << "GGX sample " << i << " alpha " << ggxInputs[k].z;
    }
    for (std::size_t i = 0; i < cosineInputs.size(); ++i) {
        const glm::dvec3 l = sampleCosineHemisphere(hammersley(std::uint32_t(i), kCount));
        EXPECT_LT(glm::length(glm::dvec3(glm::vec3(cosine[i])) - l), 2e-5) << "cosine sample " << i;
        expectClose(cosine[i].w, pdfCosineHemisphere(l), 2e-5, "cosine pdf " + std::to_string(i));
    }
}

TEST_F(GlTest, TangentFrameAgreesWithCore)
{
    auto library = probeLibrary();
    std::vector<glm::vec4> inputs;
    for (int i = 0; i < 64; ++i)
        inputs.emplace_back(glm::normalize(glm::vec3(std::sin(i * 0.9f), std::cos(i * 1.7f), std::sin(i * 2.3f + 0.4f))), 0.0f);
    inputs.emplace_back(0.0f, 0.0f, 1.0f, 0.0f);
    inputs.emplace_back(0.0f, 0.0f, -1.0f, 0.0f); // Frisvad's original is singular here
    const auto gpu = probe(library, 4, inputs);
    for (std::size_t i = 0; i < inputs.size(); ++i) {
        const glm::dvec3 cpu = tangentFrame(glm::dvec3(glm::vec3(inputs[i]))).toWorld({0.3, -0.5, 0.81});
        EXPECT_LT(glm::length(glm::dvec3(glm::vec3(gpu[i])) - cpu), 1e-5) << "normal " << i;
    }
}

TEST_F(GlTest, Sh9EvaluationAgreesWithCore)
{
    auto library = probeLibrary();
    SH9Color coefficients;
    for (int i = 0; i < kSh9Count; ++i)
        coefficients.c[std::size_t(i)] = glm::dvec3(0.7 - 0.13 * i, 0.05 * i * i - 0.3, std::sin(1.0 + i));
    const gl::ShaderProgram& program = library.program({"bake_shared_probe.comp"}, {{"MODE", "5"}});
    std::vector<glm::vec3> uniformValue;
    for (const glm::dvec3& c : coefficients.c)
        uniformValue.emplace_back(c);
    gl::UniformArray<glm::vec3>(program, "uCoefficients").set(uniformValue);
    std::vector<glm::vec4> inputs;
    for (int i = 0; i < 100; ++i)
        inputs.emplace_back(glm::normalize(glm::vec3(std::sin(i * 0.37f), std::cos(i * 0.71f), std::sin(i * 1.13f + 0.2f))), 0.0f);
    const auto gpu = probe(library, 5, inputs);
    for (std::size_t i = 0; i < inputs.size(); ++i) {
        const glm::dvec3 cpu = evaluate(coefficients, glm::dvec3(glm::vec3(inputs[i])));
        // Same order, signs and constants: float rounding of a 9-term sum of O(1) values.
        EXPECT_LT(glm::length(glm::dvec3(glm::vec3(gpu[i])) - cpu), 2e-6 * 9) << "direction " << i;
    }
}

TEST_F(GlTest, PrefilterLodIsTheSameSourceOnBothSides)
{
    auto library = probeLibrary();
    std::vector<glm::vec4> inputs;
    for (int i = 0; i < 50; ++i)
        inputs.emplace_back(std::sin(i * 0.37f), std::cos(i * 0.71f), std::sin(i * 1.13f + 0.2f), float(16 << (i % 5)));
    const auto gpu = probe(library, 6, inputs);
    for (std::size_t i = 0; i < inputs.size(); ++i) {
        const glm::vec3 d = glm::normalize(glm::vec3(inputs[i]));
        const float faceSize = inputs[i].w;
        expectClose(gpu[i].x, cubeTexelSolidAngle(d, faceSize), 1e-5, "cubeTexelSolidAngle");
        expectClose(gpu[i].y, sourceLodFromPdfAt(d, 0.37f, 64.0f, faceSize, 0.5f), 1e-5, "sourceLodFromPdfAt");
        expectClose(gpu[i].z, sourceLodFromPdf(0.37f, 64.0f, faceSize, 0.5f), 1e-5, "sourceLodFromPdf");
        // Mip 2 of 5 is roughness 2 / 4; roughness 0.3 of 5 levels is lod 0.3 * 4.
        // Quadratic mip 2 of 5: 1 - sqrt(1 - 0.5); linear 0.3 of 5: 1.2; quadratic 0.3 of 6: 5 x 0.51.
        EXPECT_NEAR(gpu[i].w, (1.0 - std::sqrt(0.5)) + 1.2 + 2.55, 1e-5);
    }
    // The anchor: a sample standing for exactly one average texel reads mip 0 (+ bias), and
    // four times that share reads mip 1.
    const float faceSize = 128.0f;
    const float averageTexel = float(4.0 * kPi / (6.0 * faceSize * faceSize));
    EXPECT_NEAR(sourceLodFromPdf(1.0f / (64.0f * averageTexel), 64.0f, faceSize, 0.0f), 0.0f, 1e-5f);
    EXPECT_NEAR(sourceLodFromPdf(1.0f / (64.0f * 4.0f * averageTexel), 64.0f, faceSize, 1.0f), 2.0f, 1e-5f);
    // The texel solid angles of a face must add up to the face's 4 pi / 6 (the formula is the
    // exact density at the texel's centre; midpoint rule over 64^2 texels).
    double face = 0.0;
    constexpr int kSize = 64;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            face += cubeTexelSolidAngle(
                cubeFaceUvToDirection(4, glm::vec2((x + 0.5f) / kSize, (y + 0.5f) / kSize)), float(kSize));
    EXPECT_NEAR(face, 4.0 * kPi / 6.0, 1e-3);
}

} // namespace
} // namespace iblab
