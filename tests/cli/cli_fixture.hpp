#pragma once
// The fixture of the CLI suites: runs the real iblab executable headless, in a directory
// and with a bake cache of the test's own, as a user's script would.
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <sys/wait.h>

#include <gtest/gtest.h>

namespace cli_test {

namespace fs = std::filesystem;

struct Result {
    int exitCode = -1;
    std::string out;
    std::string err;
};

class Cli : public ::testing::Test {
protected:
    void SetUp() override
    {
        dir = fs::temp_directory_path() / ("iblab-cli-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }

    // Runs iblab in the test's directory with DISPLAY unset, so that the run is headless
    // whatever the machine has, and with a bake cache of its own.
    Result run(const std::string& arguments, const std::string& extraEnvironment = "") const
    {
        const fs::path errFile = dir / "stderr.txt";
        const std::string command = "cd '" + dir.string() + "' && env -u DISPLAY -u WAYLAND_DISPLAY IBLAB_CACHE_DIR='" + (dir / "cache").string() + "' " +
                                    extraEnvironment + " '" IBLAB_EXECUTABLE "' " + arguments +
                                    " 2> '" + errFile.string() + "'";
        Result result;
        FILE* pipe = popen(command.c_str(), "r");
        std::array<char, 4096> buffer{};
        while (std::fgets(buffer.data(), int(buffer.size()), pipe)) result.out += buffer.data();
        const int status = pclose(pipe);
        result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        std::ifstream err(errFile);
        result.err.assign(std::istreambuf_iterator<char>(err), {});
        return result;
    }

    fs::path dir;
};

inline int lineCount(const std::string& text)
{
    int lines = 0;
    for (char c : text) lines += c == '\n';
    return lines;
}

} // namespace cli_test
