// The glTF loader on files that are unusual but usable: texture images that are missing,
// undecodable, escaping the model's folder or oversized (the load succeeds with a warning
// and the slot falls back to its factor), and the format features artists' files use
// (non-indexed and quantized attributes, strips and fans, sparse accessors, node transforms,
// cycles and deep chains), plus export of a model without materials. The corpus of files
// that must fail: scene_gltf_robustness_test.cpp.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "gltf_test_files.hpp"
#include "io/error.hpp"
#include "malformed_images.hpp"

using namespace iblab;
using namespace iblab::testing;
using nlohmann::json;

// ---- textures: problems that must NOT fail the load -----------------------------------

TEST(GltfTextures, MissingImageFallsBackToTheFactorWithAWarning)
{
    TempDir dir;
    GltfBuilder b = triangle();
    addTexturedMaterial(b, "missing.png");
    const ModelData m = loadGltfModel(writeGltf(dir, b));
    EXPECT_TRUE(anyWarningContains(m, {"'missing.png'", "not found", "fall back"}));
    ASSERT_EQ(m.materials.size(), 1u);
    EXPECT_FALSE(m.materials[0].baseColorTexture.valid());
    EXPECT_EQ(m.materials[0].baseColorFactor, glm::vec4(0.5f, 0.5f, 0.5f, 1.0f));
    EXPECT_TRUE(m.textures.empty());
    EXPECT_EQ(m.instances.size(), 1u);
}

TEST(GltfTextures, UndecodableOrEscapingImagesWarn)
{
    TempDir dir;
    GltfBuilder b = triangle();
    writeBytes(dir.file("junk.png"), "this is not a png");
    addTexturedMaterial(b, "junk.png");
    ModelData m = loadGltfModel(writeGltf(dir, b));
    EXPECT_TRUE(anyWarningContains(m, {"'junk.png'", "cannot be decoded"})) << joined(m.warnings);
    EXPECT_FALSE(m.materials[0].baseColorTexture.valid());

    writeBytes(dir.file("secret.png"), "outside");
    std::filesystem::create_directories(dir.path / "sub");
    addTexturedMaterial(b, "../secret.png");
    b.doc["buffers"] = {{{"uri", "../model.bin"}, {"byteLength", b.bin.size()}}};
    writeBytes(dir.file("model.bin"), std::string(b.bin.begin(), b.bin.end()));
    expectLoadError(writeGltf(dir, b, "sub/model.gltf"), {"points outside the model's folder"});
    b.doc["buffers"] = {{{"uri", "model.bin"}, {"byteLength", b.bin.size()}}};
    writeBytes(dir.file("sub/model.bin"), std::string(b.bin.begin(), b.bin.end()));
    m = loadGltfModel(writeGltf(dir, b, "sub/model.gltf"));
    EXPECT_TRUE(anyWarningContains(m, {"'../secret.png'", "points outside the model's folder"}));
}

TEST(GltfTextures, BadTextureReferencesAreIgnored)
{
    TempDir dir;
    GltfBuilder b = triangle();
    b.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 9}}}}}, {"alphaMode", "WEIRD"}}};
    b.primitive()["material"] = 0;
    const ModelData m = loadGltfModel(writeGltf(dir, b));
    EXPECT_TRUE(anyWarningContains(m, {"textures[9], which does not exist"}));
    EXPECT_TRUE(anyWarningContains(m, {"alphaMode 'WEIRD'"}));
    EXPECT_EQ(m.materials[0].alphaMode, AlphaMode::Opaque);
}

TEST(GltfTextures, OversizedImagesAreDownsampledOrRefused)
{
    TempDir dir;
    // 128 x 64 one-texel checkerboard of 0 and 255: every 4 x 4 block averages to 128.
    std::vector<std::uint8_t> rgba(128 * 64 * 4);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 128; ++x)
            for (int c = 0; c < 4; ++c) rgba[std::size_t((y * 128 + x) * 4 + c)] = c == 3 ? 255 : ((x + y) % 2) * 255;
    writePng(dir.file("big.png"), 128, 64, rgba);
    GltfBuilder b = triangle();
    addTexturedMaterial(b, "big.png");
    const std::string path = writeGltf(dir, b);

    ModelLoadOptions options;
    options.maxTextureDimension = 32;
    ModelData m = loadGltfModel(path, options);
    ASSERT_EQ(m.textures.size(), 1u);
    EXPECT_EQ(m.textures[0].width, 32);
    EXPECT_EQ(m.textures[0].height, 16);
    EXPECT_TRUE(m.textures[0].srgb);
    for (std::size_t i = 0; i < m.textures[0].rgba8.size(); i += 4) ASSERT_EQ(m.textures[0].rgba8[i], 128) << i;
    EXPECT_TRUE(anyWarningContains(m, {"'big.png'", "downsampled to 32x16"}));

    options.maxTextureDimension = 8; // 128 > 8 x 8: not even decoded
    m = loadGltfModel(path, options);
    EXPECT_TRUE(m.textures.empty());
    EXPECT_TRUE(anyWarningContains(m, {"'big.png'", "claims 128x64 texels"}));

    options = {};
    options.maxTextureBytes = 1000;
    m = loadGltfModel(path, options);
    EXPECT_TRUE(m.textures.empty());
    EXPECT_TRUE(anyWarningContains(m, {"'big.png'", "texture budget"}));
}

