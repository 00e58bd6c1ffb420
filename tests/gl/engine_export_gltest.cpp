// `iblab bake --export`'s files read back by readers iblab did not write: Filament's own KTX 1
// reader (KtxBundle, Debian's libfilament-dev), npm's ktx-parse run with the machine's node
// for KTX 2.0, and Filament's cmgen for the SH. Each check is skipped, saying why, where its
// reader is absent (scripts/install-deps.sh installs them all).
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "cmgen_sh_window.hpp"
#include "bake/engine_export.hpp"
#include "bake_test_support.hpp"
#include "gl_test_fixture.hpp"
#include "ibl/engine_sh.hpp"
#include "io/builtin_environments.hpp"

#ifdef IBLAB_HAVE_FILAMENT_IMAGE
#include <image/KtxBundle.h>
#endif

namespace iblab {
namespace {

using testing::GlTest;
using testing::TempDirectory;

// The OpenGL cube-map table (GL 4.6, table 8.19), written out here rather than taken from
// iblab's conventions.glsl: face (+X, -X, +Y, -Y, +Z, -Z), texel (x, row) -> direction.
glm::dvec3 glCubeDirection(int face, int x, int row, int size)
{
    const double sc = 2.0 * (x + 0.5) / size - 1.0;
    const double tc = 2.0 * (row + 0.5) / size - 1.0;
    const glm::dvec3 d[6] = {{1, -tc, -sc}, {-1, -tc, sc}, {sc, 1, tc}, {sc, -1, -tc}, {sc, -tc, 1}, {-sc, -tc, -1}};
    return glm::normalize(d[face]);
}

// builtin:axes: radiance (1 + d) / 2 at iblab direction d.
glm::dvec3 axesRadiance(glm::dvec3 iblabDirection) { return 0.5 * (glm::dvec3(1.0) + iblabDirection); }

// Each engine's convention, written per face: the iblab direction its face centre shows.
// filament: cmgen's panorama centre is +Z where iblab's is -Z, and cmgen mirrors x;
// khronos: the IBL-Sampler's u = 0.5 is +X, growing towards +Z; bevy: its shader reads
// (x, y, -z) of the world direction.
struct Convention {
    const char* name;
    std::array<glm::dvec3, 6> faceCentre; // iblab direction seen at the centre of faces +X..-Z
};
constexpr Convention kFilament{"filament", {{{-1, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, -1}, {0, 0, 1}}}};
constexpr Convention kKhronos{"khronos", {{{0, 0, -1}, {0, 0, 1}, {0, 1, 0}, {0, -1, 0}, {1, 0, 0}, {-1, 0, 0}}}};
constexpr Convention kBevy{"bevy", {{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, -1}, {0, 0, 1}}}};

// The linear map the face centres define (engine direction -> iblab direction).
glm::dmat3 mapOf(const Convention& c) { return glm::dmat3(c.faceCentre[0], c.faceCentre[2], c.faceCentre[4]); }

// Level 0 of a cube, RGBA floats per face, against builtin:axes seen through the convention.
void expectAxesCube(const std::vector<std::vector<float>>& faces, int size, const Convention& c, double scale,
                    const std::function<glm::dvec3(glm::dvec3)>& expectedAt, const std::string& what)
{
    ASSERT_EQ(faces.size(), 6u) << what;
    const glm::dmat3 m = mapOf(c);
    double worst = 0.0;
    for (int f = 0; f < 6; ++f) {
        ASSERT_EQ(faces[std::size_t(f)].size(), std::size_t(size * size * 4)) << what;
        for (int row = 0; row < size; ++row)
            for (int x = 0; x < size; ++x) {
                const float* t = &faces[std::size_t(f)][std::size_t((row * size + x) * 4)];
                const glm::dvec3 got(t[0], t[1], t[2]);
                const glm::dvec3 want = scale * expectedAt(m * glCubeDirection(f, x, row, size));
                worst = std::max(worst, glm::length(got - want));
            }
        // The face centre, as the table says, in words for a failure.
        const float* mid = &faces[std::size_t(f)][std::size_t(((size / 2) * size + size / 2) * 4)];
        const glm::dvec3 centre = scale * expectedAt(c.faceCentre[std::size_t(f)]);
        EXPECT_NEAR(mid[0], centre.x, 0.1 * scale) << what << " face " << f;
        EXPECT_NEAR(mid[1], centre.y, 0.1 * scale) << what << " face " << f;
        EXPECT_NEAR(mid[2], centre.z, 0.1 * scale) << what << " face " << f;
    }
    EXPECT_LT(worst, 0.03 * scale) << what << ": a texel is not where " << c.name << "'s convention puts its colour";
}

// Irradiance / pi of builtin:axes: 1/2 + d / 3 (the cosine lobe's band-1 factor 2 pi / 3).
glm::dvec3 axesIrradianceOverPi(glm::dvec3 d) { return glm::dvec3(0.5) + d / 3.0; }

class EngineExport : public GlTest {
protected:
    static bake::BakeResult bakeAxes(gl::ShaderLibrary& shaders, Environment& environment)
    {
        environment = testing::environmentFromImage(makeBuiltinEnvironment("builtin:axes?width=128"), "builtin:axes");
        return testing::runBake(shaders, environment, testing::smallBakeSettings());
    }
};

std::string ktxParseScript() { return std::string(IBLAB_SOURCE_DIR) + "/tests/ktx2/inspect.mjs"; }

// ktx-parse's view of a file, or a reason it is not available.
std::optional<nlohmann::json> readWithKtxParse(const std::filesystem::path& file, std::string& why)
{
    if (std::system("node --version > /dev/null 2>&1") != 0) {
        why = "node is not installed (scripts/install-deps.sh: nodejs npm)";
        return std::nullopt;
    }
    if (!std::filesystem::exists(std::string(IBLAB_SOURCE_DIR) + "/tests/ktx2/node_modules/ktx-parse")) {
        why = "ktx-parse is not installed (scripts/install-ktx-parse.sh)";
        return std::nullopt;
    }
    const std::string command = "node " + ktxParseScript() + " '" + file.string() + "' --texels";
    FILE* pipe = popen(command.c_str(), "r");
    std::string out;
    char buffer[65536];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) out.append(buffer, n);
    const int status = pclose(pipe);
    if (status != 0) {
        ADD_FAILURE() << "ktx-parse could not read " << file << " (exit " << status << ")";
        return std::nullopt;
    }
    return nlohmann::json::parse(out);
}

