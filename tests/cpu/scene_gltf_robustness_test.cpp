// The glTF loader against hostile input: a corpus of broken files built on the fly from a
// one-triangle model (gltf_test_files.hpp): files that are not glTF at all, broken GLB
// containers, buffers that are missing, too large or outside the model's folder, and
// accessors, bufferViews and indices out of range or over budget.
// Every failure must be an iblab::Error whose single line starts with the file's path.
// What a usable file's problems must NOT fail: scene_gltf_features_test.cpp.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <sys/stat.h>

#include "gltf_test_files.hpp"

using namespace iblab;
using namespace iblab::testing;

// ---- the baseline the corpus mutates -------------------------------------------------

TEST(GltfBaseline, TriangleLoadsAsGltfAndGlb)
{
    TempDir dir;
    for (const std::string& path : {writeGltf(dir, triangle()), writeGlb(dir, triangle())}) {
        const ModelData m = loadGltfModel(path);
        EXPECT_TRUE(m.warnings.empty()) << path << ": " << m.warnings.front();
        ASSERT_EQ(m.instances.size(), 1u) << path;
        const MeshData& mesh = m.instances[0].mesh;
        EXPECT_EQ(mesh.indices, (std::vector<std::uint32_t>{0, 1, 2}));
        EXPECT_EQ(mesh.positions[1], glm::vec3(1, 0, 0));
        EXPECT_EQ(mesh.uvs[1], glm::vec2(1, 1));
        for (std::size_t i = 0; i < 3; ++i) {
            EXPECT_EQ(mesh.normals[i], glm::vec3(0, 0, 1)); // computed
            EXPECT_NEAR(glm::distance(glm::vec3(mesh.tangents[i]), glm::vec3(1, 0, 0)), 0.0f, 1e-6f); // generated
        }
        EXPECT_EQ(m.instances[0].materialIndex, -1);
        EXPECT_EQ(m.material(-1).metallicFactor, 1.0f); // glTF's default material
    }
}

// ---- files that are not glTF at all --------------------------------------------------

TEST(GltfCorpus, MissingFile)
{
    TempDir dir;
    EXPECT_EQ(expectLoadError(dir.file("nope.gltf"), {}), dir.file("nope.gltf") + ": no such file");
}

TEST(GltfCorpus, EmptyFile)
{
    TempDir dir;
    writeBytes(dir.file("empty.glb"), "");
    EXPECT_EQ(expectLoadError(dir.file("empty.glb"), {}), dir.file("empty.glb") + ": empty file");
}

TEST(GltfCorpus, NotJsonAtAll)
{
    TempDir dir;
    writeBytes(dir.file("text.gltf"), "hello world, this is not a model");
    EXPECT_EQ(expectLoadError(dir.file("text.gltf"), {}),
              dir.file("text.gltf") + ": not a glTF file: starts with 'hello wo', neither a JSON object nor the GLB magic 'glTF'");
    writeBytes(dir.file("image.glb"), std::string("\x89PNG\r\n\x1a\n\0\0\0\0", 12));
    expectLoadError(dir.file("image.glb"), {"not a binary glTF", "no 'glTF' magic", "89 50 4E 47"});
}

TEST(GltfCorpus, MalformedJson)
{
    TempDir dir;
    writeBytes(dir.file("cut.gltf"), R"({"asset": {"version": "2.0"}, "nodes": [)");
    expectLoadError(dir.file("cut.gltf"), {"malformed JSON", "line 1"});
}

TEST(GltfCorpus, DeeplyNestedJsonFailsFastWithoutRecursing)
{
    // 100000 nested arrays in "extras": a recursive parser would overflow the stack.
    TempDir dir;
    const std::string deep = R"({"asset": {"version": "2.0"}, "extras": )" + std::string(100000, '[') + std::string(100000, ']') + "}";
    writeBytes(dir.file("deep.gltf"), deep);
    const auto start = std::chrono::steady_clock::now();
    EXPECT_EQ(expectLoadError(dir.file("deep.gltf"), {}), dir.file("deep.gltf") + ": JSON nests deeper than 64 levels");
    EXPECT_LT(secondsSince(start), 0.5);
    // Brackets inside strings are text, not nesting.
    GltfBuilder b = triangle();
    b.doc["extras"] = {{"note", std::string(1000, '[')}};
    EXPECT_NO_THROW(loadGltfModel(writeGltf(dir, b, "strings.gltf")));
}

