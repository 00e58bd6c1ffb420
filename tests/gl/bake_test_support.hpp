#pragma once
// Small bakes for the bake gltests: tiny environments and settings that run in tens of
// milliseconds on llvmpipe, and helpers that build environments directly from images.
#include <filesystem>
#include <functional>
#include <unistd.h>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bake/bake_accuracy.hpp"
#include "bake/bake_job.hpp"
#include "bake/bake_settings.hpp"
#include "io/environment.hpp"
#include "gl/shader_library.hpp"

namespace iblab::testing {

// The default preset scaled down: every output present, every pass of the bake exercised
// (the irradiance cube of `irradiance`, PDF filtering with growing sample counts, both LUTs),
// nothing large. Each irradiance method's settings are small, whichever is chosen.
inline constexpr std::array<bake::IrradianceMethod, 3> kIrradianceCubeMethods{
    bake::IrradianceMethod::Riemann, bake::IrradianceMethod::Importance, bake::IrradianceMethod::Moments};

inline bake::BakeSettings smallBakeSettings(bake::IrradianceMethod irradiance = bake::IrradianceMethod::Moments)
{
    bake::BakeSettings s = bake::defaultPreset();
    s.irradiance = irradiance;
    s.riemann = {.faceSize = 8, .sampleDelta = 0.05f, .mipFiltering = false, .mipBias = 0.0f};
    s.importance = {.faceSize = 8, .samples = 256, .mipFiltering = true, .mipBias = 0.0f};
    s.moments = {.faceSize = 8, .sourceFaceSize = 4};
    s.prefilter = {.faceSize = 16,
                   .levels = 5,
                   .layout = bake::RoughnessLayout::Linear,
                   .samples = 64,
                   .sampleGrowth = 2.0f,
                   .mipSampleScale = {},
                   .mipFiltering = true,
                   .mipBias = 0.0f,
                   .mirrorCopy = true,
                   .brightTexels = 0,
                   .brightThreshold = 4.0f};
    s.lut = {.size = 16, .samples = 256, .schlickGgx = true, .heightCorrelatedSmith = true};
    return s;
}

// The shipped shaders, as the bake passes load them.
inline gl::ShaderLibrary bakeShaderLibrary() { return gl::ShaderLibrary(IBLAB_SHADER_DIR); }

inline Environment environmentFromImage(ImageRGB32F image, std::string name)
{
    Environment e;
    e.source = std::move(name);
    e.image = std::move(image);
    e.contentHash = contentHash(e.image);
    return e;
}

inline bake::BakeResult runBake(gl::ShaderLibrary& shaders, const Environment& environment, const bake::BakeSettings& settings,
                                bake::BakeCache* cache = nullptr)
{
    return bake::BakeJob(shaders, environment, settings, cache).runToCompletion();
}

// Per-mip relative RMSE of a bake's prefilter at the texel centres (mips with roughness > 0).
inline std::vector<double> perMipErrors(gl::ShaderLibrary& shaders, const Environment& environment, const bake::BakeSettings& settings)
{
    const bake::BakeResult result = runBake(shaders, environment, settings);
    std::vector<double> errors;
    for (const bake::PrefilterLevelError& e : bake::measureBakeErrors(result, environment.image, shaders, {}).prefilter)
        if (e.roughness > 0.0f)
            errors.push_back(e.relativeRmse);
    return errors;
}

// Issue #29's bound on every prefiltered mip with roughness > 0 (relative RMSE at texel centres).
inline constexpr double kPerMipBound = 0.05;

// Every mip from firstMip (1: the first with roughness > 0) within kPerMipBound.
inline void expectWithinPerMipBound(const std::vector<double>& errors, const std::string& source, std::size_t firstMip = 1)
{
    ASSERT_EQ(errors.size(), 5u) << source;
    for (std::size_t m = firstMip - 1; m < errors.size(); ++m)
        EXPECT_LE(errors[m], kPerMipBound) << source << " mip " << m + 1;
}

// A width x width/2 grey map whose texel (x, y) holds value(x, y), named source.
inline Environment greyMap(std::string source, int width, std::uint32_t hash, const std::function<float(int, int)>& value)
{
    Environment e;
    e.source = std::move(source);
    e.image = ImageRGB32F(width, width / 2);
    for (int y = 0; y < e.image.height; ++y)
        for (int x = 0; x < e.image.width; ++x)
            for (int c = 0; c < 3; ++c)
                e.image.texels[e.image.offset(x, y) + std::size_t(c)] = value(x, y);
    e.contentHash = hash;
    return e;
}

// A fresh empty directory under the system temp dir, removed by the destructor.
class TempDirectory {
public:
    explicit TempDirectory(const std::string& name)
        : path_(std::filesystem::temp_directory_path() / ("iblab-" + name + "-" + std::to_string(::getpid())))
    {
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~TempDirectory()
    {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

} // namespace iblab::testing