std::vector<std::vector<float>> level0Faces(const nlohmann::json& j)
{
    std::vector<std::vector<float>> faces;
    for (const auto& f : j["level0"]) faces.push_back(f.get<std::vector<float>>());
    return faces;
}

// Format, faces and every level, as ktx-parse reads them.
void expectKtx2Cube(const nlohmann::json& j, int size, int levels, const std::string& what)
{
    EXPECT_EQ(j["vkFormat"], 97) << what; // VK_FORMAT_R16G16B16A16_SFLOAT
    EXPECT_EQ(j["typeSize"], 2) << what;
    EXPECT_EQ(j["pixelWidth"], size) << what;
    EXPECT_EQ(j["faceCount"], 6) << what;
    EXPECT_EQ(j["supercompressionScheme"], 0) << what;
    ASSERT_EQ(int(j["levels"].size()), levels) << what;
    for (int m = 0; m < levels; ++m) {
        const int e = std::max(size >> m, 1);
        EXPECT_EQ(j["levels"][std::size_t(m)]["byteLength"], 6 * e * e * 8) << what << " level " << m;
    }
    ASSERT_EQ(j["dfd"].size(), 1u) << what;
    EXPECT_EQ(j["dfd"][0]["samples"].size(), 4u) << what;
    EXPECT_EQ(j["dfd"][0]["transferFunction"], 1) << what; // linear
}

