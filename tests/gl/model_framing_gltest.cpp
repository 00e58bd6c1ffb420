// Every model is drawn and framed whatever its units: the clip planes follow the scene's
// bounds and the camera, and framing fits the bounding sphere from the model's home view.
// The Khronos samples come from Debian's assimp-testmodels (scripts/install-deps.sh, tests
// group); without it those cases skip with a message.
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "bake_test_support.hpp"
#include "frame/camera.hpp"
#include "renderer_fixture.hpp"
#include "scene/gltf_model.hpp"

namespace iblab {
namespace {

constexpr int kWidth = 96, kHeight = 64;
const std::filesystem::path kAssimpGltf2 = "/usr/share/assimp/models/glTF2";

// Where the model covers the frame: how many pixels, and the box around them.
struct Coverage {
    int pixels = 0;
    int minX = kWidth, minY = kHeight, maxX = -1, maxY = -1;
    float fraction() const { return float(pixels) / float(kWidth * kHeight); }
};

class ModelFraming : public testing::RendererTest {
protected:
    void SetUp() override
    {
        testing::RendererTest::SetUp();
        bakeEnvironment("builtin:studio?width=64", testing::smallBakeSettings());
    }
    // The model shown as a new scene is: from its home view, framed.
    Coverage render(const ModelData& model)
    {
        renderer().setModel(model, "model.glb");
        FrameSettings s;
        s.scene.kind = SceneKind::Model;
        s.scene.modelPath = "model.glb";
        s.material.overrideModel = false;
        const SceneInfo info = renderer().sceneInfo(s);
        homeView(s.camera, true);
        frameScene(s.camera, info.centre, info.halfExtents, true, float(kWidth) / float(kHeight));
        renderer().renderFrame(s, kWidth, kHeight);
        const FrameReadback frame = renderer().readHdrFrame();
        Coverage c;
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x)
                if (frame.rgba[(std::size_t(y) * kWidth + std::size_t(x)) * 4 + 3] > 0.5f) {
                    ++c.pixels;
                    c.minX = std::min(c.minX, x), c.maxX = std::max(c.maxX, x);
                    c.minY = std::min(c.minY, y), c.maxY = std::max(c.maxY, y);
                }
        return c;
    }
};

ModelData scaled(ModelData model, float factor)
{
    for (MeshInstance& instance : model.instances)
        for (glm::vec3& p : instance.mesh.positions) p *= factor;
    model.bounds.min *= factor;
    model.bounds.max *= factor;
    return model;
}

std::vector<std::filesystem::path> assimpGltfFiles()
{
    std::vector<std::filesystem::path> files;
    if (!std::filesystem::is_directory(kAssimpGltf2)) return files;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(kAssimpGltf2)) {
        const std::string extension = entry.path().extension().string();
        if (extension == ".gltf" || extension == ".glb") files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    return files;
}

// Each sample that loads with triangles is visible in its framed view. 2CylinderEngine
// (about 800 units across) showed an empty sky under a far plane fixed at 100. Files the
// loader refuses (malformed on purpose, Draco, points and lines only) have their own tests.
TEST_F(ModelFraming, EveryTriangleModelOfAssimpsGltf2SamplesIsVisible)
{
    const std::vector<std::filesystem::path> files = assimpGltfFiles();
    if (files.empty()) GTEST_SKIP() << kAssimpGltf2 << " is absent: install assimp-testmodels (scripts/install-deps.sh)";
    int rendered = 0;
    bool sawEngine = false;
    for (const std::filesystem::path& file : files) {
        ModelData model;
        try {
            model = loadGltfModel(file.string());
        } catch (const std::exception&) {
            continue;
        }
        if (model.instances.empty() || model.bounds.empty()) continue;
        SCOPED_TRACE(file.string());
        const Coverage c = render(model);
        EXPECT_GT(c.pixels, 0) << "nothing of the model is in the frame";
        // Framed whole, with a margin: nothing touches the frame's edge.
        EXPECT_GT(c.minX, 0);
        EXPECT_GT(c.minY, 0);
        EXPECT_LT(c.maxX, kWidth - 1);
        EXPECT_LT(c.maxY, kHeight - 1);
        ++rendered;
        sawEngine = sawEngine || file.filename() == "2CylinderEngine.glb";
    }
    std::printf("rendered %d of %zu glTF2 samples\n", rendered, files.size());
    EXPECT_TRUE(sawEngine);
    EXPECT_GE(rendered, 10);
}

// A model in millimetres, metres or kilometres looks the same: copies scaled from 0.001x to
// 1000x cover the same pixels as the original, to within anti-aliasing's rounding. Under
// the fixed planes 0.01..100 the small copies were clipped by the near plane and the large
// ones by the far plane.
TEST_F(ModelFraming, ScaledCopiesFrom0001xTo1000xAreFramedAlike)
{
    const ModelData model = loadGltfModel(IBLAB_ASSET_DIR "/models/material_spheres.glb");
    const Coverage original = render(model);
    ASSERT_GT(original.pixels, 200);
    std::printf("1x: %.3f of the frame\n", double(original.fraction()));
    for (const float factor : {0.001f, 0.01f, 0.1f, 10.0f, 100.0f, 1000.0f}) {
        SCOPED_TRACE("scale " + std::to_string(factor));
        const Coverage c = render(scaled(model, factor));
        std::printf("%gx: %.3f of the frame\n", double(factor), double(c.fraction()));
        EXPECT_NEAR(c.fraction(), original.fraction(), 0.01f * original.fraction() + 2.0f / float(kWidth * kHeight));
        EXPECT_NEAR(c.minX, original.minX, 1);
        EXPECT_NEAR(c.maxX, original.maxX, 1);
        EXPECT_NEAR(c.minY, original.minY, 1);
        EXPECT_NEAR(c.maxY, original.maxY, 1);
    }
}

// The planes hold the whole bounding sphere from outside it and from inside it.
TEST(ClipPlanes, HoldTheSceneFromAnyDistance)
{
    for (const float radius : {1e-3f, 1.0f, 1e3f})
        for (const float distance : {0.5f, 3.0f, 1e4f}) {
            CameraSettings camera;
            camera.distance = distance * radius;
            const ClipPlanes planes = clipPlanesFor(camera, glm::vec3(0.0f), radius);
            EXPECT_GE(planes.farPlane, camera.distance + radius);
            EXPECT_LT(planes.nearPlane, planes.farPlane);
            EXPECT_GT(planes.nearPlane, 0.0f);
            if (camera.distance > radius) {
                EXPECT_LE(planes.nearPlane, camera.distance - radius);
            }
        }
}

} // namespace
} // namespace iblab
