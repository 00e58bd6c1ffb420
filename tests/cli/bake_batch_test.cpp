// `iblab bake` with several maps (issue #15): one process, a progress line per map, one JSON
// report with an entry per map; a bad map fails alone and makes the exit status non-zero.
#include <string>

#include <nlohmann/json.hpp>

#include "cli_fixture.hpp"

namespace {

using namespace iblab::cli_testing;

// Small enough that a map bakes in well under a second on llvmpipe.
const std::string kSmallBake = " --no-errors --json --prefilter-size 16 --prefilter-levels 3 --moments-size 8 --lut-size 16 --lut-samples 64";

TEST_F(Cli, BakeBatchReportsEveryMapAndFailsOnlyTheBadOne)
{
    std::ofstream(dir / "bad.exr") << "not an EXR";
    const Result r = run("bake --env 'builtin:sky?width=64' --env bad.exr --env 'builtin:white?width=64'" + kSmallBake);
    EXPECT_EQ(r.exitCode, 1) << "a map failed: " << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    ASSERT_EQ(j["maps"].size(), 3u) << r.out;
    EXPECT_EQ(j["failed"], 1);
    EXPECT_EQ(j["maps"][0]["source"], "builtin:sky?width=64");
    EXPECT_EQ(j["maps"][2]["source"], "builtin:white?width=64");
    for (int good : {0, 2}) {
        const nlohmann::json& map = j["maps"][good];
        EXPECT_FALSE(map.contains("error")) << map;
        EXPECT_TRUE(map["timings_ms"].contains("prefilter")) << map;
        EXPECT_EQ(map["sh"]["radiance"].size(), 9u) << map;
    }
    // The third map reuses the context the first one made.
    EXPECT_EQ(j["maps"][2]["other_ms"]["context"].get<double>() < 1.0, true) << j["maps"][2]["other_ms"];
    EXPECT_NE(j["maps"][1]["error"].get<std::string>().find("bad.exr"), std::string::npos) << j["maps"][1];
    // One progress line per map on stderr, the failure's saying why.
    EXPECT_NE(r.err.find("[1/3] builtin:sky?width=64: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("[2/3] bad.exr: failed: bad.exr: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("[3/3] builtin:white?width=64: "), std::string::npos) << r.err;
    EXPECT_EQ(lineCount(r.err), 3) << r.err;
}

TEST_F(Cli, BakeOfADirectoryBakesItsMapsInNameOrder)
{
    const fs::path maps = dir / "maps";
    fs::create_directories(maps);
    fs::copy_file(IBLAB_SOURCE_DIR "/assets/environments/sunset.exr", maps / "b-sunset.exr");
    fs::copy_file(IBLAB_SOURCE_DIR "/assets/environments/night.exr", maps / "a-night.EXR");
    std::ofstream(maps / "notes.txt") << "not a map";
    {
        // A PFM is a map too (the directory took only .exr and .hdr): the header, then the rows
        // in this machine's byte order, little-endian on amd64, as the scale's sign says.
        std::ofstream pfm(maps / "c-grey.pfm", std::ios::binary);
        pfm << "PF\n8 4\n-1.0\n";
        const float grey = 2.0f;
        for (int i = 0; i < 8 * 4 * 3; ++i)
            pfm.write(reinterpret_cast<const char*>(&grey), sizeof grey);
    }
    const Result r = run("bake --env maps" + kSmallBake);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    ASSERT_EQ(j["maps"].size(), 3u) << r.out;
    EXPECT_EQ(j["maps"][0]["source"], "maps/a-night.EXR");
    EXPECT_EQ(j["maps"][1]["source"], "maps/b-sunset.exr");
    EXPECT_EQ(j["maps"][2]["source"], "maps/c-grey.pfm");
    EXPECT_EQ(j["failed"], 0);

    // One map named once keeps the single report that scripts read.
    const Result single = run("bake --env maps/b-sunset.exr" + kSmallBake);
    ASSERT_EQ(single.exitCode, 0) << single.err;
    const nlohmann::json one = nlohmann::json::parse(single.out);
    EXPECT_FALSE(one.contains("maps"));
    EXPECT_EQ(one["source"], "maps/b-sunset.exr");
    EXPECT_TRUE(one["timings_ms"].contains("total"));
}

// --no-cache leaves the cache's files alone, but a batch still bakes its LUTs once.
TEST_F(Cli, ABatchWithoutTheCacheBakesTheLutsOnce)
{
    const Result r = run("bake --env 'builtin:sky?width=64' --env 'builtin:white?width=64' --no-cache" + kSmallBake);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    ASSERT_EQ(j["maps"].size(), 2u) << r.out;
    for (const char* term : {"schlick-ggx", "height-correlated-smith"}) {
        EXPECT_EQ(j["maps"][0]["lut_from_cache"][term], false) << j["maps"][0];
        EXPECT_EQ(j["maps"][1]["lut_from_cache"][term], true) << j["maps"][1];
    }
    EXPECT_FALSE(j["other_ms"].contains("cache_write")) << j["other_ms"];
    EXPECT_FALSE(fs::exists(dir / "cache")) << "--no-cache writes no file";
}

// A bake restarts itself with malloc's huge pages (command_support.hpp), one map or a batch;
// a GLIBC_TUNABLES that names the tunable is kept as it is.
TEST_F(Cli, BakesRunWithMallocHugePagesUnlessTheTunableIsSet)
{
    const Result single = run("bake --env 'builtin:sky?width=64'" + kSmallBake);
    ASSERT_EQ(single.exitCode, 0) << single.err;
    EXPECT_EQ(nlohmann::json::parse(single.out)["malloc_huge_pages"], true) << single.out;

    const Result declined = run("bake --env 'builtin:sky?width=64'" + kSmallBake, "GLIBC_TUNABLES=glibc.malloc.hugetlb=0");
    ASSERT_EQ(declined.exitCode, 0) << declined.err;
    EXPECT_EQ(nlohmann::json::parse(declined.out)["malloc_huge_pages"], false) << declined.out;

    const Result batch = run("bake --env 'builtin:sky?width=64' --env 'builtin:white?width=64'" + kSmallBake);
    ASSERT_EQ(batch.exitCode, 0) << batch.err;
    const nlohmann::json j = nlohmann::json::parse(batch.out);
    ASSERT_EQ(j["maps"].size(), 2u) << batch.out;
    for (const nlohmann::json& map : j["maps"]) EXPECT_EQ(map["malloc_huge_pages"], true) << map;
}

} // namespace
