// Loading real glTF models (the generated test model, the shared CC0/CC-BY candidates)
// and exporting tuned copies. Expected counts come from reading the files' JSON here,
// independently of the loader.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/error.hpp"
#include "scene/gltf_model.hpp"
#include "scene/sphere.hpp"
#include "scene/test_model.hpp"
#include "temp_dir.hpp"

namespace fs = std::filesystem;
using namespace iblab;
using iblab::testing::TempDir;
using nlohmann::json;

namespace {

const fs::path kSpheres = fs::path(IBLAB_SOURCE_DIR) / "assets" / "models" / "material_spheres.glb";
const fs::path kShared = IBLAB_SHARED_ASSETS;
const fs::path kBunny = kShared / "models" / "pmndrs" / "bunny_nodraco.glb";
const fs::path kClearCoat = kShared / "models" / "assimp-clearcoat" / "ClearCoatTest.gltf";

#define SKIP_IF_MISSING(path)                                                                                          \
    if (!fs::exists(path))                                                                                             \
    GTEST_SKIP() << (path) << " is not available"

json readGltfJson(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), {});
    if (bytes.rfind("glTF", 0) == 0) {
        std::uint32_t length = 0;
        std::memcpy(&length, bytes.data() + 12, 4);
        return json::parse(bytes.substr(20, length));
    }
    return json::parse(bytes);
}

// (node, primitive) pairs of the default scene, walked here without the loader.
std::size_t countScenePrimitives(const json& doc)
{
    std::size_t count = 0;
    const std::function<void(int)> visit = [&](int node) {
        const json& n = doc["nodes"][std::size_t(node)];
        if (n.contains("mesh"))
            count += doc["meshes"][n["mesh"].get<std::size_t>()]["primitives"].size();
        for (const json& c : n.value("children", json::array())) visit(c.get<int>());
    };
    for (const json& root : doc["scenes"][doc.value("scene", 0)]["nodes"]) visit(root.get<int>());
    return count;
}

void expectUnitAndOrthogonal(const MeshData& m)
{
    for (std::size_t i = 0; i < m.vertexCount(); ++i) {
        ASSERT_NEAR(glm::length(m.normals[i]), 1.0f, 1e-5f) << i;
        ASSERT_NEAR(glm::length(glm::vec3(m.tangents[i])), 1.0f, 1e-5f) << i;
        ASSERT_NEAR(glm::dot(m.normals[i], glm::vec3(m.tangents[i])), 0.0f, 1e-5f) << i;
        ASSERT_TRUE(m.tangents[i].w == 1.0f || m.tangents[i].w == -1.0f) << i;
    }
}

void expectSameGeometry(const ModelData& a, const ModelData& b)
{
    ASSERT_EQ(a.instances.size(), b.instances.size());
    for (std::size_t i = 0; i < a.instances.size(); ++i) {
        EXPECT_EQ(a.instances[i].name, b.instances[i].name);
        EXPECT_EQ(a.instances[i].mesh.positions, b.instances[i].mesh.positions);
        EXPECT_EQ(a.instances[i].mesh.normals, b.instances[i].mesh.normals);
        EXPECT_EQ(a.instances[i].mesh.uvs, b.instances[i].mesh.uvs);
        EXPECT_EQ(a.instances[i].mesh.indices, b.instances[i].mesh.indices);
        EXPECT_EQ(a.instances[i].materialIndex, b.instances[i].materialIndex);
    }
}

void expectSameTextures(const ModelData& a, const ModelData& b)
{
    ASSERT_EQ(a.textures.size(), b.textures.size());
    for (std::size_t i = 0; i < a.textures.size(); ++i) {
        EXPECT_EQ(a.textures[i].width, b.textures[i].width);
        EXPECT_EQ(a.textures[i].srgb, b.textures[i].srgb);
        EXPECT_TRUE(a.textures[i].rgba8 == b.textures[i].rgba8) << "texture " << i << " changed";
    }
}

bool anyWarningContains(const ModelData& m, const std::string& text)
{
    return std::any_of(m.warnings.begin(), m.warnings.end(), [&](const std::string& w) { return w.find(text) != std::string::npos; });
}

} // namespace

