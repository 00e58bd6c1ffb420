// The bake's sample tables (renderer/bake/source_samples.hpp) against the samplers they are
// built from: each entry is the sampler's direction, and its lod term, completed with the
// texel's term, is the PDF-based lod prefilter_lod.glsl computes from the pdf directly.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/glm.hpp>

#include "ibl/prefilter_lod.hpp"
#include "bake/bake_settings.hpp"
#include "bake/source_samples.hpp"
#include "ibl/sampling.hpp"

namespace iblab::bake {
namespace {

constexpr float kFaceSize = 256.0f;
constexpr float kBias = 0.5f;

// A frame that is not the identity, so the texel term depends on the world direction.
const Frame kFrame = tangentFrame(glm::normalize(glm::dvec3(0.3, 0.8, -0.5)));

TEST(SourceSamples, CosineTableIsTheSamplerWithItsLod)
{
    const int n = 64;
    const std::vector<glm::vec4> table = cosineSampleTable(n, kBias);
    ASSERT_EQ(table.size(), std::size_t(n));
    for (int i = 0; i < n; ++i) {
        const glm::dvec3 l = sampleCosineHemisphere(hammersley(std::uint32_t(i), std::uint32_t(n)));
        const glm::vec4 e = table[std::size_t(i)];
        EXPECT_NEAR(glm::length(glm::dvec3(glm::vec3(e)) - l), 0.0, 1e-6) << i;
        const glm::vec3 world(kFrame.toWorld(l));
        const float direct = sourceLodFromPdfAt(world, float(pdfCosineHemisphere(l)), float(n), kFaceSize, kBias);
        EXPECT_NEAR(sourceLodFromSampleTerm(e.w, cubeTexelSolidAngle(world, kFaceSize)), direct, 1e-4f) << i;
    }
}

TEST(SourceSamples, GgxTableKeepsTheSamplesAboveTheHorizonWithTheirLod)
{
    const int n = 256;
    const float roughness = 0.8f; // wide enough that some reflected directions fall below
    const double alpha = double(roughness) * roughness;
    const std::vector<glm::vec4> table = ggxReflectedSampleTable(roughness, n, kBias);
    std::size_t next = 0;
    for (int i = 0; i < n; ++i) {
        const glm::dvec3 h = sampleGgxHalfVector(hammersley(std::uint32_t(i), std::uint32_t(n)), alpha);
        const glm::dvec3 l = 2.0 * h.z * h - glm::dvec3(0.0, 0.0, 1.0);
        if (l.z <= 0.0)
            continue;
        ASSERT_LT(next, table.size());
        const glm::vec4 e = table[next++];
        EXPECT_NEAR(glm::length(glm::dvec3(glm::vec3(e)) - l), 0.0, 1e-6) << i;
        const glm::vec3 world(kFrame.toWorld(l));
        // The lod counts all n samples drawn, the dropped ones included.
        const float pdf = float(pdfGgxReflected(pdfGgxHalfVector(h, alpha), h.z));
        EXPECT_NEAR(sourceLodFromSampleTerm(e.w, cubeTexelSolidAngle(world, kFaceSize)),
                    sourceLodFromPdfAt(world, pdf, float(n), kFaceSize, kBias), 1e-4f) << i;
    }
    EXPECT_EQ(next, table.size());
    EXPECT_LT(table.size(), std::size_t(n)) << "roughness 0.8 drops some samples below the horizon";
}

TEST(SourceSamples, RoughnessZeroIsEverySampleOnTheNormal)
{
    const std::vector<glm::vec4> table = ggxReflectedSampleTable(0.0f, 16, kBias);
    ASSERT_EQ(table.size(), 16u);
    for (const glm::vec4& e : table)
        EXPECT_EQ(glm::vec3(e), glm::vec3(0.0f, 0.0f, 1.0f));
}

// How many samples each prefiltered mip draws: the default doubles mip 3 on the tripling rule
// (docs/bake.md), a preset with its own rule keeps it, and a malformed scale list is refused
// naming its key.
// The tutorial preset's source lods against LearnOpenGL's own (2.2.1.prefilter.fs lines
// 87-96): pdf = D (n.h) / (4 h.v) + 0.0001, saSample = 1 / (N pdf + 0.0001), saTexel the
// face average of its 512 cube. The preset drops the two guards; this bounds what that
// moves, on every sample of every mip it bakes.
TEST(SourceSamples, TutorialLodsAreLearnOpenGlsWithinItsGuards)
{
    const BakeSettings tutorial = tutorialPreset();
    const PrefilterSettings& p = tutorial.prefilter;
    ASSERT_TRUE(p.mipFiltering);
    ASSERT_FALSE(tutorial.exactTexelSolidAngle);
    const double resolution = tutorial.cube.faceSize; // LOGL: 512.0
    const double saTexel = 4.0 * std::numbers::pi / (6.0 * resolution * resolution);
    const float maxLod = float(std::log2(resolution));
    double worst = 0.0;
    for (int level = 1; level < p.levels; ++level) {
        const float roughness = prefilterRoughnessFromMip(float(level), float(p.levels), int(p.layout));
        const int n = prefilterSamples(p, level);
        const double a2 = std::pow(double(roughness), 4.0);
        for (const glm::vec4& e : ggxReflectedSampleTable(roughness, n, p.mipBias)) {
            const glm::dvec3 h = glm::normalize(glm::dvec3(glm::vec3(e)) + glm::dvec3(0.0, 0.0, 1.0));
            const double t = h.z * h.z * (a2 - 1.0) + 1.0;
            const double pdf = a2 / (std::numbers::pi * t * t) / 4.0 + 0.0001; // v = n: n.h = h.v
            const double saSample = 1.0 / (double(n) * pdf + 0.0001);
            const float theirs = std::clamp(float(0.5 * std::log2(saSample / saTexel)), 0.0f, maxLod);
            const float ours = std::clamp(sourceLodFromSampleTerm(e.w, cubeAverageTexelSolidAngle(float(resolution))), 0.0f, maxLod);
            worst = std::max(worst, double(std::abs(ours - theirs)));
        }
    }
    EXPECT_LT(worst, 0.06);
    std::printf("tutorial preset: largest source-lod difference from LearnOpenGL's guarded formula %.4f mip\n", worst);
}

TEST(PrefilterSampleCounts, DefaultDoublesMipThreeAndPresetsKeepTheirRule)
{
    auto counts = [](const PrefilterSettings& p) {
        std::vector<int> n;
        for (int level = 0; level < p.levels; ++level) n.push_back(prefilterSamples(p, level));
        return n;
    };
    EXPECT_EQ(counts(defaultPreset().prefilter), (std::vector<int>{1, 8, 24, 288, 216, 648}));
    PrefilterSettings rule = defaultPreset().prefilter;
    rule.mipSampleScale = {};
    EXPECT_EQ(counts(rule), (std::vector<int>{1, 8, 24, 72, 216, 648}));
    rule.mipSampleScale = {0.5, 1, 1, 1, 1, 4}; // a factor beyond the last mip is ignored
    EXPECT_EQ(counts(rule), (std::vector<int>{1, 4, 24, 72, 216, 648}));
    EXPECT_EQ(counts(tutorialPreset().prefilter), (std::vector<int>(5, 1024)));
    EXPECT_EQ(counts(filamentPreset().prefilter), (std::vector<int>{1, 1024, 1024, 1024, 1024}));

    // As the command line and presets written before the factors were a list give them.
    for (const char* list : {"1,x", "1,,2", "0", "100", ","}) {
        BakeSettings bad;
        try {
            fromJson(bakeSettingsFields(), nlohmann::json{{"prefilter", {{"mip_sample_scale", list}}}}, bad, "bake settings");
            validate(bad);
            ADD_FAILURE() << "accepted \"" << list << "\"";
        } catch (const std::exception& e) {
            EXPECT_NE(std::string(e.what()).find("prefilter.mip_sample_scale"), std::string::npos) << e.what();
        }
    }
}

} // namespace
} // namespace iblab::bake