void checkKtx2Export(const bake::EngineFormat format, const Convention& c, const std::filesystem::path& specular,
                     const std::filesystem::path& diffuse)
{
    std::string why;
    const auto spec = readWithKtxParse(specular, why);
    if (!spec) GTEST_SKIP() << why;
    expectKtx2Cube(*spec, 16, 4, specular.string()); // face 16: floor(log2(16)) = 4 mips, down to 2^2
    // Mip 0 is the mirror: the environment itself.
    expectAxesCube(level0Faces(*spec), 16, c, 1.0, axesRadiance, specular.string());
    const auto diff = readWithKtxParse(diffuse, why);
    ASSERT_TRUE(diff) << why;
    expectKtx2Cube(*diff, 8, 1, diffuse.string());
    // E / pi: what the engine multiplies by the albedo.
    expectAxesCube(level0Faces(*diff), 8, c, 1.0, axesIrradianceOverPi, diffuse.string());
    (void)format;
}

TEST_F(EngineExport, KhronosFilesInTheSamplersOrientationReadByKtxParse)
{
    gl::ShaderLibrary shaders = testing::bakeShaderLibrary();
    Environment environment;
    const bake::BakeResult result = bakeAxes(shaders, environment);
    TempDirectory dir("export-khronos");
    const bake::ExportReport report = bake::exportForEngine(shaders, environment, result, bake::EngineFormat::Khronos, dir.path());
    EXPECT_TRUE(report.reprefiltered); // the small bake has 5 mips, the sampler's layout 4
    ASSERT_TRUE(std::filesystem::exists(dir.path() / "lut_ggx.ktx2"));
    checkKtx2Export(bake::EngineFormat::Khronos, kKhronos, dir.path() / "ggx" / "specular.ktx2",
                    dir.path() / "lambertian" / "diffuse.ktx2");
    std::string why;
    if (const auto lut = readWithKtxParse(dir.path() / "lut_ggx.ktx2", why)) {
        EXPECT_EQ((*lut)["faceCount"], 1);
        EXPECT_EQ((*lut)["pixelWidth"], 16);
    }
}

TEST_F(EngineExport, BevyFilesInItsOrientationReadByKtxParse)
{
    gl::ShaderLibrary shaders = testing::bakeShaderLibrary();
    Environment environment;
    const bake::BakeResult result = bakeAxes(shaders, environment);
    TempDirectory dir("export-bevy");
    bake::exportForEngine(shaders, environment, result, bake::EngineFormat::Bevy, dir.path() / "axes");
    checkKtx2Export(bake::EngineFormat::Bevy, kBevy, dir.path() / "axes" / "axes_specular.ktx2", dir.path() / "axes" / "axes_diffuse.ktx2");
}

#ifdef IBLAB_HAVE_FILAMENT_IMAGE
std::vector<std::uint8_t> readBytes(const std::filesystem::path& p)
{
    std::ifstream in(p, std::ios::binary);
    return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), {});
}

float halfToFloat(std::uint16_t h)
{
    const int e = (h >> 10) & 0x1f;
    const int m = h & 0x3ff;
    const float sign = (h & 0x8000) ? -1.0f : 1.0f;
    if (e == 0) return sign * float(m) * std::ldexp(1.0f, -24);
    return sign * (1.0f + float(m) / 1024.0f) * std::ldexp(1.0f, e - 15);
}

std::vector<std::vector<float>> bundleFaces(const image::KtxBundle& bundle, int level)
{
    std::vector<std::vector<float>> faces;
    for (std::uint32_t f = 0; f < 6; ++f) {
        std::uint8_t* data = nullptr;
        std::uint32_t size = 0;
        EXPECT_TRUE(bundle.getBlob({std::uint32_t(level), 0, f}, &data, &size));
        std::vector<float> texels(size / 2);
        for (std::size_t i = 0; i < texels.size(); ++i) texels[i] = halfToFloat(std::uint16_t(data[2 * i] | (data[2 * i + 1] << 8)));
        faces.push_back(std::move(texels));
    }
    return faces;
}
#endif