TEST(GltfTextures, TextureWithAChunkLongerThanItsFileIsSkippedBeforeDecoding)
{
    // Texture bytes are decoded from memory: libpng would allocate and zero the claimed
    // 1.97 GB for the text chunk before noticing that 7 bytes follow.
    TempDir dir;
    std::ofstream(dir.file("text-chunk.png"), std::ios::binary) << iblab::testing::pngClaimingAHugeTextChunk();
    GltfBuilder b = triangle();
    addTexturedMaterial(b, "text-chunk.png");
    const ModelData m = loadGltfModel(writeGltf(dir, b));
    EXPECT_TRUE(m.textures.empty());
    EXPECT_TRUE(anyWarningContains(m, {"'text-chunk.png'", "corrupt PNG: chunk 'tEXt' claims 1970828288 bytes, more than the 7 left"}));
}

// ---- format features ----------------------------------------------------------------

TEST(GltfFeatures, NonIndexedAndNormalizedIntegerTexcoords)
{
    TempDir dir;
    GltfBuilder b = triangle();
    b.primitive().erase("indices");
    b.primitive()["attributes"]["TEXCOORD_0"] = b.accessor(b.view(std::vector<std::uint8_t>{0, 0, 255, 0, 128, 255}), kUByte, 3, "VEC2", true);
    b.primitive()["attributes"]["TEXCOORD_1"] =
        b.accessor(b.view(std::vector<std::uint16_t>{0, 65535, 65535, 0, 0, 0}), kUShort, 3, "VEC2", true);
    const ModelData m = loadGltfModel(writeGltf(dir, b));
    ASSERT_EQ(m.instances.size(), 1u);
    const MeshData& mesh = m.instances[0].mesh;
    EXPECT_EQ(mesh.indices, (std::vector<std::uint32_t>{0, 1, 2}));
    EXPECT_EQ(mesh.uvs[1], glm::vec2(1, 0));
    EXPECT_FLOAT_EQ(mesh.uvs[2].x, 128.0f / 255.0f);
    EXPECT_EQ(mesh.uvs1[0], glm::vec2(0, 1));
}

TEST(GltfFeatures, StripsAndFansBecomeListsAndPointsAreSkipped)
{
    TempDir dir;
    GltfBuilder b;
    const int strip = b.accessor(b.view(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}), kFloat, 4, "VEC3");
    const int fan = b.accessor(b.view(std::vector<float>{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}), kFloat, 4, "VEC3");
    b.doc["meshes"] = {{{"primitives",
                         {{{"attributes", {{"POSITION", strip}}}, {"mode", 5}},
                          {{"attributes", {{"POSITION", fan}}}, {"mode", 6}},
                          {{"attributes", {{"POSITION", fan}}}, {"mode", 0}}}}}};
    b.doc["nodes"] = {{{"mesh", 0}}};
    b.doc["scenes"] = {{{"nodes", {0}}}};
    const ModelData m = loadGltfModel(writeGltf(dir, b));
    ASSERT_EQ(m.instances.size(), 2u);
    EXPECT_EQ(m.instances[0].mesh.indices, (std::vector<std::uint32_t>{0, 1, 2, 1, 3, 2}));
    EXPECT_EQ(m.instances[1].mesh.indices, (std::vector<std::uint32_t>{1, 2, 0, 2, 3, 0}));
    for (const MeshInstance& inst : m.instances)
        for (const glm::vec3& n : inst.mesh.normals) EXPECT_EQ(n, glm::vec3(0, 0, 1)) << inst.name; // all counter-clockwise
    EXPECT_TRUE(anyWarningContains(m, {"primitives[2]", "mode POINTS", "skipped"}));
}

TEST(GltfFeatures, SparseAccessorsOverrideTheirBase)
{
    TempDir dir;
    GltfBuilder b = triangle();
    // POSITION without a bufferView (all zeros) plus sparse values for all 3 vertices,
    // then a second, dense-based one moving vertex 1.
    const int sparseIndices = b.view(std::vector<std::uint8_t>{0, 1, 2, 0});
    const int sparseValues = b.view(std::vector<float>{0, 0, 0, 2, 0, 0, 0, 2, 0});
    json& position = b.doc["accessors"][0];
    position.erase("bufferView");
    position["sparse"] = {{"count", 3},
                          {"indices", {{"bufferView", sparseIndices}, {"componentType", kUByte}}},
                          {"values", {{"bufferView", sparseValues}}}};
    ModelData m = loadGltfModel(writeGltf(dir, b));
    ASSERT_EQ(m.instances.size(), 1u);
    EXPECT_EQ(m.instances[0].mesh.positions, (std::vector<glm::vec3>{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}}));

    position["sparse"]["count"] = 4;
    expectLoadError(writeGltf(dir, b), {"sparse.count 4 is not in 0..3"});
    position["sparse"]["count"] = 3;
    b.bin[std::size_t(b.doc["bufferViews"][std::size_t(sparseIndices)]["byteOffset"]) + 2] = 9;
    expectLoadError(writeGltf(dir, b), {"sparse index 9 is past the 3 elements"});
}