TEST(MaterialSpheres, LoadsWithTexturesMaterialsAndPlacement)
{
    const ModelData m = loadGltfModel(kSpheres.string());
    EXPECT_TRUE(m.warnings.empty()) << m.warnings.front();
    ASSERT_EQ(m.instances.size(), 3u);
    ASSERT_EQ(m.materials.size(), 3u);
    const MeshData sphere = makeUvSphere(1.0f, 64, 32);
    const float expectedX[] = {-2.5f, 0.0f, 2.5f};
    for (std::size_t i = 0; i < 3; ++i) {
        const MeshInstance& inst = m.instances[i];
        EXPECT_EQ(inst.materialIndex, int(i));
        EXPECT_EQ(inst.mesh.vertexCount(), sphere.vertexCount());
        EXPECT_EQ(inst.mesh.indices, sphere.indices);
        EXPECT_FLOAT_EQ(inst.worldMatrix[3][0], expectedX[i]);
        EXPECT_NEAR(computeBounds(inst.mesh).center().x, expectedX[i], 1e-6f);
        EXPECT_NO_THROW(inst.mesh.validate(inst.name));
        expectUnitAndOrthogonal(inst.mesh);
    }
    EXPECT_EQ(m.instances[1].name, "gold/sphere_gold#0");
    EXPECT_NEAR(m.bounds.min.x, -3.5f, 1e-6f);
    EXPECT_NEAR(m.bounds.max.x, 3.5f, 1e-6f);

    const PbrMaterial& textured = m.materials[0];
    EXPECT_EQ(textured.name, "textured");
    ASSERT_TRUE(textured.baseColorTexture.valid() && textured.metallicRoughnessTexture.valid() &&
                textured.normalTexture.valid() && textured.occlusionTexture.valid());
    EXPECT_FALSE(textured.emissiveTexture.valid());
    const PbrMaterial& gold = m.materials[1];
    EXPECT_FLOAT_EQ(gold.baseColorFactor.g, 0.766f);
    EXPECT_FLOAT_EQ(gold.metallicFactor, 1.0f);
    EXPECT_FLOAT_EQ(gold.roughnessFactor, 0.3f);
    EXPECT_FALSE(gold.baseColorTexture.valid());
    const PbrMaterial& emissive = m.materials[2];
    EXPECT_EQ(emissive.emissiveFactor, glm::vec3(1.0f, 0.5f, 0.1f));
    ASSERT_TRUE(emissive.emissiveTexture.valid());

    // Colour textures are sRGB, data textures linear; pixels decode exactly (PNG).
    ASSERT_EQ(m.textures.size(), 5u);
    const std::vector<TextureImage> generated = materialSpheresTextures();
    const TextureRef refs[] = {textured.baseColorTexture, textured.metallicRoughnessTexture, textured.normalTexture,
                               textured.occlusionTexture, emissive.emissiveTexture};
    const bool srgb[] = {true, false, false, false, true};
    for (std::size_t i = 0; i < 5; ++i) {
        const TextureImage& t = m.textures[std::size_t(refs[i].index)];
        EXPECT_EQ(t.srgb, srgb[i]) << generated[i].name;
        EXPECT_EQ(t.width, 64);
        EXPECT_EQ(t.height, 64);
        EXPECT_EQ(t.name, generated[i].name);
        EXPECT_TRUE(t.rgba8 == generated[i].rgba8) << generated[i].name << " does not decode to what was generated";
    }
}

TEST(MaterialSpheres, CommittedFileIsWhatTheGeneratorWrites)
{
    // Catches a stale assets/models/material_spheres.glb after the generator changed.
    TempDir dir;
    const std::string fresh = dir.file("spheres.glb");
    writeMaterialSpheresGlb(fresh);
    const ModelData committed = loadGltfModel(kSpheres.string());
    const ModelData regenerated = loadGltfModel(fresh);
    expectSameGeometry(committed, regenerated);
    expectSameTextures(committed, regenerated);
    EXPECT_LT(fs::file_size(kSpheres), 300u * 1024u) << "keep the committed model small";
}

