// The GUI's session (app/lab_session, with app/loaded_model) facing bad files: every malformed environment or model
// is refused with one line naming the file, and what the user had (environment, bake,
// model, their settings) stays exactly as it was. Also: environment requests made while one
// loads are queued, never waited for, and the newest wins.
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <string>
#include <thread>

#include "bake_test_support.hpp"
#include "gl_test_fixture.hpp"
#include "bake/bake_cache.hpp"
#include "io/image_writer.hpp"
#include "lab_session.hpp"
#include "loaded_model.hpp"
#include "malformed_images.hpp"
#include "temp_dir.hpp"

namespace iblab {
namespace {

using testing::GlTest;

class LabSessionTest : public GlTest {
protected:
    void SetUp() override
    {
        GlTest::SetUp();
        ::setenv("IBLAB_CACHE_DIR", (folder.path / "cache").c_str(), 1);
    }

    // Pumps the way the GUI loop does (small budgets) until the session is idle.
    app::LabSession::Finished pumpUntilIdle(app::LabSession& session, FrameSettings& settings)
    {
        app::LabSession::Finished last;
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(1);
        while (session.busy() && std::chrono::steady_clock::now() < deadline) {
            const app::LabSession::Finished finished = session.pump(std::chrono::milliseconds(5));
            // As the GUI does: the session reports the map it shows, the caller's settings name it.
            if (finished.environmentShown) settings.environment.source = *finished.environmentShown;
            if (finished.environment) last.environment = finished.environment;
            if (finished.bake) last.bake = finished.bake;
            std::this_thread::sleep_for(std::chrono::milliseconds(1)); // the rest of a frame
        }
        EXPECT_FALSE(session.busy());
        return last;
    }

