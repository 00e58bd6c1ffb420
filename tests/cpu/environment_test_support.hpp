#pragma once
// Helpers of the environment loading tests (environment_test.cpp, environment_resampling_test.cpp):
// maps written and read with OpenImageIO directly, independently of the code under test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>

#include "io/environment.hpp"
#include "io/error.hpp"
#include "temp_dir.hpp"

namespace iblab::environment_test {

namespace fs = std::filesystem;

inline const fs::path kSourceDir = IBLAB_SOURCE_DIR;
inline const fs::path kSharedAssets = kSourceDir / ".." / "shared" / "assets";
inline constexpr double kPiD = 3.14159265358979323846;

using iblab::testing::TempDir;

inline void writeImage(const std::string& path, int w, int h, int channels, const std::vector<float>& data,
                OIIO::TypeDesc format = OIIO::TypeDesc::FLOAT, int tile = 0)
{
    OIIO::ImageSpec spec(w, h, channels, format);
    if (tile > 0) {
        spec.tile_width = tile;
        spec.tile_height = tile;
    }
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out) << OIIO::geterror();
    ASSERT_TRUE(out->open(path, spec)) << out->geterror();
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, data.data())) << out->geterror();
    ASSERT_TRUE(out->close());
}

inline std::vector<float> readRaw(const std::string& path, int& w, int& h)
{
    auto in = OIIO::ImageInput::open(path);
    EXPECT_TRUE(in) << OIIO::geterror();
    w = in->spec().width;
    h = in->spec().height;
    std::vector<float> px(std::size_t(w) * std::size_t(h) * 3);
    EXPECT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, px.data()));
    return px;
}

// Independent solid angle of a texel row (same formula as documented, derived here).
inline double rowOmega(int y, int w, int h) { return 2.0 * kPiD / w * (std::cos(kPiD * y / h) - std::cos(kPiD * (y + 1) / h)); }

inline double meanLuminance(const ImageRGB32F& img)
{
    double sum = 0.0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const glm::vec3 c = img.at(x, y);
            sum += rowOmega(y, img.width, img.height) * (0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b);
        }
    return sum / (4.0 * kPiD);
}

inline void expectFiniteNonNegative(const ImageRGB32F& img)
{
    std::size_t bad = 0;
    for (float v : img.texels)
        bad += (std::isfinite(v) && v >= 0.0f) ? 0 : 1;
    EXPECT_EQ(bad, 0u);
}

// Runs f, expects an iblab::Error, returns its message (one line, naming `mustName`).
template <class F>
inline std::string errorOf(F&& f, const std::string& mustName)
{
    try {
        f();
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        EXPECT_NE(what.find(mustName), std::string::npos) << what;
        return what;
    }
    ADD_FAILURE() << "no iblab::Error thrown";
    return {};
}

inline bool hasWarningContaining(const Environment& env, const std::string& word)
{
    for (const std::string& w : env.warnings)
        if (w.find(word) != std::string::npos)
            return true;
    return false;
}


} // namespace iblab::environment_test
