// `iblab render --method reference`: the full integral, headless and run to completion, as
// EXR and PNG, alone or as either side of the A/B split.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_fixture.hpp"

namespace {

using iblab::cli_testing::Cli;
using iblab::cli_testing::readExr;
using iblab::cli_testing::Result;
namespace fs = std::filesystem;

const std::string kScene = " --env builtin:studio?width=128 --reference-width 64 --width 40 --height 40 --metallic 0.5 --roughness 0.6 --gl-debug";

// Pixels whose values differ by more than 1% of the larger: the two images show different things there.
int differingPixels(const std::vector<float>& a, const std::vector<float>& b)
{
    int differing = 0;
    for (std::size_t i = 0; i + 3 < a.size() && i + 3 < b.size(); i += 4) {
        bool differs = false;
        for (std::size_t c = 0; c < 3; ++c) differs = differs || std::abs(a[i + c] - b[i + c]) > 0.01f * std::max(std::abs(a[i + c]), std::abs(b[i + c]));
        differing += differs;
    }
    return differing;
}

// The frame is the reference the error view measures against: the error of the one against
// the other is the half-float rounding of the frame alone (2^-11 relative, 4.9e-4), where
// the split sum is off by percents.
TEST_F(Cli, ReferenceMethodRendersTheFullIntegralHeadless)
{
    const Result exr = run("render --method reference" + kScene + " --json -o reference.exr");
    ASSERT_EQ(exr.exitCode, 0) << exr.err;
    const auto report = nlohmann::json::parse(exr.out);
    EXPECT_GT(report["timings_ms"]["reference"].get<double>(), 0.0) << "the reference ran before the frame";
    const Result png = run("render --method reference" + kScene + " -o reference.png");
    ASSERT_EQ(png.exitCode, 0) << png.err;
    EXPECT_TRUE(fs::exists(dir / "reference.png"));

    const Result error = run("render --method reference --view error" + kScene + " --json -o error.png");
    ASSERT_EQ(error.exitCode, 0) << error.err;
    const auto frame = nlohmann::json::parse(error.out)["error"]["frame"];
    EXPECT_GT(frame["pixels"].get<int>(), 200);
    EXPECT_LT(frame["max_relative"].get<double>(), 1e-3);

    ASSERT_EQ(run("render --method splitsum" + kScene + " -o splitsum.exr").exitCode, 0);
    int width = 0;
    const std::vector<float> reference = readExr(dir / "reference.exr", width), splitSum = readExr(dir / "splitsum.exr", width);
    ASSERT_EQ(width, 40);
    EXPECT_GT(differingPixels(reference, splitSum), 100) << "the reference is not the split-sum preview";
}

// With --split, either side can be the reference: its columns are the reference's frame,
// the other side's columns the other method's, value for value.
TEST_F(Cli, ReferenceMethodIsEitherSideOfTheSplit)
{
    ASSERT_EQ(run("render --method reference" + kScene + " -o reference.exr").exitCode, 0);
    ASSERT_EQ(run("render --method splitsum" + kScene + " -o splitsum.exr").exitCode, 0);
    int width = 0;
    const std::vector<float> reference = readExr(dir / "reference.exr", width), splitSum = readExr(dir / "splitsum.exr", width);
    ASSERT_EQ(width, 40);
    ASSERT_GT(differingPixels(reference, splitSum), 100) << "A and B must differ for this to prove anything";
    for (const bool referenceOnTheLeft : {true, false}) {
        const std::string sides = referenceOnTheLeft ? " --method reference --b-method splitsum" : " --method splitsum --b-method reference";
        const Result r = run("render --split 0.5" + sides + kScene + " -o split.exr");
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const std::vector<float> both = readExr(dir / "split.exr", width);
        ASSERT_EQ(both.size(), reference.size());
        for (std::size_t i = 0; i < both.size(); ++i) {
            const int x = int(i / 4 % std::size_t(width));
            const bool referenceSide = (x < 20) == referenceOnTheLeft;
            ASSERT_EQ(both[i], referenceSide ? reference[i] : splitSum[i]) << "pixel column " << x << ", reference on the left " << referenceOnTheLeft;
        }
    }
}

// The fitted lobe's diffuse under a sun of 1e6: the irradiance cube and SH9 hold the map less
// the shading lights, and each light adds flux max(0, n.l) per pixel. Read from the cube
// alone, the terminator was a 32 face's texel wide and lit the dark side beside it (relative
// RMSE 0.064 on this sphere, 0.011 now); SH9 rang with the sun (42).
TEST_F(Cli, FittedLobeDiffuseSumsTheSunExactly)
{
    for (const char* diffuse : {"irradiance-cube", "sh9"}) {
        const Result r = run(std::string("render --env 'builtin:sun?size=0.5&intensity=1e6' --metallic 0 --roughness 1 --base-color 0.8,0.8,0.8 "
                                         "--view error --reference-width 512 --width 96 --height 96 --json -o error.png --diffuse ") + diffuse);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const auto frame = nlohmann::json::parse(r.out)["error"]["frame"];
        EXPECT_GT(frame["pixels"].get<int>(), 2000);
        EXPECT_LT(frame["relative_rmse"].get<double>(), 0.025) << diffuse;
    }
}

} // namespace
