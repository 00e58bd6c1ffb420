// The GUI's session (app/lab_session) facing bad files: every malformed environment or model
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
#include "lab_session.hpp"
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
            const app::LabSession::Finished finished = session.pump(settings, std::chrono::milliseconds(5));
            if (finished.environment) last.environment = finished.environment;
            if (finished.bake) last.bake = finished.bake;
            std::this_thread::sleep_for(std::chrono::milliseconds(1)); // the rest of a frame
        }
        EXPECT_FALSE(session.busy());
        return last;
    }

    testing::TempDir folder{"iblab-lab-session"};
};

void expectOneLineNaming(const ui::StatusLine& status, const std::string& fileName, const std::string& problem)
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
    ASSERT_FALSE(session.loadEnvironment("builtin:sky?width=64", settings).isError);
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
    ASSERT_FALSE(session.loadEnvironment("builtin:studio?width=64", settings).isError);
    const std::string goodModel = IBLAB_ASSET_DIR "/models/material_spheres.glb";
    ASSERT_FALSE(session.loadModel(goodModel, settings).isError);
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
        const ui::StatusLine status = session.loadModel((models / name).string(), settings);
        expectOneLineNaming(status, name, "");
        EXPECT_EQ(settings.scene.kind, SceneKind::Model);
        EXPECT_EQ(settings.scene.modelPath, goodModel);
        EXPECT_EQ(renderer.sceneInfo(settings).draws, drawsBefore);
    }
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

TEST_F(LabSessionTest, BakeStatusReportsItsGpuMemory)
{
    Renderer renderer(shaderDirectory());
    app::LabSession session(renderer, testing::smallBakeSettings());
    FrameSettings settings;
    const ui::StatusLine status = session.loadEnvironment("builtin:sky?width=64", settings);
    ASSERT_FALSE(status.isError) << status.text;
    char expected[64];
    std::snprintf(expected, sizeof expected, "%.1f MiB of GPU memory", double(session.bake()->gpuBytes()) / (1024.0 * 1024.0));
    EXPECT_NE(status.text.find(expected), std::string::npos) << status.text;
    EXPECT_GT(session.bake()->gpuBytes(), 0u);
}

} // namespace
} // namespace iblab
