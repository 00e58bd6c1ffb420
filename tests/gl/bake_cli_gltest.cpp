// `iblab bake`, `iblab sh` and `iblab lut` as a user runs them: the files and JSON they
// write, read back independently (OpenImageIO, nlohmann_json), and their failures.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <sys/wait.h>

#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>
#include <nlohmann/json.hpp>

#include "bake_test_support.hpp"
#include "ibl/brdf_lut.hpp"
#include "ibl/sh.hpp"

namespace iblab {
namespace {

namespace fs = std::filesystem;
using testing::TempDirectory;

struct CommandRun {
    int status = -1;
    std::string out;
    std::string err;
};

// Runs the iblab executable with `arguments` (shell syntax), the cache in `cacheDir`.
CommandRun iblab(const std::string& arguments, const fs::path& scratch)
{
    const fs::path errPath = scratch / "stderr.txt";
    const std::string command = "IBLAB_CACHE_DIR='" + (scratch / "cache").string() + "' '" + IBLAB_EXECUTABLE + "' " + arguments +
                                " 2> '" + errPath.string() + "'";
    CommandRun run;
    FILE* pipe = ::popen(command.c_str(), "r");
    if (!pipe)
        return run;
    std::array<char, 4096> buffer{};
    std::size_t n = 0;
    while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
        run.out.append(buffer.data(), n);
    const int status = ::pclose(pipe);
    run.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::ifstream errFile(errPath);
    std::stringstream text;
    text << errFile.rdbuf();
    run.err = text.str();
    return run;
}

int lineCount(const std::string& text)
{
    int lines = 0;
    for (char c : text)
        lines += c == '\n';
    return lines + (!text.empty() && text.back() != '\n');
}

struct Exr {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::vector<float> pixels;
    float at(int x, int y, int c) const { return pixels[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * std::size_t(channels) + std::size_t(c)]; }
};

Exr readExr(const fs::path& path)
{
    Exr exr;
    auto in = OIIO::ImageInput::open(path.string());
    if (!in)
        return exr;
    exr.width = in->spec().width;
    exr.height = in->spec().height;
    exr.channels = in->spec().nchannels;
    exr.pixels.resize(std::size_t(exr.width) * std::size_t(exr.height) * std::size_t(exr.channels));
    in->read_image(0, 0, 0, exr.channels, OIIO::TypeDesc::FLOAT, exr.pixels.data());
    return exr;
}

TEST(BakeCli, LutFileStartsWithRoughnessZero)
{
    TempDirectory dir("cli-lut");
    constexpr int kSize = 16;
    constexpr int kSamples = 128;
    for (bool multiscatter : {false, true}) {
        const fs::path file = dir.path() / (multiscatter ? "ms.exr" : "plain.exr");
        const GeometryTerm term = multiscatter ? GeometryTerm::HeightCorrelatedSmith : GeometryTerm::SchlickGGX;
        const CommandRun run = iblab("lut --size 16 --samples 128 --geometry " + std::string(multiscatter ? "correlated --multiscatter" : "schlick") +
                                  " -o '" + file.string() + "'",
                              dir.path());
        ASSERT_EQ(run.status, 0) << run.err;
        const Exr exr = readExr(file);
        ASSERT_EQ(exr.width, kSize);
        ASSERT_EQ(exr.height, kSize);
        ASSERT_EQ(exr.channels, 3);
        // Scanline 0 of the file is roughness 0.5 / 16, the last one 15.5 / 16, each texel
        // at n.v = (x + 0.5) / 16. The values differ by up to 0.5 between the two rows, the
        // tolerance is half-float storage and float arithmetic (see bake_accuracy_gltest).
        for (int row : {0, kSize - 1})
            for (int x = 0; x < kSize; ++x) {
                const glm::dvec3 cpu = integrateSplitSumBrdf((x + 0.5) / kSize, (row + 0.5) / kSize, kSamples, term);
                EXPECT_NEAR(exr.at(x, row, 0), cpu.x, 1e-3) << "A at row " << row << " x " << x;
                EXPECT_NEAR(exr.at(x, row, 1), cpu.y, 1e-3) << "B at row " << row << " x " << x;
                EXPECT_NEAR(exr.at(x, row, 2), multiscatter ? cpu.z : 0.0, 1e-3) << "third channel at row " << row;
            }
    }
}

TEST(BakeCli, ShPrintsTheBasisAndBothCoefficientSets)
{
    TempDirectory dir("cli-sh");
    const CommandRun run = iblab("sh --env 'builtin:sky?width=128&top=1&ground=0.1' --json", dir.path());
    ASSERT_EQ(run.status, 0) << run.err;
    const nlohmann::json j = nlohmann::json::parse(run.out);
    EXPECT_EQ(j["basis"], kSh9Convention);
    ASSERT_EQ(j["radiance"].size(), 9u);
    ASSERT_EQ(j["irradiance"].size(), 9u);
    // The sky differs between the hemispheres y > 0 and y < 0 and nowhere else, so besides
    // (0,0) only (1,-1) = sqrt(3 / 4 pi) y is non-zero: integral of L y = pi * 1 - pi * 0.1.
    // Tolerance: the projection evaluates y at row centres, a midpoint rule good to
    // (pi / height)^2 / 8 = 3e-4 relative at height 64.
    const double y1 = std::sqrt(3.0 / (4.0 * kPi)) * 0.9 * kPi;
    const double y0 = 0.5 * std::sqrt(1.0 / kPi) * 4.0 * kPi * 0.55;
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(j["radiance"][0][c].get<double>(), y0, 1e-3 * y0);
        EXPECT_NEAR(j["radiance"][1][c].get<double>(), y1, 1e-3 * y1);
        for (int i = 2; i < 9; ++i)
            EXPECT_NEAR(j["radiance"][i][c].get<double>(), 0.0, 2e-3 * y0) << "coefficient " << i;
        // Irradiance: band 0 times pi, band 1 times 2 pi / 3.
        EXPECT_NEAR(j["irradiance"][0][c].get<double>(), kPi * y0, 1e-3 * y0);
        EXPECT_NEAR(j["irradiance"][1][c].get<double>(), 2.0 * kPi / 3.0 * y1, 2.0 * kPi / 3.0 * 1e-3 * y1);
    }
}

TEST(BakeCli, BakeWritesItsOutputsAndReportsTimingsAndErrors)
{
    TempDirectory dir("cli-bake");
    const fs::path out = dir.path() / "out";
    const CommandRun run = iblab("bake --env 'builtin:sky?width=64' --json --no-cache --prefilter-size 16 --prefilter-levels 3 "
                          "--irradiance importance --importance-size 8 --importance-samples 64 --moments-size 8 --lut-size 16 --lut-samples 64 --out '" +
                              out.string() + "'",
                          dir.path());
    ASSERT_EQ(run.status, 0) << run.err;
    const nlohmann::json j = nlohmann::json::parse(run.out);
    for (const char* phase : {"shaders", "upload", "environment_cube", "sh9", "irradiance_importance", "prefilter", "brdf_lut",
                              "total"})
        EXPECT_TRUE(j["timings_ms"].contains(phase)) << phase;
    // The longest step is one of the phases' steps: no longer than its phase, and named by it.
    const std::string longest = j["longest_step"]["name"].get<std::string>();
    const std::string longestPhase = longest.substr(0, longest.find('.'));
    ASSERT_TRUE(j["timings_ms"].contains(longestPhase)) << longest;
    EXPECT_GT(j["longest_step"]["milliseconds"].get<double>(), 0.0);
    EXPECT_LE(j["longest_step"]["milliseconds"].get<double>(), j["timings_ms"][longestPhase].get<double>());
    EXPECT_EQ(j["errors"]["prefilter"].size(), 3u);
    EXPECT_TRUE(j["errors"]["irradiance"].contains("sh"));
    EXPECT_TRUE(j["errors"]["irradiance"].contains("cube_importance"));
    EXPECT_TRUE(j["errors"]["irradiance_shaded"].contains("cube_importance"));
    // One irradiance method per bake: the default's moment cube is not baked beside it.
    EXPECT_FALSE(j["errors"]["irradiance"].contains("cube_moments"));
    EXPECT_FALSE(j["timings_ms"].contains("irradiance_moments"));
    EXPECT_FALSE(fs::exists(out / "irradiance_moments.exr"));
    EXPECT_TRUE(j["errors"]["lut_max_abs"].contains("schlick-ggx"));
    for (const char* file : {"environment.exr", "irradiance_importance.exr", "prefiltered_mip0.exr", "prefiltered_mip2.exr",
                             "sh.json", "bake.json", "brdf_lut_schlick-ggx.exr", "brdf_lut_height-correlated-smith.exr"})
        EXPECT_TRUE(fs::exists(out / file)) << file;
    // A cube level is a strip of six faces: 16 wide, 96 high at mip 0, 4 x 24 at mip 2.
    const Exr mip2 = readExr(out / "prefiltered_mip2.exr");
    EXPECT_EQ(mip2.width, 4);
    EXPECT_EQ(mip2.height, 24);
}

// --error-texel-grid N measures each mip at N x N texel centres per face, or at every texel of
// a smaller face (the default 16 x 16: on these faces of 16 and less, every texel).
TEST(BakeCli, ErrorTexelGridSetsTheDirectionsOfEachMip)
{
    TempDirectory dir("cli-grid");
    const std::string bake = "bake --env 'builtin:sky?width=64' --json --no-cache --prefilter-size 16 --prefilter-levels 3 --lut-size 16 --lut-samples 64";
    for (const auto& [option, grid] : {std::pair{"", 16}, std::pair{" --error-texel-grid 2", 2}, std::pair{" --error-texel-grid 8", 8}}) {
        const CommandRun run = iblab(bake + option, dir.path());
        ASSERT_EQ(run.status, 0) << run.err;
        const nlohmann::json j = nlohmann::json::parse(run.out);
        ASSERT_EQ(j["errors"]["prefilter"].size(), 3u);
        for (int m = 0; m < 3; ++m) {
            const int perEdge = std::min(grid, 16 >> m); // faces of 16, 8, 4
            EXPECT_EQ(j["errors"]["prefilter"][m]["directions"].get<int>(), 6 * perEdge * perEdge) << option << " mip " << m;
        }
    }
    EXPECT_NE(iblab(bake + " --error-texel-grid 0", dir.path()).status, 0);
}

TEST(BakeCli, FailuresAreOneLineNamingTheProblem)
{
    TempDirectory dir("cli-fail");
    const CommandRun missing = iblab("bake --env /nonexistent/missing.exr", dir.path());
    EXPECT_NE(missing.status, 0);
    EXPECT_EQ(lineCount(missing.err), 1) << missing.err;
    EXPECT_NE(missing.err.find("/nonexistent/missing.exr"), std::string::npos) << missing.err;

    const CommandRun badSettings = iblab("bake --env builtin:white --prefilter-size 16 --prefilter-levels 9", dir.path());
    EXPECT_NE(badSettings.status, 0);
    EXPECT_EQ(lineCount(badSettings.err), 1) << badSettings.err;
    EXPECT_NE(badSettings.err.find("prefilter.levels"), std::string::npos) << badSettings.err;

    const CommandRun badOutput = iblab("lut --size 16 -o '" + (dir.path() / "lut.png").string() + "'", dir.path());
    EXPECT_NE(badOutput.status, 0);
    EXPECT_EQ(lineCount(badOutput.err), 1) << badOutput.err;

    const CommandRun unwritable = iblab("lut --size 16 -o /nonexistent/dir/lut.exr", dir.path());
    EXPECT_NE(unwritable.status, 0);
    EXPECT_EQ(lineCount(unwritable.err), 1) << unwritable.err;
    EXPECT_NE(unwritable.err.find("/nonexistent/dir/lut.exr"), std::string::npos) << unwritable.err;

    const CommandRun unknown = iblab("sh --env builtin:nothing", dir.path());
    EXPECT_NE(unknown.status, 0);
    EXPECT_EQ(lineCount(unknown.err), 1) << unknown.err;

    for (const char* command : {"bake", "sh", "lut"})
        EXPECT_EQ(iblab(std::string(command) + " --help", dir.path()).status, 0) << command;
}

} // namespace
} // namespace iblab