    testing::TempDir folder{"iblab-lab-session"};
};

// Loads a model as the GUI does: a loaded one becomes the scene in the caller's settings.
app::StatusReport loadModel(app::LoadedModel& model, const std::string& path, FrameSettings& settings)
{
    app::StatusReport status = model.load(path, settings.scene.kind == SceneKind::Model);
    if (!status.isError) {
        settings.scene.kind = SceneKind::Model;
        settings.scene.modelPath = path;
    }
    return status;
}

void expectOneLineNaming(const app::StatusReport& status, const std::string& fileName, const std::string& problem)
{
    EXPECT_TRUE(status.isError) << status.text;
    EXPECT_EQ(status.text.find('\n'), std::string::npos) << status.text;
    EXPECT_NE(status.text.find(fileName), std::string::npos) << status.text;
    EXPECT_NE(status.text.find(problem), std::string::npos) << "expected \"" << problem << "\" in: " << status.text;
}

TEST_F(LabSessionTest, MalformedEnvironmentsAreRefusedAndTheCurrentOneStays)
{
    Renderer renderer(shaderDirectory());
    app::LabSession session(renderer, testing::smallBakeSettings());
    FrameSettings settings;
    ASSERT_FALSE(session.loadEnvironment("builtin:sky?width=64").isError);
    const auto bakeBefore = session.bake();
    const std::string sourceBefore = settings.environment.source;
    ASSERT_TRUE(bakeBefore);

    for (const testing::MalformedImage& bad : testing::writeMalformedImages(folder.path)) {
        SCOPED_TRACE(bad.fileName);
        session.requestEnvironment((folder.path / bad.fileName).string());
        const app::LabSession::Finished finished = pumpUntilIdle(session, settings);
        ASSERT_TRUE(finished.environment);
        expectOneLineNaming(*finished.environment, bad.fileName, bad.problem);
        EXPECT_FALSE(finished.bake) << "a refused environment must not start a bake";
        EXPECT_EQ(settings.environment.source, sourceBefore);
        EXPECT_EQ(session.environment()->source, "builtin:sky?width=64");
        EXPECT_EQ(session.bake(), bakeBefore);
    }
    // The lab still renders what it had.
    settings.scene.kind = SceneKind::Sphere;
    renderer.renderFrame(settings, 16, 16);
}

TEST_F(LabSessionTest, MalformedModelsAreRefusedAndTheLoadedModelStays)
{
    Renderer renderer(shaderDirectory());
    app::LabSession session(renderer, testing::smallBakeSettings());
    FrameSettings settings;
    ASSERT_FALSE(session.loadEnvironment("builtin:studio?width=64").isError);
    const std::string goodModel = IBLAB_ASSET_DIR "/models/material_spheres.glb";
    app::LoadedModel model(renderer);
    ASSERT_FALSE(loadModel(model, goodModel, settings).isError);
    const std::size_t drawsBefore = renderer.sceneInfo(settings).draws;
    ASSERT_GT(drawsBefore, 0u);

    const std::filesystem::path models = folder.path / "models";
    std::filesystem::create_directories(models);
    std::ofstream(models / "broken.gltf") << "{ not json";
    std::ofstream(models / "empty.glb");
    // A 12-byte header (length 64) and a JSON chunk header claiming 255 bytes, then "{}": 22
    // bytes, embedded NULs included (the literal's own length; a count written by hand read
    // past it, which AddressSanitizer caught).
    constexpr char shortChunk[] = "glTF\x02\0\0\0\x40\0\0\0\xff\0\0\0JSON{}";
    std::ofstream(models / "short-chunk.glb", std::ios::binary) << std::string(shortChunk, sizeof shortChunk - 1);
    std::ofstream(models / "missing-buffer.gltf")
        << R"({"asset":{"version":"2.0"},"buffers":[{"uri":"nowhere.bin","byteLength":36}],"bufferViews":[{"buffer":0,"byteLength":36}],)"
           R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],)"
           R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}]})";
    std::ofstream(models / "escaping.gltf")
        << R"({"asset":{"version":"2.0"},"buffers":[{"uri":"../../etc/passwd","byteLength":36}],"bufferViews":[{"buffer":0,"byteLength":36}],)"
           R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],)"
           R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}]})";
    for (const char* name : {"broken.gltf", "empty.glb", "short-chunk.glb", "missing-buffer.gltf", "escaping.gltf", "no-such-model.glb"}) {
        SCOPED_TRACE(name);
        const app::StatusReport status = loadModel(model, (models / name).string(), settings);
        expectOneLineNaming(status, name, "");
        EXPECT_EQ(settings.scene.kind, SceneKind::Model);
        EXPECT_EQ(settings.scene.modelPath, goodModel);
        EXPECT_EQ(renderer.sceneInfo(settings).draws, drawsBefore);
    }
    // Well formed, but its scene's only node is empty: nothing to draw, so it does not
    // replace the model on screen with an empty view.
    std::ofstream(models / "no-triangles.gltf") << R"({"asset":{"version":"2.0"},"nodes":[{}],"scenes":[{"nodes":[0]}],"scene":0})";
    const app::StatusReport empty = loadModel(model, (models / "no-triangles.gltf").string(), settings);
    expectOneLineNaming(empty, "no-triangles.gltf", "nothing to draw");
    ASSERT_EQ(empty.notes.size(), 1u);
    EXPECT_NE(empty.notes[0].find("material_spheres.glb"), std::string::npos) << empty.notes[0];
    EXPECT_EQ(settings.scene.modelPath, goodModel);
    EXPECT_EQ(renderer.sceneInfo(settings).draws, drawsBefore);
    renderer.renderFrame(settings, 16, 16);
}