TEST(GltfCorpus, UnsupportedVersionOrRequiredExtension)
{
    TempDir dir;
    GltfBuilder b = triangle();
    b.doc["asset"]["version"] = "1.0";
    expectLoadError(writeGltf(dir, b, "old.gltf"), {"glTF version '1.0' is not supported"});
    b = triangle();
    b.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    b.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    expectLoadError(writeGltf(dir, b, "draco.gltf"), {"requires the extension KHR_draco_mesh_compression"});
}

// ---- GLB container -------------------------------------------------------------------

TEST(GltfCorpus, GlbWithWrongChunkLength)
{
    TempDir dir;
    std::string glb = glbBytes(triangle());
    std::string jsonTooLong = glb;
    const std::uint32_t huge = 1u << 30;
    std::memcpy(&jsonTooLong[12], &huge, 4);
    writeBytes(dir.file("json_chunk.glb"), jsonTooLong);
    expectLoadError(dir.file("json_chunk.glb"), {"GLB chunk 0 declares a length of 1073741824 bytes"});

    std::uint32_t jsonLength = 0;
    std::memcpy(&jsonLength, &glb[12], 4);
    std::string binTooLong = glb;
    std::memcpy(&binTooLong[20 + jsonLength], &huge, 4);
    writeBytes(dir.file("bin_chunk.glb"), binTooLong);
    expectLoadError(dir.file("bin_chunk.glb"), {"GLB chunk 1 declares a length of 1073741824 bytes"});
}

TEST(GltfCorpus, TruncatedGlb)
{
    TempDir dir;
    const std::string glb = glbBytes(triangle());
    writeBytes(dir.file("half.glb"), glb.substr(0, glb.size() / 2));
    expectLoadError(dir.file("half.glb"), {"truncated GLB: the header declares " + std::to_string(glb.size()) + " bytes",
                                           "the file has " + std::to_string(glb.size() / 2) + " bytes"});
    writeBytes(dir.file("stub.glb"), glb.substr(0, 7));
    expectLoadError(dir.file("stub.glb"), {"truncated GLB: 7 bytes, the GLB header alone needs 12"});
}

// ---- buffers -------------------------------------------------------------------------

TEST(GltfCorpus, MissingBufferFile)
{
    TempDir dir;
    GltfBuilder b = triangle();
    b.doc["buffers"] = {{{"uri", "missing.bin"}, {"byteLength", b.bin.size()}}};
    const std::string path = writeGltf(dir, b);
    EXPECT_EQ(expectLoadError(path, {}), path + ": buffers[0]: the file 'missing.bin' not found");
}

TEST(GltfCorpus, BufferUriThatLeavesTheFolder)
{
    TempDir dir;
    GltfBuilder b = triangle();
    writeBytes(dir.file("model.bin"), std::string(b.bin.begin(), b.bin.end()));
    std::filesystem::create_directories(dir.path / "a" / "b");
    for (const auto& [uri, problem] : std::vector<std::pair<std::string, std::string>>{
             {"../../model.bin", "points outside the model's folder"},
             {"x/../../../model.bin", "points outside the model's folder"},
             {"%2E%2E/%2E%2E/model.bin", "points outside the model's folder"},
             {"..\\..\\model.bin", "points outside the model's folder"},
             {dir.file("model.bin"), "is an absolute path"},
             {"file:///etc/passwd", "uses the scheme 'file:'"},
             {"https://example.com/model.bin", "uses the scheme 'https:'"}}) {
        SCOPED_TRACE(uri);
        b.doc["buffers"] = {{{"uri", uri}, {"byteLength", b.bin.size()}}};
        const std::string path = writeGltf(dir, b, "a/b/model.gltf");
        expectLoadError(path, {"buffers[0].uri", problem});
    }
    // Inside the folder, ".." is fine.
    std::filesystem::create_directories(dir.path / "sub");
    b.doc["buffers"] = {{{"uri", "sub/../model.bin"}, {"byteLength", b.bin.size()}}};
    EXPECT_NO_THROW(loadGltfModel(writeGltf(dir, b, "ok.gltf")));
}