TEST_F(EngineExport, FilamentFilesReadByKtxBundleCarryTheShAndCmgensOrientation)
{
#ifndef IBLAB_HAVE_FILAMENT_IMAGE
    GTEST_SKIP() << "Filament's KtxBundle (libfilament-dev) was not found when this test was built";
#else
    gl::ShaderLibrary shaders = testing::bakeShaderLibrary();
    Environment environment;
    const bake::BakeResult result = bakeAxes(shaders, environment);
    TempDirectory dir("export-filament");
    const std::filesystem::path out = dir.path() / "axes";
    bake::exportForEngine(shaders, environment, result, bake::EngineFormat::Filament, out);

    std::vector<std::uint8_t> iblBytes = readBytes(out / "axes_ibl.ktx");
    image::KtxBundle ibl(iblBytes.data(), std::uint32_t(iblBytes.size()));
    EXPECT_TRUE(ibl.isCubemap());
    EXPECT_EQ(ibl.getNumMipLevels(), 5u); // a 16^2 face: cmgen keeps every level when the face is not above 16
    EXPECT_EQ(ibl.getInfo().glInternalFormat, 0x881Au);
    EXPECT_EQ(ibl.getInfo().pixelWidth, 16u);
    expectAxesCube(bundleFaces(ibl, 0), 16, kFilament, 1.0, axesRadiance, "axes_ibl.ktx");

    std::vector<std::uint8_t> skyBytes = readBytes(out / "axes_skybox.ktx");
    image::KtxBundle sky(skyBytes.data(), std::uint32_t(skyBytes.size()));
    EXPECT_EQ(sky.getNumMipLevels(), 1u);
    expectAxesCube(bundleFaces(sky, 0), int(sky.getInfo().pixelWidth), kFilament, 1.0, axesRadiance, "axes_skybox.ktx");

    // The SH as Filament reads it: E / pi = 1/2 + sinc(pi / w)^4 (M d) / 3 with M the mirror
    // and w cmgen's automatic cut-off for a never-negative map.
    filament::math::float3 sh[9];
    ASSERT_TRUE(ibl.getSphericalHarmonics(sh));
    const double w = iblab::testing::cmgenNeverNegativeCutoff();
    const double w1 = std::pow(std::sin(std::numbers::pi / w) / (std::numbers::pi / w), 4) / 3.0;
    // Filament's polynomial order: 1, y, z, x, ...; red varies with iblab x = -x, green with
    // y, blue with iblab z = -z.
    EXPECT_NEAR(sh[0].r, 0.5, 0.01);
    EXPECT_NEAR(sh[3].r, -w1, 0.01);
    EXPECT_NEAR(sh[1].g, w1, 0.01);
    EXPECT_NEAR(sh[2].b, -w1, 0.01);
    EXPECT_NEAR(sh[3].g, 0.0, 0.01);
    for (int i = 4; i < 9; ++i) EXPECT_NEAR(sh[i].r, 0.0, 0.01) << i;
#endif
}

// A Radiance .hdr (flat RGBE scanlines) for cmgen, whose EXR decoder refuses some of the
// compressions the repository's maps use.
void writeHdr(const std::filesystem::path& path, const ImageRGB32F& image)
{
    std::ofstream out(path, std::ios::binary);
    out << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " << image.height << " +X " << image.width << "\n";
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const glm::vec3 c = image.at(x, y);
            const float v = std::max({c.r, c.g, c.b});
            unsigned char rgbe[4] = {0, 0, 0, 0};
            if (v > 1e-32f) {
                int e = 0;
                const float scale = std::frexp(v, &e) * 256.0f / v;
                rgbe[0] = (unsigned char)(c.r * scale);
                rgbe[1] = (unsigned char)(c.g * scale);
                rgbe[2] = (unsigned char)(c.b * scale);
                rgbe[3] = (unsigned char)(e + 128);
            }
            out.write(reinterpret_cast<const char*>(rgbe), 4);
        }
}