TEST_F(LabSessionTest, RequestsDuringALoadAreQueuedAndTheNewestWins)
{
    Renderer renderer(shaderDirectory());
    app::LabSession session(renderer, testing::smallBakeSettings());
    FrameSettings settings;
    // Three requests in a row, as a user clicking through the gallery: none may block, and
    // only the last one counts.
    const auto start = std::chrono::steady_clock::now();
    session.requestEnvironment("builtin:sun?width=1024");
    session.requestEnvironment("builtin:sky?width=64");
    session.requestEnvironment("builtin:studio?width=64");
    // Generous for llvmpipe under load; a blocking request would wait for the 1024 load.
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::milliseconds(50));
    EXPECT_NE(session.activity().find("builtin:studio"), std::string::npos) << session.activity();
    pumpUntilIdle(session, settings);
    EXPECT_EQ(settings.environment.source, "builtin:studio?width=64");
    EXPECT_EQ(session.environment()->source, "builtin:studio?width=64");
    EXPECT_TRUE(session.bake());
}

// Enter in the path field and then the Load button ask for the same map twice: it loads once
// (the second request used to queue a second load, which threw the first one's result away).
TEST_F(LabSessionTest, AMapAskedForAgainWhileItLoadsLoadsOnce)
{
    Renderer renderer(shaderDirectory());
    app::LabSession session(renderer, testing::smallBakeSettings());
    FrameSettings settings;
    session.requestEnvironment("builtin:sky?width=64");
    session.requestEnvironment("builtin:sky?width=64");
    session.waitForLoad(std::chrono::seconds(30));
    const app::LabSession::Finished finished = session.pump(std::chrono::seconds(30));
    ASSERT_TRUE(finished.environment) << "the first load's result was used";
    EXPECT_FALSE(finished.environment->isError) << finished.environment->text;
    EXPECT_EQ(session.environment()->source, "builtin:sky?width=64");
    pumpUntilIdle(session, settings);

    // Asked for again once decoded, while it bakes: the bake goes on, nothing decodes again.
    session.requestEnvironment("builtin:sun?width=256");
    session.waitForLoad(std::chrono::seconds(30));
    session.pump(std::chrono::microseconds(1)); // the decode lands, the bake starts
    ASSERT_EQ(session.environment()->source, "builtin:sun?width=256");
    ASSERT_NE(session.activity().find("baking"), std::string::npos) << session.activity();
    session.requestEnvironment("builtin:sun?width=256");
    EXPECT_EQ(session.activity().find("loading"), std::string::npos) << session.activity();
    pumpUntilIdle(session, settings);
}

// A map whose bake is cached from an earlier run: its bake is read from the cache's record
// of the file and shown first, then the file decodes and must be what the record said.
class EarlyBakeTest : public LabSessionTest {
protected:
    void SetUp() override
    {
        LabSessionTest::SetUp();
        writeExr(mapA.string(), loadEnvironment("builtin:sun?width=64&size=20&elevation=30").image);
        writeExr(mapB.string(), loadEnvironment("builtin:sky?width=64").image);
        // An earlier run: both decoded and baked once (bakes and records in the cache).
        Renderer renderer(shaderDirectory());
        app::LabSession earlier(renderer, testing::smallBakeSettings());
        FrameSettings settings;
        ASSERT_FALSE(earlier.loadEnvironment(mapA.string()).isError);
        hashA = earlier.environment()->contentHash;
        ASSERT_FALSE(earlier.loadEnvironment(mapB.string()).isError);
        hashB = earlier.environment()->contentHash;
    } // the session's cache finishes its writes

    // A session showing map B, as the user's before the switch.
    void showB(app::LabSession& session)
    {
        ASSERT_FALSE(session.loadEnvironment(mapB.string()).isError);
        ASSERT_EQ(session.bake()->contentHash, hashB);
    }

    std::filesystem::path mapA = folder.path / "a.exr", mapB = folder.path / "b.exr";
    std::uint64_t hashA = 0, hashB = 0;
};

