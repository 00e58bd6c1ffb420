// `iblab bake --export` from the command line: the option's errors and the files it writes.
#include <cstdio>
#include <filesystem>
#include <string>

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

TEST(EngineExportCli, WritesTheEnginesFilesAndRefusesAMissingOut)
{
    std::string output;
    EXPECT_NE(runIblab("bake --env 'builtin:axes?width=64' --no-cache --no-errors --export bevy", output), 0);
    EXPECT_NE(output.find("--export: needs --out"), std::string::npos) << output;
    output.clear();
    EXPECT_NE(runIblab("bake --env 'builtin:axes?width=64' --no-cache --export unreal --out /tmp/x", output), 0);
    EXPECT_NE(output.find("filament"), std::string::npos) << output; // the choices are named
    testing::TempDirectory dir("export-cli");
    output.clear();
    const std::string out = (dir.path() / "studio").string();
    ASSERT_EQ(runIblab("bake --env 'builtin:axes?width=64' --no-cache --no-errors --prefilter-size 32 --prefilter-levels 5 --export filament --json --out '" +
                           out + "'",
                       output),
              0)
        << output;
    const auto json = nlohmann::json::parse(output.substr(output.find('{')));
    EXPECT_EQ(json["export"]["format"], "filament");
    EXPECT_EQ(json["export"]["files"].size(), 3u);
    EXPECT_TRUE(std::filesystem::exists(dir.path() / "studio" / "studio_ibl.ktx"));
    EXPECT_TRUE(std::filesystem::exists(dir.path() / "studio" / "studio_skybox.ktx"));
    EXPECT_TRUE(std::filesystem::exists(dir.path() / "studio" / "sh.txt"));
}

} // namespace
} // namespace iblab
