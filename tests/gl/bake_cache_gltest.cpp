// The bake as a job of steps, and its on-disk cache: results loaded from the cache are the
// results baked, corrupt entries are reported by name and rebuilt, the LUT cache ignores
// the environment, and cutting the work into smaller steps changes nothing.
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include <glm/glm.hpp>

#include "bake/bake_cache.hpp"
#include "bake/bake_files.hpp"
#include "bake/bake_job.hpp"
#include "bake/bake_passes.hpp"
#include "bake_test_support.hpp"
#include "io/atomic_file.hpp"
#include "io/error.hpp"
#include "io/image_writer.hpp"
#include "gl_test_fixture.hpp"

namespace iblab {
namespace {

namespace fs = std::filesystem;
using testing::GlTest;
using testing::runBake;
using testing::smallBakeSettings;
using testing::TempDirectory;

gl::ShaderLibrary library() { return gl::ShaderLibrary(IBLAB_SHADER_DIR); }

void expectSameTexels(const bake::BakedTexture& a, const bake::BakedTexture& b, const std::string& what)
{
    ASSERT_EQ(a.size, b.size) << what;
    ASSERT_EQ(a.levels, b.levels) << what;
    for (int level = 0; level < a.levels; ++level) {
        if (a.target == GL_TEXTURE_2D) {
            EXPECT_EQ(bake::read2D(a).texels, bake::read2D(b).texels) << what;
        } else {
            EXPECT_EQ(bake::readCubeLevel(a, level).texels, bake::readCubeLevel(b, level).texels) << what << " level " << level;
        }
    }
}

void expectSameResults(const bake::BakeResult& a, const bake::BakeResult& b)
{
    expectSameTexels(a.environmentCube, b.environmentCube, "environment cube");
    EXPECT_EQ(a.settings.irradiance, b.settings.irradiance);
    expectSameTexels(a.irradianceCube, b.irradianceCube, "irradiance");
    expectSameTexels(a.prefiltered, b.prefiltered, "prefiltered");
    for (GeometryTerm term : bake::kGeometryTerms)
        expectSameTexels(a.lut(term), b.lut(term), std::string(enumName(term)));
    for (std::size_t i = 0; i < a.sh.radiance.c.size(); ++i) {
        EXPECT_EQ(a.sh.radiance.c[i], b.sh.radiance.c[i]);
        EXPECT_EQ(a.sh.irradianceWindowed.c[i], b.sh.irradianceWindowed.c[i]);
    }
}

TEST_F(GlTest, ASecondBakeIsLoadedFromTheCacheUnchanged)
{
    auto shaders = library();
    TempDirectory dir("bake-cache");
    bake::BakeCache cache(dir.path());
    const Environment env = loadEnvironment("builtin:sun?width=64&size=10");
    const bake::BakeResult first = runBake(shaders, env, smallBakeSettings(), &cache);
    EXPECT_FALSE(first.fromCache);
    EXPECT_TRUE(first.notes.empty());
    EXPECT_TRUE(cache.finishWrites().empty()); // the files are written in the background
    EXPECT_TRUE(fs::exists(cache.bakeDirectory(bake::BakeCache::bakeKey(env.contentHash, first.settings, first.shaderFingerprint)) / "bake.json"));

    const bake::BakeResult second = runBake(shaders, env, smallBakeSettings(), &cache);
    EXPECT_TRUE(second.fromCache);
    EXPECT_TRUE(second.lutFromCache[0] && second.lutFromCache[1]);
    EXPECT_EQ(second.phaseMilliseconds(bake::BakePhase::Prefilter), 0.0); // nothing was baked
    // Half floats written as half-float EXR and read back: bit-identical; mips rebuilt by the
    // same pass from the same level 0.
    expectSameResults(first, second);
}

TEST_F(GlTest, TheMirrorMipIsStoredOnceAndLoadedUnchanged)
{
    // The mirror mip is a texel copy of an environment level: the cache stores that level
    // once and copies it back on load, at the environment's own face size (level 0), or from
    // a mip rebuilt on load (an environment face twice the prefilter's: level 1).
    auto shaders = library();
    TempDirectory dir("bake-mirror");
    bake::BakeCache cache(dir.path());
    for (const char* spec : {"builtin:sun?width=64&size=10", "builtin:sun?width=128&size=10"}) {
        SCOPED_TRACE(spec);
        const Environment env = loadEnvironment(spec);
        const bake::BakeResult baked = runBake(shaders, env, smallBakeSettings(), &cache);
        ASSERT_TRUE(cache.finishWrites().empty());
        const fs::path entry = cache.bakeDirectory(bake::BakeCache::bakeKey(env.contentHash, baked.settings, baked.shaderFingerprint));
        EXPECT_FALSE(fs::exists(entry / "prefiltered_mip0.exr"));
        EXPECT_TRUE(fs::exists(entry / "prefiltered_mip1.exr"));
        const bake::BakeResult loaded = runBake(shaders, env, smallBakeSettings(), &cache);
        EXPECT_TRUE(loaded.fromCache);
        EXPECT_TRUE(loaded.notes.empty());
        expectSameResults(baked, loaded);
    }
    // Without the mirror copy the mip is filtered like the others, and has its file.
    bake::BakeSettings filtered = smallBakeSettings();
    filtered.prefilter.mirrorCopy = false;
    const Environment env = loadEnvironment("builtin:sun?width=64&size=10");
    const bake::BakeResult unfiltered = runBake(shaders, env, filtered, &cache);
    ASSERT_TRUE(cache.finishWrites().empty());
    EXPECT_TRUE(fs::exists(cache.bakeDirectory(bake::BakeCache::bakeKey(env.contentHash, filtered, unfiltered.shaderFingerprint)) /
                           "prefiltered_mip0.exr"));
}

TEST_F(GlTest, TheLutCacheIgnoresTheEnvironment)
{
    auto shaders = library();
    TempDirectory dir("lut-cache");
    bake::BakeCache cache(dir.path());
    runBake(shaders, loadEnvironment("builtin:white?width=32"), smallBakeSettings(), &cache);
    const bake::BakeResult other = runBake(shaders, loadEnvironment("builtin:sky?width=32"), smallBakeSettings(), &cache);
    EXPECT_FALSE(other.fromCache);
    EXPECT_TRUE(other.lutFromCache[0] && other.lutFromCache[1]);
    // ... but not the LUT's own settings.
    bake::BakeSettings more = smallBakeSettings();
    more.lut.samples *= 2;
    EXPECT_FALSE(runBake(shaders, loadEnvironment("builtin:sky?width=32"), more, &cache).lutFromCache[0]);
}

TEST_F(GlTest, TheCacheKeyFollowsTheOutputNotTheBookkeeping)
{
    const bake::BakeSettings base = smallBakeSettings();
    const std::string key = bake::BakeCache::bakeKey(42, base, 7);
    bake::BakeSettings s = base;
    s.samplesPerStep *= 4;
    s.preset = "renamed";
    EXPECT_EQ(bake::BakeCache::bakeKey(42, s, 7), key);
    EXPECT_NE(bake::BakeCache::bakeKey(43, base, 7), key);
    EXPECT_NE(bake::BakeCache::bakeKey(42, base, 8), key) << "the shaders' fingerprint";
    s = base;
    s.prefilter.mipBias += 0.5f;
    EXPECT_NE(bake::BakeCache::bakeKey(42, s, 7), key);
    s = base;
    s.precision = bake::Precision::Float;
    EXPECT_NE(bake::BakeCache::bakeKey(42, s, 7), key);
    EXPECT_NE(bake::BakeCache::lutKey(128, 64, GeometryTerm::SchlickGGX, 7), bake::BakeCache::lutKey(128, 64, GeometryTerm::SchlickGGX, 8));
}

// A bake made by other shaders is not the bake these would make: an edited (or updated) bake
// shader, or a file it includes, misses the cache, bake and LUTs alike; an edit elsewhere
// (the frame's shaders) does not.
TEST_F(GlTest, AnEditedBakeShaderMissesTheCache)
{
    TempDirectory dir("bake-shader-edit");
    const fs::path shaderCopy = dir.path() / "shaders";
    fs::copy(IBLAB_SHADER_DIR, shaderCopy, fs::copy_options::recursive);
    bake::BakeCache cache(dir.path() / "cache");
    const Environment env = loadEnvironment("builtin:sun?width=64&size=10");
    auto bakeWithCopy = [&] {
        gl::ShaderLibrary shaders(shaderCopy);
        bake::BakeResult result = runBake(shaders, env, smallBakeSettings(), &cache);
        EXPECT_TRUE(cache.finishWrites().empty());
        return result;
    };
    auto append = [](const fs::path& file) { std::ofstream(file, std::ios::app) << "\n// edited\n"; };
    const bake::BakeResult first = bakeWithCopy();
    EXPECT_FALSE(first.fromCache);
    EXPECT_TRUE(bakeWithCopy().fromCache);

    append(shaderCopy / "pbr.frag");
    const bake::BakeResult frameEdited = bakeWithCopy();
    EXPECT_TRUE(frameEdited.fromCache) << "pbr.frag is not the bake's";
    EXPECT_EQ(frameEdited.shaderFingerprint, first.shaderFingerprint);

    append(shaderCopy / "bake" / "prefilter_ggx.comp");
    const bake::BakeResult edited = bakeWithCopy();
    EXPECT_FALSE(edited.fromCache);
    EXPECT_FALSE(edited.lutFromCache[0] || edited.lutFromCache[1]);
    EXPECT_NE(edited.shaderFingerprint, first.shaderFingerprint);

    append(shaderCopy / "common" / "sampling.glsl");
    EXPECT_FALSE(bakeWithCopy().fromCache) << "a file the bake's shaders include";
}

// Damages one file of a cached entry, bakes again, and checks that the damage is reported
// by the file's name, that the bake is redone, and that the entry is whole again after.
void expectDetectedAndRebuilt(const std::string& file, const std::function<void(const fs::path&)>& damage)
{
    auto shaders = library();
    TempDirectory dir("bake-corrupt");
    bake::BakeCache cache(dir.path());
    const Environment env = loadEnvironment("builtin:studio?width=64");
    const bake::BakeResult original = runBake(shaders, env, smallBakeSettings(), &cache);
    ASSERT_TRUE(cache.finishWrites().empty());
    const fs::path entry = cache.bakeDirectory(bake::BakeCache::bakeKey(env.contentHash, original.settings, original.shaderFingerprint));
    damage(entry / file);

    const bake::BakeResult rebuilt = runBake(shaders, env, smallBakeSettings(), &cache);
    EXPECT_FALSE(rebuilt.fromCache) << file;
    ASSERT_EQ(rebuilt.notes.size(), 1u) << file;
    EXPECT_NE(rebuilt.notes[0].find((entry / file).string()), std::string::npos) << rebuilt.notes[0];
    EXPECT_EQ(rebuilt.notes[0].find('\n'), std::string::npos) << "one line";
    expectSameResults(original, rebuilt);

    const bake::BakeResult again = runBake(shaders, env, smallBakeSettings(), &cache);
    EXPECT_TRUE(again.fromCache) << file;
    EXPECT_TRUE(again.notes.empty()) << file;
}

TEST_F(GlTest, ATruncatedExrIsReportedAndRebuilt)
{
    expectDetectedAndRebuilt("prefiltered_mip2.exr", [](const fs::path& p) { fs::resize_file(p, fs::file_size(p) / 2); });
}

TEST_F(GlTest, BadJsonIsReportedAndRebuilt)
{
    expectDetectedAndRebuilt("sh.json", [](const fs::path& p) { std::ofstream(p) << "{\"radiance\": [[1, 2, 3], "; });
}

TEST_F(GlTest, AnExrOfTheWrongSizeIsReportedAndRebuilt)
{
    expectDetectedAndRebuilt("environment.exr", [](const fs::path& p) {
        writeExr(p.string(), ImageRGB32F(8, 48)); // a valid EXR, but a cube of face 8, not 16
    });
}

TEST_F(GlTest, AnEntryOfAnotherFormatVersionIsReportedAndRebuilt)
{
    // Entries of another version have other keys (the key hashes the version) and are never
    // looked up; one found under this version's key anyway is refused by its bake.json.
    expectDetectedAndRebuilt("bake.json", [](const fs::path& p) {
        std::string text = readTextFile(p.string());
        const std::string current = "\"format\": " + std::to_string(bake::kBakeFormatVersion);
        ASSERT_NE(text.find(current), std::string::npos) << text;
        text.replace(text.find(current), current.size(), "\"format\": 1");
        std::ofstream(p, std::ios::trunc) << text;
    });
}

TEST_F(GlTest, ABadMirrorLevelIsReportedAndRebuilt)
{
    expectDetectedAndRebuilt("bake.json", [](const fs::path& p) {
        std::string text = readTextFile(p.string());
        const std::string key = "\"mirror_of_environment_level\": ";
        const std::size_t at = text.find(key);
        ASSERT_NE(at, std::string::npos) << text;
        const std::string level = text.substr(at, text.find_first_not_of("0123456789", at + key.size()) - at);
        text.replace(text.find(level), level.size(), "\"mirror_of_environment_level\": \"zero\"");
        std::ofstream(p, std::ios::trunc) << text;
    });
}

// A cache reads each LUT file once: later bakes through the same cache (a batch, the GUI's
// next environment) upload the image it kept, even once the file is gone.
TEST_F(GlTest, ALutReadOnceIsKeptForTheNextBakeOfTheSameCache)
{
    auto shaders = library();
    TempDirectory dir("lut-kept");
    const Environment env = loadEnvironment("builtin:white?width=32");
    const bake::BakeSettings settings = smallBakeSettings();
    {
        bake::BakeCache writer(dir.path());
        runBake(shaders, env, settings, &writer);
        ASSERT_TRUE(writer.finishWrites().empty());
    }
    bake::BakeCache cache(dir.path());
    const bake::BakeResult first = runBake(shaders, env, settings, &cache);
    ASSERT_TRUE(first.lutFromCache[0] && first.lutFromCache[1]);
    for (GeometryTerm term : bake::kGeometryTerms)
        ASSERT_TRUE(fs::remove(cache.lutPath(bake::BakeCache::lutKey(settings.lut.size, settings.lut.samples, term, first.shaderFingerprint))));
    const bake::BakeResult kept = runBake(shaders, env, settings, &cache);
    EXPECT_TRUE(kept.lutFromCache[0] && kept.lutFromCache[1]);
    EXPECT_EQ(bake::read2D(kept.lut(GeometryTerm::SchlickGGX)).texels, bake::read2D(first.lut(GeometryTerm::SchlickGGX)).texels);
    bake::BakeCache another(dir.path());
    EXPECT_FALSE(runBake(shaders, env, settings, &another).lutFromCache[0]) << "a new cache reads the files, which are gone";
}

TEST_F(GlTest, ACorruptLutIsReportedAndRebuilt)
{
    auto shaders = library();
    TempDirectory dir("lut-corrupt");
    bake::BakeCache cache(dir.path());
    const Environment env = loadEnvironment("builtin:white?width=32");
    const bake::BakeSettings settings = smallBakeSettings();
    const bake::BakeResult stored = runBake(shaders, env, settings, &cache);
    ASSERT_TRUE(cache.finishWrites().empty());
    const fs::path lut = cache.lutPath(bake::BakeCache::lutKey(settings.lut.size, settings.lut.samples, GeometryTerm::SchlickGGX, stored.shaderFingerprint));
    ASSERT_TRUE(fs::exists(lut));
    std::ofstream(lut, std::ios::trunc) << "not an EXR";
    // A new cache (the next process): the one that stored the LUT keeps it in memory.
    bake::BakeCache reader(dir.path());
    const bake::BakeResult result = runBake(shaders, env, settings, &reader);
    EXPECT_FALSE(result.lutFromCache[0]);
    EXPECT_TRUE(result.lutFromCache[1]);
    ASSERT_EQ(result.notes.size(), 1u);
    EXPECT_NE(result.notes[0].find(lut.string()), std::string::npos) << result.notes[0];
    ASSERT_TRUE(reader.finishWrites().empty());
    bake::BakeCache next(dir.path());
    EXPECT_TRUE(runBake(shaders, env, settings, &next).lutFromCache[0]); // stored again
}

// Without a root (--no-cache) a cache touches no files, bakes each environment, and still
// bakes the LUTs only once: a batch's later maps and the GUI's next environment upload them.
TEST_F(GlTest, ACacheWithoutARootKeepsOnlyTheLutsAndOnlyInMemory)
{
    auto shaders = library();
    bake::BakeCache memoryOnly{fs::path()};
    ASSERT_FALSE(memoryOnly.enabled());
    const Environment env = loadEnvironment("builtin:sky?width=32");
    const bake::BakeSettings settings = smallBakeSettings();
    const bake::BakeResult first = runBake(shaders, env, settings, &memoryOnly);
    EXPECT_FALSE(first.lutFromCache[0] || first.lutFromCache[1]);
    const bake::BakeResult second = runBake(shaders, env, settings, &memoryOnly);
    EXPECT_TRUE(second.lutFromCache[0] && second.lutFromCache[1]);
    EXPECT_FALSE(second.fromCache) << "the environment's results are not kept";
    EXPECT_EQ(second.phaseMilliseconds(bake::BakePhase::CacheLookup), 0.0);
    EXPECT_EQ(second.phaseMilliseconds(bake::BakePhase::CacheStore), 0.0);
    expectSameResults(first, second);
    bake::BakeSettings otherLut = settings;
    otherLut.lut.samples *= 2;
    EXPECT_FALSE(runBake(shaders, env, otherLut, &memoryOnly).lutFromCache[0]) << "kept by the LUT's own settings";
    EXPECT_TRUE(memoryOnly.finishWrites().empty());
}

// A map's upload in bands of rows, one step each, and its mips built after the last band: the
// same textures as one upload. A 256-wide map into a 16 face has equirect mips to build.
TEST_F(GlTest, TheMapUploadsInBandsOfRowsToTheSameBake)
{
    auto shaders = library();
    const Environment env = loadEnvironment("builtin:studio?width=256");
    bake::BakeSettings fine = smallBakeSettings();
    fine.cube.faceSize = 16;
    fine.samplesPerStep = 4096; // 16 rows of the map per step
    ASSERT_GT(bake::BakePasses::equirectLevelsForCube(256, 128, fine.cube.faceSize), 1);
    bake::BakeJob job(shaders, env, fine);
    int uploadSteps = 0;
    do {
        if (job.currentPhase() == bake::BakePhase::Upload) ++uploadSteps;
    } while (job.step());
    EXPECT_GE(uploadSteps, 2 + 128 / 16 + 1) << "the textures, the bands, the mips";
    bake::BakeSettings coarse = fine;
    coarse.samplesPerStep = bake::kUnslicedBake;
    expectSameResults(job.takeResult(), runBake(shaders, env, coarse));
}

TEST_F(GlTest, StepsReportProgressAndSlicingChangesNothing)
{
    auto shaders = library();
    const Environment env = loadEnvironment("builtin:studio?width=64");
    for (bake::IrradianceMethod irradiance : testing::kIrradianceCubeMethods) {
    SCOPED_TRACE(std::string(enumName(irradiance)));
    bake::BakeSettings fine = smallBakeSettings(irradiance);
    fine.samplesPerStep = 4096; // a few rows of a face per step
    bake::BakeJob job(shaders, env, fine);
    EXPECT_THROW(job.takeResult(), std::logic_error);
    float last = job.progress();
    EXPECT_EQ(last, 0.0f);
    int steps = 0;
    bool more = true;
    while (more) {
        EXPECT_TRUE(job.currentPhase().has_value());
        more = job.step();
        ++steps;
        EXPECT_GE(job.progress(), last);
        EXPECT_LE(job.progress(), 1.0f);
        last = job.progress();
    }
    EXPECT_TRUE(job.done());
    EXPECT_EQ(job.progress(), 1.0f);
    EXPECT_FALSE(job.step());
    const bake::BakeResult sliced = job.takeResult();

    bake::BakeSettings coarse = smallBakeSettings(irradiance);
    coarse.samplesPerStep = std::int64_t(1) << 40; // whole faces
    bake::BakeJob whole(shaders, env, coarse);
    int wholeSteps = 1;
    while (whole.step()) ++wholeSteps;
    // Every sampling pass was cut into bands of rows: several steps where whole faces take one.
    EXPECT_GT(steps, 2 * wholeSteps);
    const bake::BakeResult unsliced = whole.takeResult();
    // Each texel is computed by the same code from the same inputs whichever dispatch it is in.
    expectSameResults(sliced, unsliced);
    using bake::BakePhase;
    for (const BakePhase phase : {BakePhase::Shaders, BakePhase::Upload, BakePhase::EnvironmentCube, BakePhase::Sh9,
                                  bake::irradiancePhase(irradiance), BakePhase::Prefilter, BakePhase::BrdfLut})
        EXPECT_GT(sliced.phaseMilliseconds(phase), 0.0) << enumName(phase);
    // Each prefiltered mip is a part of the prefilter phase, timed by the same clock: the
    // parts are a share of the phase's time, never more.
    double parts = 0.0;
    for (int level = 0; level < sliced.settings.prefilter.levels; ++level) {
        const std::string name = "prefilter.mip" + std::to_string(level);
        const auto part = std::find_if(sliced.partTimings.begin(), sliced.partTimings.end(),
                                       [&](const bake::PartTiming& t) { return t.name == name; });
        ASSERT_NE(part, sliced.partTimings.end()) << name;
        EXPECT_GT(part->milliseconds, 0.0) << name;
    }
    for (const bake::PartTiming& t : sliced.partTimings) parts += t.milliseconds;
    EXPECT_LE(parts, sliced.phaseMilliseconds(BakePhase::Prefilter) * (1.0 + 1e-9));
    EXPECT_GT(sliced.gpuBytes(), 0u);
    }
}

// Forces where bakes made meanwhile run their host work, Auto again when it goes.
struct ScopedHostWorkPlacement {
    explicit ScopedHostWorkPlacement(bake::HostWorkPlacement placement) { bake::setHostWorkPlacement(placement); }
    ~ScopedHostWorkPlacement() { bake::setHostWorkPlacement(bake::HostWorkPlacement::Auto); }
};

// The small bake with both kinds of host work: the split's plan and the shading lights.
bake::BakeSettings hostWorkSettings()
{
    bake::BakeSettings s = smallBakeSettings();
    s.prefilter.brightTexels = 16;
    s.prefilter.shadingLights = 4;
    return s;
}

TEST_F(GlTest, HostWorkOnWorkerThreadsBakesTheSameAsInItsOwnSteps)
{
    // A hardware GPU runs the shading lights and the split's plan on worker threads beside its
    // passes; llvmpipe, where every test runs, in steps of their own. Both ways, forced.
    auto shaders = library();
    const Environment env = loadEnvironment("builtin:sun?width=128&size=3&intensity=1e3");
    const bake::BakeSettings s = hostWorkSettings();
    auto bakeWith = [&](bake::HostWorkPlacement placement) {
        const ScopedHostWorkPlacement forced(placement);
        return bake::BakeJob(shaders, env, s).runToCompletion();
    };
    const bake::BakeResult own = bakeWith(bake::HostWorkPlacement::OwnSteps);
    const bake::BakeResult threads = bakeWith(bake::HostWorkPlacement::WorkerThreads);
    expectSameResults(own, threads);
    ASSERT_FALSE(own.shadingLights.groups.empty());
    ASSERT_EQ(own.shadingLights.groups.size(), threads.shadingLights.groups.size());
    for (std::size_t i = 0; i < own.shadingLights.groups.size(); ++i) {
        EXPECT_EQ(own.shadingLights.groups[i].light.direction, threads.shadingLights.groups[i].light.direction) << i;
        EXPECT_EQ(own.shadingLights.groups[i].light.flux, threads.shadingLights.groups[i].light.flux) << i;
    }
    // The parts say where the work ran: in its own step, or started on the threads.
    auto hasPart = [](const bake::BakeResult& r, const std::string& name) {
        return std::any_of(r.partTimings.begin(), r.partTimings.end(), [&](const bake::PartTiming& t) { return t.name == name; });
    };
    EXPECT_TRUE(hasPart(own, "prefilter.shading_lights"));
    EXPECT_FALSE(hasPart(own, "prefilter.host_work_start"));
    EXPECT_TRUE(hasPart(threads, "prefilter.host_work_start"));
    EXPECT_TRUE(hasPart(threads, "prefilter.split"));
}

// A job dropped mid-bake (the GUI switching maps) while its worker threads still read its
// map: the destructor waits for them before the map goes (under scripts/sanitize.sh a read of
// the freed map would be reported).
TEST_F(GlTest, AJobDroppedWhileItsHostWorkRunsWaitsForIt)
{
    auto shaders = library();
    const bake::BakeSettings s = hostWorkSettings();
    const ScopedHostWorkPlacement forced(bake::HostWorkPlacement::WorkerThreads);
    for (int attempt = 0; attempt < 3; ++attempt) {
        auto job = std::make_unique<bake::BakeJob>(shaders, loadEnvironment("builtin:sun?width=512&size=3&intensity=1e3"), s);
        // Up to the upload, the step after the one that starts the worker threads.
        while (job->currentPhase() != bake::BakePhase::Upload)
            ASSERT_TRUE(job->step());
        job.reset();
    }
    // And a job run to the end after it bakes as before.
    EXPECT_NO_THROW(bake::BakeJob(shaders, loadEnvironment("builtin:sun?width=512&size=3&intensity=1e3"), s).runToCompletion());
}

TEST_F(GlTest, InvalidSettingsAreRefusedWithTheirName)
{
    auto shaders = library();
    bake::BakeSettings s = smallBakeSettings();
    s.prefilter.levels = 9; // more mips than a 16 face has
    try {
        bake::BakeJob job(shaders, loadEnvironment("builtin:white?width=32"), s);
        FAIL() << "accepted 9 levels on a face of 16";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("prefilter.levels"), std::string::npos) << e.what();
    }
}

// The record of what a file decoded to (the GUI reads its bake while the file decodes):
// found for the file as it was, and for nothing else.
TEST(BakeCacheSources, AreFoundForTheFileAsItWasOnly)
{
    TempDirectory dir("bake-sources");
    bake::BakeCache cache(dir.path() / "cache");
    const fs::path map = dir.path() / "map.exr";
    writeExr(map.string(), loadEnvironment("builtin:sky?width=32").image);
    EXPECT_FALSE(cache.findSource(map.string())) << "never loaded";
    cache.rememberSource(map.string(), {0x0123456789abcdefull, 32, 16});
    cache.rememberSource("builtin:sky?width=32", {1, 32, 16});
    ASSERT_TRUE(cache.finishWrites().empty());

    const std::optional<bake::BakeCache::SourceRecord> found = cache.findSource(map.string());
    ASSERT_TRUE(found);
    EXPECT_EQ(found->contentHash, 0x0123456789abcdefull);
    EXPECT_EQ(found->width, 32);
    EXPECT_EQ(found->height, 16);
    EXPECT_FALSE(cache.findSource("builtin:sky?width=32")) << "builtins decode in no time: no record";
    EXPECT_FALSE(cache.findSource((dir.path() / "other.exr").string())) << "a missing file";
    // The same file by a relative path: the record is keyed by the absolute one.
    const fs::path before = fs::current_path();
    fs::current_path(dir.path());
    EXPECT_TRUE(cache.findSource("map.exr"));
    fs::current_path(before);

    // Saved again (another modification time): the record no longer applies.
    fs::last_write_time(map, fs::last_write_time(map) + std::chrono::seconds(2));
    EXPECT_FALSE(cache.findSource(map.string()));
    cache.rememberSource(map.string(), {42, 32, 16});
    ASSERT_TRUE(cache.finishWrites().empty());
    ASSERT_TRUE(cache.findSource(map.string()));
    EXPECT_EQ(cache.findSource(map.string())->contentHash, 42u);

    // A torn record is a miss, not an error.
    for (const auto& entry : fs::directory_iterator(dir.path() / "cache" / "source"))
        std::ofstream(entry.path(), std::ios::trunc) << "{\"content_hash\": ";
    EXPECT_FALSE(cache.findSource(map.string()));
    EXPECT_FALSE(bake::BakeCache(fs::path()).findSource(map.string())) << "no cache";
}

// A job from the record alone (no pixels) reads the bake the pixels would have made, or says
// that the entry is gone.
TEST_F(GlTest, AJobFromASourceRecordReadsTheCachedBakeOrSaysItMissed)
{
    auto shaders = library();
    TempDirectory dir("bake-from-record");
    bake::BakeCache cache(dir.path());
    const Environment env = loadEnvironment("builtin:sun?width=64&size=10");
    const bake::BakeResult baked = runBake(shaders, env, smallBakeSettings(), &cache);
    ASSERT_TRUE(cache.finishWrites().empty());
    const bake::BakeCache::SourceRecord record{env.contentHash, env.image.width, env.image.height};

    bake::BakeJob job(shaders, "sun.exr", record, smallBakeSettings(), cache);
    const bake::BakeResult read = job.runToCompletion();
    EXPECT_FALSE(job.missedCache());
    EXPECT_TRUE(read.fromCache);
    EXPECT_EQ(read.contentHash, env.contentHash);
    EXPECT_EQ(read.source, "sun.exr");
    expectSameResults(baked, read);

    fs::remove_all(cache.bakeDirectory(bake::BakeCache::bakeKey(env.contentHash, baked.settings, baked.shaderFingerprint)));
    bake::BakeJob missing(shaders, "sun.exr", record, smallBakeSettings(), cache);
    const bake::BakeResult empty = missing.runToCompletion();
    EXPECT_TRUE(missing.missedCache());
    EXPECT_FALSE(empty.fromCache);
    EXPECT_FALSE(empty.environmentCube);
    EXPECT_FALSE(empty.prefiltered);
}

TEST(BakeCacheDirectory, FollowsTheEnvironmentVariables)
{
    // Restores the variables it changes so that the other tests see the caller's.
    struct Saved {
        const char* name;
        std::optional<std::string> value;
    };
    std::vector<Saved> saved;
    for (const char* name : {"IBLAB_CACHE_DIR", "XDG_CACHE_HOME", "HOME"}) {
        const char* v = std::getenv(name);
        saved.push_back({name, v ? std::optional<std::string>(v) : std::nullopt});
    }
    ::setenv("IBLAB_CACHE_DIR", "/tmp/override", 1);
    ::setenv("XDG_CACHE_HOME", "/tmp/xdg", 1);
    ::setenv("HOME", "/tmp/home", 1);
    EXPECT_EQ(bake::defaultCacheDirectory(), fs::path("/tmp/override"));
    ::unsetenv("IBLAB_CACHE_DIR");
    EXPECT_EQ(bake::defaultCacheDirectory(), fs::path("/tmp/xdg/iblab"));
    ::unsetenv("XDG_CACHE_HOME");
    EXPECT_EQ(bake::defaultCacheDirectory(), fs::path("/tmp/home/.cache/iblab"));
    for (const Saved& s : saved) {
        if (s.value)
            ::setenv(s.name, s.value->c_str(), 1);
        else
            ::unsetenv(s.name);
    }
}

} // namespace
} // namespace iblab
