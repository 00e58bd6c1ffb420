// Export then import: a cube written by the engine export's KTX writers in an engine's
// orientation (bake/engine_export.hpp, io/ktx_writer.hpp) and read back by the import
// (io/ktx_cube.hpp, io/imported_bake.hpp) gives back every texel of every level in iblab's
// orientation, to the format's precision; Filament's SH read back is what Filament's shader
// evaluates. Two sides written separately, so an orientation or layout that one side gets
// wrong (and the other not) fails here.
#include <cmath>
#include <span>
#include <string>

#include <gtest/gtest.h>

#include "bake/baked_texture.hpp"
#include "bake/engine_export.hpp"
#include "ibl/conventions.hpp"
#include "ibl/engine_sh.hpp"
#include "io/imported_bake.hpp"
#include "io/ktx_cube.hpp"
#include "io/ktx_writer.hpp"

using namespace iblab;

namespace {

// Distinct values, every texel of every face and level, all positive (as radiance is: the
// reader replaces negatives).
bake::CubeImage testLevel(int size, int level)
{
    bake::CubeImage image(size);
    for (int face = 0; face < 6; ++face)
        for (int row = 0; row < size; ++row)
            for (int x = 0; x < size; ++x) {
                const float v = 1.0f + float(face) + 0.37f * float(x) + 0.11f * float(row) + 3.1f * float(level);
                image.at(face, x, row) = glm::vec4(v, 0.5f * v + 1.0f + std::sin(float(x * 7 + row)), 2.0f + std::cos(v), 1.0f);
            }
    return image;
}

// The texels to the import's precision (relative: half 2^-11, float exact).
void expectRoundTrip(bake::EngineFormat format, ktx::PixelType pixelType, const AxisMap& fileToWorld)
{
    const int size = 8, levels = 4;
    const bake::EngineLayout layout = bake::engineLayout(format, size);
    ktx::KtxTexture texture;
    texture.size = size;
    texture.faces = 6;
    texture.pixelType = pixelType;
    std::vector<bake::CubeImage> original;
    for (int m = 0; m < levels; ++m) {
        original.push_back(testLevel(std::max(size >> m, 1), m));
        const bake::CubeImage engine = bake::reorientCube(original.back(), layout.engineToIblab);
        std::vector<float> values;
        for (const glm::vec4& t : engine.texels)
            values.insert(values.end(), {t.r, t.g, t.b, t.a});
        texture.levels.push_back(std::move(values));
    }
    const bool ktx1 = format == bake::EngineFormat::Filament;
    const std::string bytes = ktx1 ? ktx::encodeKtx1(texture) : ktx::encodeKtx2(texture);
    const KtxCube cube = parseKtxCube(std::as_bytes(std::span(bytes.data(), bytes.size())), "roundtrip");
    EXPECT_EQ(cube.version, ktx1 ? 1 : 2);
    ASSERT_EQ(int(cube.levels.size()), levels);
    const double tolerance = pixelType == ktx::PixelType::Half ? std::ldexp(1.0, -11) : 0.0;
    for (int m = 0; m < levels; ++m) {
        const ImageRGB32F world = reorientCubeStrip(cube.levels[std::size_t(m)], fileToWorld);
        const int s = original[std::size_t(m)].size;
        for (int face = 0; face < 6; ++face)
            for (int row = 0; row < s; ++row)
                for (int x = 0; x < s; ++x)
                    for (int c = 0; c < 3; ++c) {
                        const double want = original[std::size_t(m)].at(face, x, row)[c];
                        const double got = world.at(x, face * s + row)[c];
                        ASSERT_LE(std::abs(got - want), tolerance * std::abs(want))
                            << enumName(format) << " level " << m << " face " << face << " x " << x << " row " << row << " channel " << c;
                    }
    }
}

} // namespace

TEST(KtxRoundTrip, FilamentHalfCube) { expectRoundTrip(bake::EngineFormat::Filament, ktx::PixelType::Half, cmgenFileToWorld()); }
TEST(KtxRoundTrip, FilamentFloatCube) { expectRoundTrip(bake::EngineFormat::Filament, ktx::PixelType::Float, cmgenFileToWorld()); }
TEST(KtxRoundTrip, KhronosHalfCube) { expectRoundTrip(bake::EngineFormat::Khronos, ktx::PixelType::Half, khronosFileToWorld()); }
TEST(KtxRoundTrip, KhronosFloatCube) { expectRoundTrip(bake::EngineFormat::Khronos, ktx::PixelType::Float, khronosFileToWorld()); }

// Filament's SH as exported (pre-scaled, windowed as cmgen windows, in Filament's cube frame)
// read back by the import gives, in iblab's world, the irradiance Filament's shader computes.
TEST(KtxRoundTrip, FilamentShReadBackIsWhatFilamentEvaluates)
{
    SH9Color irradiance;
    for (int i = 0; i < kSh9Count; ++i)
        irradiance.c[std::size_t(i)] = glm::dvec3(1.0 + 0.3 * i, 0.5 - 0.1 * i, 0.2 * std::sin(i + 1.0)) * (i == 0 ? 3.0 : 0.4);
    const bake::EngineLayout layout = bake::engineLayout(bake::EngineFormat::Filament, 256);
    const FilamentSh exported = filamentShaderSh(irradiance, layout.engineToIblab);
    const SH9Color imported = shFromFilament(exported, cmgenFileToWorld());
    for (const glm::dvec3 d : {glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1), glm::normalize(glm::dvec3(-1, 2, 0.5)),
                               glm::normalize(glm::dvec3(0.3, -0.7, -1))}) {
        const glm::dvec3 filament = kPi * evaluateFilamentSh(exported, d);
        const glm::dvec3 ours = evaluate(imported, layout.engineToIblab * d);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(ours[c], filament[c], 1e-5 * std::max(1.0, std::abs(filament[c]))) << "direction " << d.x << "," << d.y << "," << d.z;
    }
}
