// Other tools' bakes as environments (io/imported_bake.hpp): the orientation maps, the SH
// conversion, and cmgen's real output (Debian's libfilament-tools; skipped with a message
// where cmgen is not installed).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>

#include "ibl/conventions.hpp"
#include "ibl/sh.hpp"
#include "io/environment.hpp"
#include "io/error.hpp"
#include "io/imported_bake.hpp"

namespace fs = std::filesystem;
using namespace iblab;

namespace {

// A map whose radiance says where it comes from: 1 + 0.9 d per channel (x, y, z -> R, G, B).
glm::vec3 directionColour(glm::dvec3 d) { return glm::vec3(1.0 + 0.9 * d); }

// Radiance .hdr, flat (not run-length encoded) RGBE scanlines: what cmgen reads.
void writeDirectionMapHdr(const fs::path& path, int width)
{
    const int height = width / 2;
    std::ofstream out(path, std::ios::binary);
    out << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " << height << " +X " << width << "\n";
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const glm::vec2 uv((float(x) + 0.5f) / float(width), (float(y) + 0.5f) / float(height));
            const glm::vec3 c = directionColour(glm::dvec3(equirectUvToDirection(uv)));
            int exponent = 0;
            const float scale = std::frexp(std::max({c.r, c.g, c.b}), &exponent) * 256.0f / std::max({c.r, c.g, c.b});
            const unsigned char rgbe[4] = {(unsigned char)(c.r * scale), (unsigned char)(c.g * scale), (unsigned char)(c.b * scale),
                                           (unsigned char)(exponent + 128)};
            out.write(reinterpret_cast<const char*>(rgbe), 4);
        }
}

bool haveCmgen() { return std::system("command -v cmgen >/dev/null 2>&1") == 0; }

} // namespace

TEST(ImportedBake, AxisMapsInvert)
{
    for (const AxisMap& map : {cmgenFileToWorld(), khronosFileToWorld()}) {
        const glm::dvec3 v(0.3, -0.5, 0.8);
        const glm::dvec3 back = map.inverse().apply(map.apply(v));
        EXPECT_DOUBLE_EQ(back.x, v.x);
        EXPECT_DOUBLE_EQ(back.y, v.y);
        EXPECT_DOUBLE_EQ(back.z, v.z);
    }
}

// A strip whose texel holds its own GL direction, reoriented, holds fileToWorld(its direction)
// read back at the world direction: every texel, exactly.
TEST(ImportedBake, ReorientMovesEveryTexelToItsWorldDirection)
{
    const int size = 8;
    ImageRGB32F strip(size, 6 * size);
    for (int face = 0; face < 6; ++face)
        for (int row = 0; row < size; ++row)
            for (int x = 0; x < size; ++x)
                strip.set(x, face * size + row, cubeFaceUvToDirection(face, glm::vec2((x + 0.5f) / size, (row + 0.5f) / size)));
    const AxisMap map = khronosFileToWorld();
    const ImageRGB32F world = reorientCubeStrip(strip, map);
    for (int face = 0; face < 6; ++face)
        for (int row = 0; row < size; ++row)
            for (int x = 0; x < size; ++x) {
                const glm::dvec3 d(cubeFaceUvToDirection(face, glm::vec2((x + 0.5f) / size, (row + 0.5f) / size)));
                const glm::dvec3 fileDirection = map.inverse().apply(d);
                const glm::vec3 got = world.at(x, face * size + row);
                EXPECT_NEAR(got.x, fileDirection.x, 1e-6);
                EXPECT_NEAR(got.y, fileDirection.y, 1e-6);
                EXPECT_NEAR(got.z, fileDirection.z, 1e-6);
            }
}

// Filament's pre-scaled SH of a known irradiance, E(n) = pi (1 + 0.6 n_x) in the file's frame,
// is c_0 = 1, c_3 (the x term) = 0.6; in iblab's world (cmgen: x -> -x) E(w) = pi (1 - 0.6 w_x).
TEST(ImportedBake, FilamentShBecomesIblabIrradiance)
{
    std::array<glm::dvec3, 9> c{};
    c[0] = glm::dvec3(1.0);
    c[3] = glm::dvec3(0.6, 0.0, 0.0);
    c[6] = glm::dvec3(0.0, 0.1, 0.0); // 3z^2 - 1
    const SH9Color e = shFromFilament(c, cmgenFileToWorld());
    for (const glm::dvec3 w : {glm::dvec3(1, 0, 0), glm::dvec3(0, 0, 1), glm::normalize(glm::dvec3(-1, 2, 0.5))}) {
        const glm::dvec3 got = evaluate(e, w);
        EXPECT_NEAR(got.x, kPi * (1.0 - 0.6 * w.x), 1e-4);
        EXPECT_NEAR(got.y, kPi * (1.0 + 0.1 * (3.0 * w.z * w.z - 1.0)), 1e-4);
    }
    EXPECT_THROW(parseFilamentSh("1 2 3\n4 5", "x_ibl.ktx"), Error);
}

// cmgen --format=ktx on a map whose colour is its direction: after import, every sky texel
// holds (within R11G11B10F's 6-bit mantissa and one texel of resampling) the colour of its own
// direction, and the SH gives E(w) = pi (1 + 0.6 (colour's direction term)).
TEST(ImportedBake, CmgenOrientation)
{
    if (!haveCmgen()) GTEST_SKIP() << "cmgen not installed (Debian: libfilament-tools, scripts/install-deps.sh)";
    const fs::path dir = fs::temp_directory_path() / ("iblab-cmgen-test-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    writeDirectionMapHdr(dir / "dir.hdr", 256);
    const std::string command = "cd '" + dir.string() + "' && cmgen --quiet --format=ktx --size=32 --deploy=out dir.hdr >/dev/null 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
    const Environment env = loadEnvironment((dir / "out" / "out_ibl.ktx").string());
    ASSERT_TRUE(env.imported);
    const ImportedBake& bake = *env.imported;
    ASSERT_EQ(bake.sky.width, 32);
    EXPECT_GE(bake.prefiltered.size(), 2u);
    double worst = 0.0;
    for (int face = 0; face < 6; ++face)
        for (int row = 0; row < 32; ++row)
            for (int x = 0; x < 32; ++x) {
                const glm::dvec3 d(cubeFaceUvToDirection(face, glm::vec2((x + 0.5f) / 32.0f, (row + 0.5f) / 32.0f)));
                const glm::vec3 want = directionColour(d);
                const glm::vec3 got = bake.sky.at(x, face * 32 + row);
                worst = std::max(worst, double(glm::length(got - want)));
            }
    // A texel spans ~0.05 of direction at 32^2 (0.045 of colour), R11G11B10F rounds to 1/64.
    EXPECT_LT(worst, 0.08) << "a face or an axis of cmgen's cube is not where the import puts it";
    ASSERT_TRUE(bake.shIrradiance);
    for (const glm::dvec3 w : {glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, -1)}) {
        const glm::dvec3 got = evaluate(*bake.shIrradiance, w) / kPi;
        const glm::dvec3 want = glm::dvec3(1.0) + 0.6 * w;
        EXPECT_NEAR(got.x, want.x, 0.05);
        EXPECT_NEAR(got.y, want.y, 0.05);
        EXPECT_NEAR(got.z, want.z, 0.05);
    }
    fs::remove_all(dir);
}