TEST(SharedModels, BunnyLoadsWithComputedTangents)
{
    SKIP_IF_MISSING(kBunny);
    const json doc = readGltfJson(kBunny);
    const ModelData m = loadGltfModel(kBunny.string());
    EXPECT_TRUE(m.warnings.empty()) << m.warnings.front();
    ASSERT_EQ(m.instances.size(), 1u);
    const MeshData& mesh = m.instances[0].mesh;
    EXPECT_EQ(mesh.vertexCount(), doc["accessors"][1]["count"].get<std::size_t>());
    EXPECT_EQ(mesh.indices.size(), doc["accessors"][0]["count"].get<std::size_t>());
    EXPECT_TRUE(mesh.uvs.empty());
    EXPECT_NO_THROW(mesh.validate("bunny"));
    expectUnitAndOrthogonal(mesh);
    ASSERT_EQ(m.materials.size(), 1u);
    EXPECT_EQ(m.materials[0].alphaMode, AlphaMode::Blend);
    EXPECT_TRUE(m.materials[0].doubleSided);
    EXPECT_FLOAT_EQ(m.materials[0].roughnessFactor, 0.5f);
    EXPECT_FLOAT_EQ(m.materials[0].metallicFactor, 0.0f);
    EXPECT_FALSE(m.bounds.empty());
    EXPECT_GT(m.bounds.radius(), 0.0f);
}

TEST(SharedModels, ClearCoatTestLoadsItsSceneAndTextures)
{
    SKIP_IF_MISSING(kClearCoat);
    const json doc = readGltfJson(kClearCoat);
    const ModelData m = loadGltfModel(kClearCoat.string());
    EXPECT_EQ(m.instances.size(), countScenePrimitives(doc));
    EXPECT_EQ(m.materials.size(), doc["materials"].size());
    // Its clearcoat extension is not modelled: one warning says so; no texture failed.
    EXPECT_TRUE(anyWarningContains(m, "KHR_materials_clearcoat"));
    EXPECT_FALSE(anyWarningContains(m, "fall back"));
    for (std::size_t i = 0; i < m.materials.size(); ++i) {
        const json& mat = doc["materials"][i];
        const PbrMaterial& p = m.materials[i];
        EXPECT_EQ(p.name, mat["name"].get<std::string>());
        const json pbr = mat.value("pbrMetallicRoughness", json::object());
        EXPECT_EQ(p.baseColorTexture.valid(), pbr.contains("baseColorTexture")) << p.name;
        EXPECT_EQ(p.normalTexture.valid(), mat.contains("normalTexture")) << p.name;
        if (pbr.contains("roughnessFactor")) {
            EXPECT_FLOAT_EQ(p.roughnessFactor, pbr["roughnessFactor"].get<float>()) << p.name;
        }
    }
    for (const TextureImage& t : m.textures) {
        EXPECT_GT(t.width, 0);
        EXPECT_EQ(t.rgba8.size(), std::size_t(t.width) * std::size_t(t.height) * 4);
    }
    for (const MeshInstance& inst : m.instances) {
        EXPECT_NO_THROW(inst.mesh.validate(inst.name));
        EXPECT_EQ(inst.mesh.uvs.size(), inst.mesh.vertexCount()) << inst.name;
    }
}

TEST(Export, TunedFactorsRoundTripAndEverythingElseStays)
{
    TempDir dir;
    const ModelData before = loadGltfModel(kSpheres.string());
    PbrMaterial tuned = before.materials[1];
    tuned.baseColorFactor = glm::vec4(0.2f, 0.4f, 0.6f, 0.8f);
    tuned.metallicFactor = 0.25f;
    tuned.roughnessFactor = 0.75f;
    tuned.emissiveFactor = glm::vec3(0.5f, 0.25f, 0.0f);
    tuned.alphaMode = AlphaMode::Mask;
    tuned.alphaCutoff = 0.3f;
    tuned.doubleSided = true;
    const std::string out = dir.file("tuned.glb");
    EXPECT_TRUE(exportGltfWithMaterial(kSpheres.string(), out, 1, tuned).empty());
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"tuned.glb"}); // no temporary left behind

    const ModelData after = loadGltfModel(out);
    EXPECT_TRUE(after.warnings.empty());
    const PbrMaterial& m = after.materials[1];
    EXPECT_EQ(m.baseColorFactor, tuned.baseColorFactor);
    EXPECT_EQ(m.metallicFactor, 0.25f);
    EXPECT_EQ(m.roughnessFactor, 0.75f);
    EXPECT_EQ(m.emissiveFactor, tuned.emissiveFactor);
    EXPECT_EQ(m.alphaMode, AlphaMode::Mask);
    EXPECT_EQ(m.alphaCutoff, 0.3f);
    EXPECT_TRUE(m.doubleSided);
    EXPECT_EQ(m.name, "gold");
    // The other materials are untouched.
    for (std::size_t i : {0u, 2u}) {
        EXPECT_EQ(after.materials[i].baseColorFactor, before.materials[i].baseColorFactor);
        EXPECT_EQ(after.materials[i].emissiveFactor, before.materials[i].emissiveFactor);
        EXPECT_EQ(after.materials[i].baseColorTexture.valid(), before.materials[i].baseColorTexture.valid());
    }
    expectSameGeometry(before, after);
    expectSameTextures(before, after);
}

