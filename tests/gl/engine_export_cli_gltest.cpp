// `iblab bake --export` from the command line: the option's errors and the files it writes.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bake_test_support.hpp"

namespace iblab {
namespace {

int runIblab(const std::string& arguments, std::string& output)
{
    const std::string command = std::string(IBLAB_EXECUTABLE) + " " + arguments + " 2>&1";
    FILE* pipe = popen(command.c_str(), "r");
    char buffer[4096];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) output.append(buffer, n);
    return pclose(pipe);
}

// The JSON report in a run's output (the progress and notes on stderr come first).
nlohmann::json reportIn(const std::string& output) { return nlohmann::json::parse(output.substr(output.find('{'))); }

// Bakes builtin:axes 64 wide with `options` and --export FORMAT --json into OUT; the report.
nlohmann::json exportAxes(const std::string& out, const std::string& format, const std::string& options)
{
    std::string output;
    EXPECT_EQ(runIblab("bake --env 'builtin:axes?width=64' --no-cache " + options + " --export " + format + " --json --out '" + out + "'", output), 0)
        << output;
    return reportIn(output);
}

TEST(EngineExportCli, WritesTheEnginesFilesAndRefusesAMissingOut)
{
    std::string output;
    EXPECT_NE(runIblab("bake --env 'builtin:axes?width=64' --no-cache --no-errors --export bevy", output), 0);
    EXPECT_NE(output.find("--export: needs --out"), std::string::npos) << output;
    output.clear();
    EXPECT_NE(runIblab("bake --env 'builtin:axes?width=64' --no-cache --export unreal --out /tmp/x", output), 0);
    EXPECT_NE(output.find("filament"), std::string::npos) << output; // the choices are named
    testing::TempDirectory dir("export-cli");
    const auto json = exportAxes((dir.path() / "studio").string(), "filament", "--no-errors --prefilter-size 32 --prefilter-levels 5");
    EXPECT_EQ(json["export"]["format"], "filament");
    EXPECT_EQ(json["export"]["files"].size(), 3u);
    EXPECT_TRUE(std::filesystem::exists(dir.path() / "studio" / "studio_ibl.ktx"));
    EXPECT_TRUE(std::filesystem::exists(dir.path() / "studio" / "studio_skybox.ktx"));
    EXPECT_TRUE(std::filesystem::exists(dir.path() / "studio" / "sh.txt"));
}

// `iblab measure` on an exported bake (cmgen's layout, read back by the import) answers in
// the measures and JSON keys of `iblab bake --json`'s "errors", one entry per level it holds.
TEST(EngineExportCli, MeasureReportsAForeignBakeInTheBakesErrorKeys)
{
    testing::TempDirectory dir("export-measure");
    const std::string out = (dir.path() / "axes").string();
    const auto b = exportAxes(out, "filament", "--prefilter-size 64")["errors"];
    std::string measured;
    ASSERT_EQ(runIblab("measure --env 'builtin:axes?width=64' --no-cache --json --bake '" + out + "/axes_ibl.ktx'", measured), 0) << measured;
    const auto m = reportIn(measured)["errors"];
    std::vector<std::string> bakeKeys, measureKeys;
    for (const auto& [key, value] : b.items()) bakeKeys.push_back(key);
    for (const auto& [key, value] : m.items()) measureKeys.push_back(key);
    EXPECT_EQ(measureKeys, bakeKeys);
    // A 64 face in cmgen's layout: (6 + 1) - 4 levels, each measured with the bake's keys.
    ASSERT_EQ(m["prefilter"].size(), 3u) << measured;
    for (const auto& level : m["prefilter"]) {
        for (const auto& [key, value] : b["prefilter"][0].items()) EXPECT_TRUE(level.contains(key)) << key;
        EXPECT_LT(level["relative_rmse"].get<double>(), 0.05) << level.dump(); // a smooth map, read back in half floats
    }
}

// `iblab bake --env DIR` with another tool's bake in DIR (the Khronos pair exported here)
// loads that bake, as the GUI's path field and drop do; it took the directory for a folder
// of maps and found none.
TEST(EngineExportCli, BakeOfAKhronosBakesDirectoryImportsIt)
{
    testing::TempDirectory dir("export-import");
    const std::string out = (dir.path() / "khronos").string();
    exportAxes(out, "khronos", "--no-errors --prefilter-size 32");
    std::string imported;
    ASSERT_EQ(runIblab("bake --env '" + out + "' --no-cache --no-errors --json", imported), 0) << imported;
    const auto json = reportIn(imported);
    EXPECT_EQ(json["source"], out);
    EXPECT_FALSE(json.contains("maps")) << "one bake, not a directory of maps";
    EXPECT_NE(imported.find("imported glTF-IBL-Sampler bake"), std::string::npos) << imported;
    EXPECT_FALSE(json["timings_ms"].contains("prefilter")) << "uploaded, not baked";
    EXPECT_EQ(json["textures"]["prefiltered"]["size"], 32);
}

} // namespace
} // namespace iblab