FilamentSh readShTxt(const std::filesystem::path& path)
{
    std::ifstream in(path);
    FilamentSh sh{};
    std::string line;
    for (int i = 0; i < 9 && std::getline(in, line); ++i)
        if (std::sscanf(line.c_str(), " (%lf, %lf, %lf)", &sh[std::size_t(i)].x, &sh[std::size_t(i)].y, &sh[std::size_t(i)].z) != 3)
            ADD_FAILURE() << path << ": cannot read line " << i << ": " << line;
    return sh;
}

// The `filament` layout's mip count against cmgen's own _ibl.ktx (KTX 1.1 header field
// numberOfMipmapLevels, bytes 56-59) at face sizes around its 16^2 minimum
// (iblRoughnessPrefilter: (log2 size + 1) - log2 16, every level when the face is not above
// 16): cmgen's generated UV grid (an input name that is no file) keeps it fast.
TEST(EngineExportLayout, FilamentMipCountIsCmgens)
{
    if (std::system("command -v cmgen > /dev/null 2>&1") != 0)
        GTEST_SKIP() << "cmgen is not installed (Debian's libfilament-tools, scripts/install-deps.sh)";
    TempDirectory dir("export-cmgen-levels");
    for (int size : {16, 64, 256}) {
        const std::filesystem::path out = dir.path() / ("c" + std::to_string(size));
        const std::string command = "cmgen -q --format=ktx --size=" + std::to_string(size) + " --ibl-samples=2 --deploy='" + out.string() + "' uv4 > /dev/null 2>&1";
        ASSERT_EQ(std::system(command.c_str()), 0) << command;
        std::ifstream in(out / (out.filename().string() + "_ibl.ktx"), std::ios::binary);
        std::uint32_t header[16] = {};
        ASSERT_TRUE(in.read(reinterpret_cast<char*>(header), sizeof header)) << size;
        EXPECT_EQ(header[14], std::uint32_t(bake::engineLayout(bake::EngineFormat::Filament, size).levels)) << "face " << size;
    }
}

// The exported SH against cmgen's on the same map: within 3% per band. Maps: a repository
// map and builtin:sun (a bright disc, where cmgen's automatic window narrows).
TEST_F(EngineExport, ShAgreesWithCmgenPerBand)
{
    if (std::system("command -v cmgen > /dev/null 2>&1") != 0)
        GTEST_SKIP() << "cmgen is not installed (Debian's libfilament-tools, scripts/install-deps.sh)";
    gl::ShaderLibrary shaders = testing::bakeShaderLibrary();
    TempDirectory dir("export-cmgen");
    for (const std::string& spec : {std::string(IBLAB_ASSET_DIR) + "/environments/courtyard.exr", std::string("builtin:sun?width=512&size=5&intensity=300")}) {
        SCOPED_TRACE(spec);
        Environment environment = loadEnvironment(spec);
        const std::filesystem::path hdr = dir.path() / "map.hdr";
        writeHdr(hdr, environment.image);
        // cmgen reads what the .hdr holds: bake from the same rounded texels.
        environment = loadEnvironment(hdr.string());
        const std::filesystem::path cmgenDir = dir.path() / "cmgen";
        std::filesystem::remove_all(cmgenDir);
        const std::string command = "cmgen -q --format=ktx --size=256 --ibl-samples=2 --deploy='" + cmgenDir.string() + "' '" + hdr.string() + "'";
        ASSERT_EQ(std::system(command.c_str()), 0) << command;
        const bake::BakeResult result = testing::runBake(shaders, environment, testing::smallBakeSettings());
        const std::filesystem::path ours = dir.path() / "ours";
        bake::exportForEngine(shaders, environment, result, bake::EngineFormat::Filament, ours);
        const FilamentSh a = readShTxt(ours / "sh.txt");
        const FilamentSh b = readShTxt(cmgenDir / "sh.txt");
        for (int band = 0; band < 3; ++band) {
            EXPECT_LT(filamentBandDifference(a, b, band), 0.03) << "band " << band;
            std::printf("%s: band %d differs from cmgen's by %.4f\n", spec.c_str(), band, filamentBandDifference(a, b, band));
        }
    }
}

} // namespace
} // namespace iblab
