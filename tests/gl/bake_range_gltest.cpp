// A map brighter than a half float: a half-float cube stores at most 65504, and a sun wider
// than mip 1's lobe prefilters to about its own radiance there (a 2 degree sun of 1e6 read
// 0.59 at mip 1, clipped). BakeJob::cubeFormat bakes such a map in floats, its result says so
// in a note, and bake.json records each cube's format, so that the cache gives the same floats
// back.
// An engine export, in half floats, clips at 65504 (it wrote +Inf).
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bake/bake_accuracy.hpp"
#include "bake/bake_cache.hpp"
#include "bake/engine_export.hpp"
#include "bake_test_support.hpp"
#include "gl_test_fixture.hpp"
#include "io/environment.hpp"
#include "io/ktx_cube.hpp"
#include "io/ktx_writer.hpp"

namespace iblab {
namespace {

using testing::GlTest;
using testing::kPerMipBound;


// Mips with roughness > 0, at a 32 x 32 grid of texel centres per face: the clipped texels
// lie within a few degrees of the sun, which the default 16 x 16 grid can step over.
std::vector<double> finePerMipErrors(const bake::BakeResult& result, const Environment& environment, gl::ShaderLibrary& shaders)
{
    bake::AccuracyOptions options;
    options.texelsPerFaceEdge = 32;
    std::vector<double> errors;
    for (const bake::PrefilterLevelError& e : bake::measureBakeErrors(result, environment.image, shaders, options).prefilter)
        if (e.roughness > 0.0f)
            errors.push_back(e.relativeRmse);
    return errors;
}

bool notes(const bake::BakeResult& result, const std::string& text)
{
    return std::ranges::any_of(result.notes, [&](const std::string& note) { return note.find(text) != std::string::npos; });
}

TEST_F(GlTest, AMapBrighterThanAHalfFloatIsBakedInFloats)
{
    auto shaders = testing::bakeShaderLibrary();
    const bake::BakeSettings settings = bake::defaultPreset();
    ASSERT_EQ(settings.precision, bake::Precision::Half);
    const Environment environment = loadEnvironment("builtin:sun?width=1024&size=2&intensity=1e6&sky=1&elevation=30");
    testing::TempDirectory dir("bake-range");
    bake::BakeCache cache(dir.path());
    const bake::BakeResult baked = testing::runBake(shaders, environment, settings, &cache);
    const std::vector<double> errors = finePerMipErrors(baked, environment, shaders);
    ASSERT_EQ(errors.size(), 5u);
    for (std::size_t m = 0; m < errors.size(); ++m)
        EXPECT_LE(errors[m], kPerMipBound) << environment.source << " mip " << m + 1;
    EXPECT_TRUE(notes(baked, "baked in 32-bit floats"));
    // The cache gives back what was baked, in the format it was baked in.
    const bake::BakeResult loaded = testing::runBake(shaders, environment, settings, &cache);
    ASSERT_TRUE(loaded.fromCache);
    for (const bake::BakeResult* result : {&baked, &loaded}) {
        EXPECT_EQ(result->environmentCube.internalFormat, GLenum(GL_RGBA32F));
        EXPECT_EQ(result->irradianceCube.internalFormat, GLenum(GL_RGBA32F));
        EXPECT_EQ(result->prefiltered.internalFormat, GLenum(GL_RGBA32F));
    }
    EXPECT_EQ(finePerMipErrors(loaded, environment, shaders), errors);
    // The engines' layouts are half floats: a file clips at 65504 and says so; past it a half
    // is +Inf, which the exporter wrote before (every texel of the sun, repaired on reading).
    const bake::ExportReport report = bake::exportForEngine(shaders, environment, baked, bake::EngineFormat::Filament, dir.path() / "filament");
    EXPECT_TRUE(report.clippedToHalf);
    for (const std::filesystem::path& file : report.files) {
        if (file.extension() != ".ktx") continue;
        const KtxCube cube = readKtxCube(file.string());
        EXPECT_EQ(cube.repairedComponents, 0u) << file;
        float peak = 0.0f;
        for (const ImageRGB32F& level : cube.levels)
            peak = std::max(peak, *std::ranges::max_element(level.texels));
        EXPECT_EQ(peak, 65504.0f) << file;
    }
}

// At most 65504 in every channel, a map stays in half floats: the same sun at 6e4.
TEST_F(GlTest, AMapWithinAHalfFloatStaysInHalfFloats)
{
    auto shaders = testing::bakeShaderLibrary();
    const Environment environment = loadEnvironment("builtin:sun?width=1024&size=2&intensity=6e4&sky=1&elevation=30");
    const bake::BakeResult result = testing::runBake(shaders, environment, bake::defaultPreset());
    EXPECT_EQ(result.environmentCube.internalFormat, GLenum(GL_RGBA16F));
    EXPECT_EQ(result.prefiltered.internalFormat, GLenum(GL_RGBA16F));
    EXPECT_FALSE(notes(result, "32-bit floats"));
}

// Another tool's bake in 32-bit floats can be as bright, and its cubes are uploaded as they
// are: in floats too (a half-float upload clipped them, and past 65504 is +Inf).
TEST_F(GlTest, AnImportedBakeBrighterThanAHalfFloatIsUploadedInFloats)
{
    auto shaders = testing::bakeShaderLibrary();
    testing::TempDirectory dir("bake-range-import");
    auto cube = [](int size, int levels, float value) {
        ktx::KtxTexture t;
        t.size = size;
        t.faces = 6;
        t.pixelType = ktx::PixelType::Float;
        for (int level = 0; level < levels; ++level)
            t.levels.emplace_back(std::size_t(6) * std::size_t(t.levelSize(level)) * std::size_t(t.levelSize(level)) * 4, value);
        return t;
    };
    ktx::KtxTexture specular = cube(16, 5, 1.0f);
    specular.levels[0][0] = specular.levels[0][1] = specular.levels[0][2] = 1e5f; // one bright texel of mip 0
    ktx::writeKtx2((dir.path() / "specular.ktx2").string(), specular);
    ktx::writeKtx2((dir.path() / "diffuse.ktx2").string(), cube(8, 1, 3.14159f));
    const Environment environment = loadEnvironment(dir.path().string());
    ASSERT_TRUE(environment.imported);
    const bake::BakeResult result = testing::runBake(shaders, environment, bake::defaultPreset());
    EXPECT_EQ(result.prefiltered.internalFormat, GLenum(GL_RGBA32F));
    EXPECT_EQ(result.environmentCube.internalFormat, GLenum(GL_RGBA32F));
    float peak = 0.0f;
    for (const glm::vec4& t : bake::readCubeLevel(result.prefiltered, 0).texels)
        peak = std::max({peak, t.r, t.g, t.b});
    EXPECT_EQ(peak, 1e5f);
    EXPECT_TRUE(notes(result, "32-bit floats"));
}

} // namespace
} // namespace iblab