TEST_F(EarlyBakeTest, TheBakeIsShownBeforeTheFileDecodes)
{
    Renderer renderer(shaderDirectory());
    app::LabSession session(renderer, testing::smallBakeSettings());
    FrameSettings settings;
    showB(session);
    const std::uint64_t revision = renderer.contentRevision();

    session.requestEnvironment(mapA.string());
    // One pump reads the bake; the decode waits for the frame that shows it.
    const app::LabSession::Finished early = session.pump(std::chrono::seconds(10));
    ASSERT_TRUE(early.bake);
    EXPECT_NE(early.bake->text.find("(from cache)"), std::string::npos) << early.bake->text;
    EXPECT_NE(early.bake->text.find("; reading a.exr"), std::string::npos) << early.bake->text;
    ASSERT_TRUE(session.bake());
    EXPECT_EQ(session.bake()->contentHash, hashA);
    EXPECT_TRUE(session.bake()->fromCache);
    EXPECT_GT(renderer.contentRevision(), revision) << "the renderer has the new bake";
    EXPECT_EQ(session.environment()->source, mapB.string()) << "not decoded yet";
    EXPECT_TRUE(session.busy());
    // The GUI's next update reports the frame that showed the bake (and pumps: the decode starts).
    session.update({.presented = app::LabSession::Clock::now()});
    ASSERT_TRUE(session.lastSwitch());
    EXPECT_EQ(session.lastSwitch()->environment, mapA.string());
    EXPECT_TRUE(session.lastSwitch()->fromCache);

    const std::uint64_t shown = renderer.contentRevision();
    const app::LabSession::Finished decoded = pumpUntilIdle(session, settings);
    // The status no longer says the file is being read (it did until the app closed).
    ASSERT_TRUE(decoded.bake);
    EXPECT_EQ(decoded.bake->text, early.bake->text.substr(0, early.bake->text.find("; reading")));
    EXPECT_EQ(session.environment()->source, mapA.string());
    EXPECT_EQ(session.environment()->contentHash, hashA);
    EXPECT_EQ(session.bake()->contentHash, hashA);
    EXPECT_EQ(settings.environment.source, mapA.string());
    EXPECT_EQ(renderer.contentRevision(), shown) << "the decoded map draws nothing new: no second frame";
    EXPECT_GT(session.lastSwitch()->loadMs, 0.0) << "the decode's time, after the first frame";

    // Kept with its own pixels: back to B and to A again shows each at once.
    session.requestEnvironment(mapB.string());
    session.pump(std::chrono::seconds(10));
    EXPECT_EQ(session.bake()->contentHash, hashB);
    session.requestEnvironment(mapA.string());
    session.pump(std::chrono::seconds(10));
    EXPECT_EQ(session.environment()->contentHash, hashA);
    EXPECT_EQ(session.bake()->contentHash, hashA);
}

// The GUI draws its panel between the frame's pump and acting on the frame's requests: a
// recent map shown at once, on request, put its first image beside the old map's status
// line. It is shown by the next pump instead, which reports its line with it.
TEST_F(EarlyBakeTest, ARecentMapIsShownByTheNextPumpWithItsStatusLine)
{
    Renderer renderer(shaderDirectory());
    app::LabSession session(renderer, testing::smallBakeSettings());
    FrameSettings settings;
    showB(session);
    session.requestEnvironment(mapA.string());
    pumpUntilIdle(session, settings);
    ASSERT_EQ(session.environment()->contentHash, hashA);
    const std::uint64_t revision = renderer.contentRevision();

    session.requestEnvironment(mapB.string()); // recent: kept with its bake
    EXPECT_EQ(session.environment()->contentHash, hashA) << "B waits for the next pump";
    EXPECT_EQ(renderer.contentRevision(), revision) << "nothing new to draw beside A's status line";
    EXPECT_TRUE(session.busy()) << "the app must not sleep before that pump";
    const app::LabSession::Finished shown = session.pump(std::chrono::seconds(10));
    EXPECT_EQ(session.environment()->contentHash, hashB);
    EXPECT_GT(renderer.contentRevision(), revision);
    ASSERT_TRUE(shown.environment);
    EXPECT_NE(shown.environment->text.find("b.exr"), std::string::npos) << shown.environment->text;
    ASSERT_TRUE(shown.environmentShown);
    EXPECT_EQ(*shown.environmentShown, mapB.string());
}

