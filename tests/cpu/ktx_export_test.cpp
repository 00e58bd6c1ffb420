// The KTX writers' byte layout (against the specifications' field offsets, read here by
// hand) and the Filament SH conversion (against the closed form of a linear environment).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "cmgen_sh_window.hpp"
#include "ibl/engine_sh.hpp"
#include "io/ktx_writer.hpp"

namespace iblab {
namespace {

std::uint32_t u32(const std::string& s, std::size_t at)
{
    std::uint32_t v = 0;
    std::memcpy(&v, s.data() + at, 4);
    return v;
}
std::uint64_t u64(const std::string& s, std::size_t at)
{
    std::uint64_t v = 0;
    std::memcpy(&v, s.data() + at, 8);
    return v;
}

ktx::KtxTexture cube(int size, int levels, ktx::PixelType type)
{
    ktx::KtxTexture t;
    t.size = size;
    t.faces = 6;
    t.pixelType = type;
    for (int m = 0; m < levels; ++m) {
        const int e = t.levelSize(m);
        std::vector<float> texels(std::size_t(6 * e * e * 4));
        for (std::size_t i = 0; i < texels.size(); ++i) texels[i] = float(m) + float(i % 4) * 0.25f;
        t.levels.push_back(texels);
    }
    return t;
}

TEST(Ktx1Writer, HeaderKeyValueAndPerFaceImageSize)
{
    ktx::KtxTexture t = cube(8, 4, ktx::PixelType::Half);
    t.keyValues.emplace_back("sh", "1 2 3\n");
    const std::string f = ktx::encodeKtx1(t);
    ASSERT_EQ(0, std::memcmp(f.data(), ktx::kKtx1Identifier.data(), 12));
    EXPECT_EQ(u32(f, 12), 0x04030201u);
    EXPECT_EQ(u32(f, 16), 0x140Bu); // GL_HALF_FLOAT
    EXPECT_EQ(u32(f, 20), 2u);
    EXPECT_EQ(u32(f, 24), 0x1908u); // GL_RGBA
    EXPECT_EQ(u32(f, 28), 0x881Au); // GL_RGBA16F
    EXPECT_EQ(u32(f, 36), 8u);
    EXPECT_EQ(u32(f, 40), 8u);
    EXPECT_EQ(u32(f, 52), 6u); // faces
    EXPECT_EQ(u32(f, 56), 4u); // levels
    const std::uint32_t kvBytes = u32(f, 60);
    // "sh\0" + "1 2 3\n\0" = 10 bytes, with its size field 14, padded to 16.
    EXPECT_EQ(kvBytes, 16u);
    EXPECT_EQ(u32(f, 64), 10u);
    EXPECT_EQ(std::string(f.data() + 68, 2), "sh");
    std::size_t at = 64 + kvBytes;
    for (int m = 0; m < 4; ++m) {
        const std::uint32_t faceBytes = u32(f, at);
        EXPECT_EQ(faceBytes, std::uint32_t(t.levelSize(m) * t.levelSize(m) * 8)) << "level " << m;
        at += 4 + 6 * std::size_t(faceBytes);
    }
    EXPECT_EQ(at, f.size());
}

TEST(Ktx2Writer, IndexPointsAtLevelsStoredSmallestFirst)
{
    const ktx::KtxTexture t = cube(16, 5, ktx::PixelType::Float);
    const std::string f = ktx::encodeKtx2(t);
    ASSERT_EQ(0, std::memcmp(f.data(), ktx::kKtx2Identifier.data(), 12));
    EXPECT_EQ(u32(f, 12), 109u); // VK_FORMAT_R32G32B32A32_SFLOAT
    EXPECT_EQ(u32(f, 16), 4u);
    EXPECT_EQ(u32(f, 20), 16u);
    EXPECT_EQ(u32(f, 36), 6u);
    EXPECT_EQ(u32(f, 40), 5u);
    EXPECT_EQ(u32(f, 44), 0u);
    std::uint64_t previous = f.size();
    for (int m = 0; m < 5; ++m) {
        const std::uint64_t offset = u64(f, 80 + 24 * std::size_t(m));
        const std::uint64_t length = u64(f, 88 + 24 * std::size_t(m));
        EXPECT_EQ(length, std::uint64_t(6 * t.levelSize(m) * t.levelSize(m) * 16)) << "level " << m;
        EXPECT_EQ(offset % 16, 0u) << "level " << m;
        EXPECT_LE(offset + length, previous) << "level " << m << " is not before the larger one";
        previous = offset;
        float first = 0.0f;
        std::memcpy(&first, f.data() + offset, 4);
        EXPECT_EQ(first, float(m)); // the level's own texels, not a neighbour's
    }
    const std::uint32_t dfdOffset = u32(f, 48);
    EXPECT_EQ(u32(f, 52), 4u + 24u + 64u);
    EXPECT_EQ(u32(f, dfdOffset), 4u + 24u + 64u); // dfdTotalSize
    EXPECT_NE(f.find("KTXwriter"), std::string::npos);
}

TEST(KtxWriter, RefusesDataOfTheWrongSize)
{
    ktx::KtxTexture t = cube(8, 2, ktx::PixelType::Half);
    t.levels[1].pop_back();
    EXPECT_THROW(ktx::encodeKtx1(t), std::invalid_argument);
    EXPECT_THROW(ktx::encodeKtx2(t), std::invalid_argument);
    t = cube(8, 5, ktx::PixelType::Half); // 8, 4, 2, 1 and one more
    EXPECT_THROW(ktx::encodeKtx2(t), std::invalid_argument);
}

TEST(FilamentSh, LinearEnvironmentInClosedForm)
{
    // L(d) = a + b . d gives E(n) = pi a + (2 pi / 3) (b . n) (the cosine lobe's band
    // factors), so E(n) / pi = a + (b . n) / 3.
    const double a = 0.5;
    const glm::dvec3 b(0.5, 0.0, 0.0); // red only varies with x
    SH9Color radiance;
    // Project L onto iblab's basis numerically (any orthonormal basis works for this check).
    const int n = 200;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < 2 * n; ++j) {
            const double theta = (i + 0.5) * std::numbers::pi / n;
            const double phi = (j + 0.5) * std::numbers::pi / n;
            const glm::dvec3 d(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
            const double w = std::sin(theta) * (std::numbers::pi / n) * (std::numbers::pi / n);
            const auto y = sh9Basis(d);
            const glm::dvec3 L(a + glm::dot(b, d), a, a);
            for (int k = 0; k < kSh9Count; ++k) radiance.c[std::size_t(k)] += L * y[std::size_t(k)] * w;
        }
    const SH9Color irradiance = convolveWithCosineLobe(radiance);
    const double cutoff = iblab::testing::cmgenNeverNegativeCutoff();
    EXPECT_NEAR(filamentAutoWindowCutoff(irradiance), cutoff, 1e-9);
    const double w1 = std::pow(std::sin(std::numbers::pi / cutoff) / (std::numbers::pi / cutoff), 4);
    // Filament's cube direction d holds iblab's (-x, y, -z): red's x term flips.
    const FilamentSh sh = filamentShaderSh(irradiance, glm::dmat3(glm::dvec3(-1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, -1)));
    EXPECT_NEAR(sh[0].x, 0.5, 1e-4);
    EXPECT_NEAR(sh[3].x, -w1 / 3.0, 1e-4); // c3 multiplies x
    EXPECT_NEAR(sh[1].x, 0.0, 1e-4);
    EXPECT_NEAR(sh[2].x, 0.0, 1e-4);
    for (int k = 4; k < kSh9Count; ++k) EXPECT_NEAR(sh[std::size_t(k)].x, 0.0, 1e-4) << k;
    EXPECT_NEAR(sh[3].y, 0.0, 1e-4);
}

TEST(FilamentSh, BrightSourceNarrowsTheWindowUntilNonNegative)
{
    SH9Color radiance; // a small bright source at +Y over a dim sky: rings negative unwindowed
    const auto y = sh9Basis(glm::dvec3(0, 1, 0));
    for (int k = 0; k < kSh9Count; ++k) radiance.c[std::size_t(k)] = glm::dvec3(y[std::size_t(k)] * 50.0);
    radiance.c[0] += glm::dvec3(0.1 * std::sqrt(4.0 * std::numbers::pi));
    const SH9Color irradiance = convolveWithCosineLobe(radiance);
    ASSERT_LT(findMinimum(irradiance).value.x, 0.0);
    const double cutoff = filamentAutoWindowCutoff(irradiance);
    EXPECT_LT(cutoff, 13.0);
    EXPECT_GE(cutoff, 3.0);
    const FilamentSh sh = filamentShaderSh(irradiance, glm::dmat3(1.0));
    for (int i = 0; i < 50; ++i) {
        const double t = i * 0.123;
        const glm::dvec3 d = glm::normalize(glm::dvec3(std::cos(t * 7), std::sin(t * 3), std::cos(t * 5)));
        EXPECT_GE(evaluateFilamentSh(sh, d).x, -1e-3) << "direction " << i;
    }
    EXPECT_LT(filamentBandDifference(sh, sh, 1), 1e-12);
}

} // namespace
} // namespace iblab