TEST(Export, EmissionAboveOneUsesEmissiveStrength)
{
    TempDir dir;
    PbrMaterial tuned = loadGltfModel(kSpheres.string()).materials[2];
    tuned.emissiveFactor = glm::vec3(8.0f, 4.0f, 0.0f);
    tuned.occlusionStrength = 0.5f; // material 2 has no occlusion texture: not stored
    const std::string out = dir.file("bright.glb");
    exportGltfWithMaterial(kSpheres.string(), out, 2, tuned);
    const json doc = readGltfJson(out);
    const json& m = doc["materials"][2];
    EXPECT_EQ(m["emissiveFactor"], json({1.0, 0.5, 0.0}));
    EXPECT_EQ(m["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"], 8.0);
    EXPECT_FALSE(m.contains("occlusionTexture"));
    EXPECT_NE(std::find(doc["extensionsUsed"].begin(), doc["extensionsUsed"].end(), "KHR_materials_emissive_strength"),
              doc["extensionsUsed"].end());
    EXPECT_EQ(loadGltfModel(out).materials[2].emissiveFactor, glm::vec3(8.0f, 4.0f, 0.0f));

    // Back to <= 1: the extension goes away again.
    tuned.emissiveFactor = glm::vec3(0.5f);
    exportGltfWithMaterial(out, out, 2, tuned);
    EXPECT_FALSE(readGltfJson(out)["materials"][2].contains("extensions"));
    EXPECT_EQ(loadGltfModel(out).materials[2].emissiveFactor, glm::vec3(0.5f));
}

TEST(Export, GltfWithExternalFilesBecomesSelfContained)
{
    SKIP_IF_MISSING(kClearCoat);
    TempDir dir;
    const ModelData before = loadGltfModel(kClearCoat.string());
    PbrMaterial tuned = before.materials[0];
    tuned.roughnessFactor = 0.125f;
    for (const char* name : {"copy.glb", "copy.gltf"}) {
        const std::string out = dir.file(name);
        EXPECT_TRUE(exportGltfWithMaterial(kClearCoat.string(), out, 0, tuned).empty());
        // Only the one file: buffers and images are inside it.
        const ModelData after = loadGltfModel(out);
        EXPECT_EQ(after.materials[0].roughnessFactor, 0.125f);
        EXPECT_EQ(after.materials[3].roughnessFactor, before.materials[3].roughnessFactor);
        expectSameGeometry(before, after);
        expectSameTextures(before, after);
        EXPECT_FALSE(anyWarningContains(after, "fall back"));
        // Unmodelled content (the clearcoat extension) passes through.
        const json source = readGltfJson(kClearCoat), copy = readGltfJson(out);
        std::size_t withExtensions = 0;
        for (std::size_t i = 0; i < source["materials"].size(); ++i)
            if (source["materials"][i].contains("extensions")) {
                ++withExtensions;
                EXPECT_EQ(copy["materials"][i]["extensions"], source["materials"][i]["extensions"]) << i;
            }
        EXPECT_GT(withExtensions, 0u);
    }
    EXPECT_EQ(dir.entries(), (std::vector<std::string>{"copy.glb", "copy.gltf"}));
}

TEST(Export, RefusesBadRequestsAndLeavesTheTargetAlone)
{
    TempDir dir;
    const std::string out = dir.file("keep.glb");
    std::ofstream(out) << "previous";
    const auto message = [&](const std::string& target, int material) -> std::string {
        try {
            exportGltfWithMaterial(kSpheres.string(), target, material, PbrMaterial{});
        } catch (const Error& e) {
            return e.what();
        }
        return "";
    };
    EXPECT_EQ(message(out, 3), kSpheres.string() + ": materials[3] does not exist (the model has 3 materials; -1 adds one)");
    EXPECT_EQ(message(dir.file("x.obj"), 0), dir.file("x.obj") + ": exports are written as .glb or .gltf, not '.obj'");
    EXPECT_NE(message(dir.file("no/such/dir/x.glb"), 0).find("does not exist"), std::string::npos);
    std::ifstream in(out);
    EXPECT_EQ(std::string((std::istreambuf_iterator<char>(in)), {}), "previous");
}