TEST_F(EarlyBakeTest, ARecordThatNoLongerMatchesGivesWayToTheDecodedMap)
{
    // The file rewritten with another map, its size and time kept: the record says B.
    bake::BakeCache(folder.path / "cache").rememberSource(mapA.string(), {hashB, 64, 32});
    Renderer renderer(shaderDirectory());
    app::LabSession session(renderer, testing::smallBakeSettings());
    FrameSettings settings;
    ASSERT_FALSE(session.loadEnvironment("builtin:studio?width=64").isError);
    session.requestEnvironment(mapA.string());
    session.pump(std::chrono::seconds(10));
    EXPECT_EQ(session.bake()->contentHash, hashB) << "what the record promised";
    pumpUntilIdle(session, settings);
    EXPECT_EQ(session.environment()->contentHash, hashA);
    EXPECT_EQ(session.bake()->contentHash, hashA) << "the decoded pixels' bake replaces it";
}

TEST_F(EarlyBakeTest, ARecordWhoseBakeIsGoneBakesTheDecodedMap)
{
    std::filesystem::remove_all(folder.path / "cache" / "bake");
    Renderer renderer(shaderDirectory());
    app::LabSession session(renderer, testing::smallBakeSettings());
    FrameSettings settings;
    const app::StatusReport status = session.loadEnvironment(mapA.string());
    ASSERT_FALSE(status.isError) << status.text;
    EXPECT_EQ(session.environment()->contentHash, hashA);
    EXPECT_EQ(session.bake()->contentHash, hashA);
    EXPECT_FALSE(session.bake()->fromCache);
    EXPECT_NE(session.bake()->environmentCube.id(), 0u);
}

TEST_F(EarlyBakeTest, AFileThatNoLongerDecodesPutsBackWhatWasShown)
{
    Renderer renderer(shaderDirectory());
    app::LabSession session(renderer, testing::smallBakeSettings());
    FrameSettings settings;
    showB(session);
    // Damaged in place, its size and time kept: the record still applies, the decode fails.
    const auto size = std::filesystem::file_size(mapA);
    const auto time = std::filesystem::last_write_time(mapA);
    { std::ofstream(mapA, std::ios::binary | std::ios::trunc) << std::string(size, 'x'); }
    std::filesystem::last_write_time(mapA, time);
    session.requestEnvironment(mapA.string());
    session.pump(std::chrono::seconds(10));
    EXPECT_EQ(session.bake()->contentHash, hashA);
    const app::LabSession::Finished last = pumpUntilIdle(session, settings);
    ASSERT_TRUE(last.environment);
    EXPECT_TRUE(last.environment->isError);
    EXPECT_NE(last.environment->text.find("a.exr"), std::string::npos) << last.environment->text;
    EXPECT_EQ(session.environment()->source, mapB.string());
    EXPECT_EQ(session.bake()->contentHash, hashB) << "B's lighting with B's map, as before the request";
}

TEST_F(LabSessionTest, BakeStatusReportsItsGpuMemory)
{
    Renderer renderer(shaderDirectory());
    app::LabSession session(renderer, testing::smallBakeSettings());
    FrameSettings settings;
    const app::StatusReport status = session.loadEnvironment("builtin:sky?width=64");
    ASSERT_FALSE(status.isError) << status.text;
    char expected[64];
    std::snprintf(expected, sizeof expected, "%.1f MiB of GPU memory", double(session.bake()->gpuBytes()) / (1024.0 * 1024.0));
    EXPECT_NE(status.text.find(expected), std::string::npos) << status.text;
    EXPECT_GT(session.bake()->gpuBytes(), 0u);
}

} // namespace
} // namespace iblab