TEST(GltfCorpus, DataUriClaimingAGigabyteFailsBeforeAllocating)
{
    TempDir dir;
    GltfBuilder b = triangle();
    b.doc["buffers"] = {{{"uri", "data:application/octet-stream;base64,AAAA"}, {"byteLength", 1000000000}}};
    const std::string path = writeGltf(dir, b, "claims.gltf");
    const auto start = std::chrono::steady_clock::now();
    expectLoadError(path, {"buffers[0] declares 1000000000 bytes, more than the 536870912 bytes input budget"});
    EXPECT_LT(secondsSince(start), 0.2);

    // A payload really larger than what is left of the budget fails before decoding.
    b.doc["buffers"] = {{{"uri", "data:application/octet-stream;base64," + std::string(40000, 'A')}, {"byteLength", 16}}};
    ModelLoadOptions small;
    small.maxInputBytes = 50000;
    expectLoadError(writeGltf(dir, b, "holds.gltf"), {"buffers[0] (data URI) needs 30003 bytes", "input budget"}, small);
}

TEST(GltfCorpus, BufferSmallerThanDeclaredOrNotAFile)
{
    TempDir dir;
    GltfBuilder b = triangle();
    writeBytes(dir.file("short.bin"), "abc");
    b.doc["buffers"] = {{{"uri", "short.bin"}, {"byteLength", b.bin.size()}}};
    expectLoadError(writeGltf(dir, b, "short.gltf"), {"the file 'short.bin' has 3 bytes, its byteLength says 66"});
    // A FIFO would block a naive reader forever.
    ASSERT_EQ(::mkfifo(dir.file("fifo.bin").c_str(), 0600), 0);
    b.doc["buffers"] = {{{"uri", "fifo.bin"}, {"byteLength", b.bin.size()}}};
    expectLoadError(writeGltf(dir, b, "fifo.gltf"), {"'fifo.bin' is not a regular file"});
}

// ---- accessors and indices ------------------------------------------------------------

TEST(GltfCorpus, AccessorOutOfRangeOfItsBufferView)
{
    TempDir dir;
    GltfBuilder b = triangle();
    b.doc["accessors"][0]["count"] = 1000;
    b.doc["accessors"][1]["count"] = 1000;
    expectLoadError(writeGltf(dir, b), {"meshes[0].primitives[0] POSITION (accessors[0])", "1000 elements of 12 bytes",
                                        "bufferViews[0], which has only 36 bytes", "out of range"});
    expectTriangleWithFails(dir, "/accessors/0/byteOffset", 4, {"accessors[0]", "out of range"});
    // Even a count near 2^64 must not overflow the range arithmetic.
    expectTriangleWithFails(dir, "/accessors/2/count", 18446744073709551615ull, {"indices (accessors[2])"});
}

TEST(GltfCorpus, BufferViewOutOfRangeOfItsBuffer)
{
    TempDir dir;
    expectTriangleWithFails(dir, "/bufferViews/2/byteLength", 10000,
                            {"bufferViews[2] (bytes 60..10060) runs past the end of buffers[0] (66 bytes)"});
    expectTriangleWithFails(dir, "/bufferViews/0/buffer", 3, {"bufferViews[0].buffer 3 does not exist"});
}

TEST(GltfCorpus, IndexPastTheVertexCount)
{
    TempDir dir;
    GltfBuilder b = triangle();
    b.bin[60 + 4] = 7; // the third index, little-endian
    const std::string path = writeGltf(dir, b);
    EXPECT_EQ(expectLoadError(path, {}),
              path + ": meshes[0].primitives[0] indices: index 7 (at position 2) is past the 3 vertices");
}

TEST(GltfCorpus, AccessorTypesAndComponentTypesAreChecked)
{
    TempDir dir;
    expectTriangleWithFails(dir, "/accessors/0/type", "VEC2", {"POSITION (accessors[0]) is VEC2, expected VEC3"});
    expectTriangleWithFails(dir, "/accessors/0/componentType", kUInt, {"POSITION (accessors[0]) has component type 5125"});
    expectTriangleWithFails(dir, "/accessors/2/componentType", kFloat, {"indices (accessors[2]) has component type 5126"});
    expectTriangleWithFails(dir, "/accessors/1/count", 2, {"TEXCOORD_0 (accessors[1]) has 2 elements, POSITION has 3"});
}

TEST(GltfCorpus, VertexAndIndexBudgets)
{
    TempDir dir;
    const std::string path = writeGltf(dir, triangle());
    ModelLoadOptions options;
    options.maxVertices = 2;
    expectLoadError(path, {"past the 2-vertex budget"}, options);
    options = {};
    options.maxIndices = 2;
    expectLoadError(path, {"past the 2-index budget"}, options);
}
