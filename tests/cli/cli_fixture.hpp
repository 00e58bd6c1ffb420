#pragma once
// The command-line tests' fixture: runs the real iblab executable headless in a directory
// of the test's own, as a user's script would, and reads back what it wrote.
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <sys/wait.h>

#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>

namespace iblab::cli_testing {

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

// The RGBA floats of an EXR (or any image OpenImageIO reads), top row first; empty when it
// cannot be read.
inline std::vector<float> readExr(const fs::path& path, int& width)
{
    auto input = OIIO::ImageInput::open(path.string());
    if (!input) return {};
    width = input->spec().width;
    std::vector<float> pixels(std::size_t(input->spec().width * input->spec().height * 4));
    input->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, pixels.data());
    return pixels;
}

inline int lineCount(const std::string& text)
{
    int lines = 0;
    for (char c : text) lines += c == '\n';
    return lines;
}

} // namespace iblab::cli_testing