TEST(GltfFeatures, NodeTransformsAreBakedAndMirroringKeepsFrontFaces)
{
    TempDir dir;
    GltfBuilder b = triangle();
    b.doc["nodes"] = {{{"translation", {0, 0, 5}}, {"children", {1}}}, {{"mesh", 0}, {"scale", {-2, 1, 1}}}};
    const ModelData m = loadGltfModel(writeGltf(dir, b));
    ASSERT_EQ(m.instances.size(), 1u);
    const MeshData& mesh = m.instances[0].mesh;
    EXPECT_EQ(mesh.positions[1], glm::vec3(-2, 0, 5));
    const glm::vec3 face = glm::cross(mesh.positions[mesh.indices[1]] - mesh.positions[mesh.indices[0]],
                                      mesh.positions[mesh.indices[2]] - mesh.positions[mesh.indices[0]]);
    EXPECT_GT(glm::dot(face, mesh.normals[0]), 0.0f);
    EXPECT_EQ(m.instances[0].worldMatrix[3][2], 5.0f);
    EXPECT_EQ(m.bounds.max, glm::vec3(0, 1, 5));
}

TEST(GltfFeatures, NodeCyclesAndDeepChainsNeitherHangNorOverflow)
{
    TempDir dir;
    GltfBuilder b = triangle();
    b.doc["nodes"] = {{{"mesh", 0}, {"children", {1}}}, {{"children", {0}}}};
    ModelData m = loadGltfModel(writeGltf(dir, b, "cycle.gltf"));
    EXPECT_EQ(m.instances.size(), 1u);
    EXPECT_TRUE(anyWarningContains(m, {"nodes[0] is reached a second time"}));

    // 50000 nodes, each the only child of the previous one, the mesh at the bottom: a
    // recursive walk would need more than the default 8 MB of stack.
    b = triangle();
    json nodes = json::array();
    constexpr int kChain = 50000;
    for (int i = 0; i < kChain - 1; ++i) nodes.push_back({{"children", {i + 1}}, {"translation", {0, 0, 0.001}}});
    nodes.push_back({{"mesh", 0}});
    b.doc["nodes"] = std::move(nodes);
    m = loadGltfModel(writeGltf(dir, b, "chain.gltf"));
    ASSERT_EQ(m.instances.size(), 1u);
    EXPECT_NEAR(m.instances[0].mesh.positions[0].z, 0.001f * (kChain - 1), 1e-2f);
}

// A model that loads but has nothing to draw (its one primitive skipped for non-finite
// positions): loadGltfModel returns it with the reasons, loadDrawableGltfModel, which the
// GUI, render and bench use, refuses it naming the file and those reasons.
TEST(GltfFeatures, AModelWithNothingToDrawIsRefusedByTheDrawableLoad)
{
    TempDir dir;
    GltfBuilder b = triangle();
    b.doc["nodes"] = {{{"mesh", 0}, {"scale", {0, 0, 0}}}};
    const std::string path = writeGltf(dir, b, "flat.gltf");
    const ModelData m = loadGltfModel(path);
    EXPECT_TRUE(m.instances.empty());
    EXPECT_TRUE(anyWarningContains(m, {"no triangles to show"}));
    try {
        loadDrawableGltfModel(path);
        ADD_FAILURE() << "a model with nothing to draw was accepted";
    } catch (const iblab::Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("flat.gltf: nothing to draw; "), std::string::npos) << what;
        EXPECT_NE(what.find("no triangles to show"), std::string::npos) << what;
    }
    EXPECT_EQ(loadDrawableGltfModel(writeGltf(dir, triangle(), "fine.gltf")).instances.size(), 1u);
}

TEST(GltfFeatures, ExportAddsAMaterialForPrimitivesWithoutOne)
{
    TempDir dir;
    const std::string source = writeGlb(dir, triangle());
    PbrMaterial tuned;
    tuned.baseColorFactor = glm::vec4(0.1f, 0.2f, 0.3f, 1.0f);
    tuned.roughnessFactor = 0.4f;
    exportGltfWithMaterial(source, dir.file("out.glb"), -1, tuned);
    const ModelData m = loadGltfModel(dir.file("out.glb"));
    ASSERT_EQ(m.materials.size(), 1u);
    EXPECT_EQ(m.instances[0].materialIndex, 0);
    EXPECT_EQ(m.materials[0].baseColorFactor, tuned.baseColorFactor);
    EXPECT_EQ(m.materials[0].roughnessFactor, 0.4f);
}
