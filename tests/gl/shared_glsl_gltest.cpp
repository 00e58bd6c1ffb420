// The shared .glsl files compile as both GLSL and C++. These tests pin the two compilers'
// results together: the same source can still differ through float precision or a
// built-in (atan, acos, pow) that the GPU evaluates differently.
#include <glm/glm.hpp>

#include "compute_probe.hpp"
#include "gl_test_fixture.hpp"
#include "ibl/conventions.hpp"
#include "ibl/tonemap.hpp"

namespace iblab {
namespace {

using testing::GlTest;
using testing::runComputeProbe;

gl::ShaderLibrary probeLibrary() { return gl::ShaderLibrary(gl::ShaderSearchPath{IBLAB_TEST_SHADER_DIR, IBLAB_SHADER_DIR}); }

// Directions through the centre of every texel of a width x height equirect map.
std::vector<glm::vec4> equirectTexelCentres(int width, int height)
{
    std::vector<glm::vec4> directions;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            directions.emplace_back(equirectUvToDirection(glm::vec2((x + 0.5f) / width, (y + 0.5f) / height)), 0.0f);
    return directions;
}

TEST_F(GlTest, EquirectMappingAgreesTexelForTexel)
{
    // Texel centres lie half a texel from any boundary, so both sides must land in the
    // same texel even though GPU atan/acos differ from libm in the last bits.
    constexpr int kWidth = 256, kHeight = 128;
    auto library = probeLibrary();
    const auto directions = equirectTexelCentres(kWidth, kHeight);
    const auto gpu = runComputeProbe(library, "conventions_probe.comp", directions, {{"MODE", "0"}});
    int mismatches = 0;
    for (std::size_t i = 0; i < directions.size(); ++i) {
        const glm::vec2 cpu = directionToEquirectUv(glm::vec3(directions[i]));
        const glm::ivec2 cpuTexel(glm::floor(cpu * glm::vec2(kWidth, kHeight)));
        const glm::ivec2 gpuTexel(glm::floor(glm::vec2(gpu[i]) * glm::vec2(kWidth, kHeight)));
        const glm::ivec2 expected(int(i % kWidth), int(i / kWidth));
        if (cpuTexel != expected || gpuTexel != expected) ++mismatches;
    }
    EXPECT_EQ(mismatches, 0);
}

TEST_F(GlTest, CubeFaceMappingAgreesTexelForTexel)
{
    constexpr int kFace = 32;
    auto library = probeLibrary();
    std::vector<glm::vec4> faceUvs;
    for (int face = 0; face < 6; ++face)
        for (int t = 0; t < kFace; ++t)
            for (int s = 0; s < kFace; ++s) faceUvs.emplace_back(float(face), (s + 0.5f) / kFace, (t + 0.5f) / kFace, 0.0f);
    const auto gpuDirections = runComputeProbe(library, "conventions_probe.comp", faceUvs, {{"MODE", "2"}});
    const auto gpuBack = runComputeProbe(library, "conventions_probe.comp", gpuDirections, {{"MODE", "1"}});
    for (std::size_t i = 0; i < faceUvs.size(); ++i) {
        const glm::vec3 cpuDirection = cubeFaceUvToDirection(int(faceUvs[i].x), glm::vec2(faceUvs[i].y, faceUvs[i].z));
        ASSERT_LT(glm::length(cpuDirection - glm::vec3(gpuDirections[i])), 1e-5f) << "face uv " << i;
        const glm::vec3 cpuBack = directionToCubeFaceUv(cpuDirection);
        ASSERT_EQ(cpuBack.x, gpuBack[i].x) << "face of " << i;
        ASSERT_EQ(int(cpuBack.y * kFace), int(gpuBack[i].y * kFace)) << "s texel of " << i;
        ASSERT_EQ(int(cpuBack.z * kFace), int(gpuBack[i].z * kFace)) << "t texel of " << i;
    }
}

TEST_F(GlTest, RotationAgrees)
{
    auto library = probeLibrary();
    std::vector<glm::vec4> inputs;
    for (int i = 0; i < 64; ++i) inputs.emplace_back(glm::normalize(glm::vec3(std::sin(i * 0.7f), std::cos(i * 1.3f), std::sin(i * 2.1f) + 0.1f)), i * 0.2f - 6.0f);
    const auto gpu = runComputeProbe(library, "conventions_probe.comp", inputs, {{"MODE", "3"}});
    for (std::size_t i = 0; i < inputs.size(); ++i)
        EXPECT_LT(glm::length(rotateAboutY(glm::vec3(inputs[i]), inputs[i].w) - glm::vec3(gpu[i])), 1e-5f);
}

TEST_F(GlTest, ToneMapCurvesAgreeWithCpu)
{
    auto library = probeLibrary();
    std::vector<glm::vec4> inputs;
    // Scene values from deep shadow to 64x over white, coloured so the matrices matter,
    // at three exposures.
    for (float ev : {-2.0f, 0.0f, 3.0f})
        for (int i = 0; i <= 40; ++i) {
            const float v = 0.001f * std::exp2(float(i) * 0.4f);
            inputs.emplace_back(v, v * 0.5f, v * 0.25f + 0.01f, ev);
        }
    for (ToneMapOperator op : allToneMapOperators()) {
        const auto gpu = runComputeProbe(library, "tonemap_probe.comp", inputs, {{"OPERATOR", std::to_string(int(op))}});
        for (std::size_t i = 0; i < inputs.size(); ++i) {
            const glm::vec3 cpu = displayEncode(glm::vec3(inputs[i]), inputs[i].w, op);
            // 2e-4 is a fortieth of an 8-bit step: the two sides only differ in float rounding.
            EXPECT_LT(glm::length(cpu - glm::vec3(gpu[i])), 2e-4f) << enumName(op) << " input " << i;
        }
    }
}

} // namespace
} // namespace iblab
