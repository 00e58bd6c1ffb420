// The glTF loader against hostile and unusual input: a corpus of broken files built on
// the fly from a one-triangle model (written here with nlohmann_json and a hand-rolled
// GLB writer, independent of the code under test), plus the format features artists'
// files use (strips, fans, sparse and quantized accessors, node transforms).
// Every failure must be an iblab::Error whose single line starts with the file's path.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <sys/stat.h>

#include <OpenImageIO/imageio.h>
#include <nlohmann/json.hpp>

#include "io/error.hpp"
#include "scene/gltf_model.hpp"
#include "temp_dir.hpp"

using namespace iblab;
using iblab::testing::TempDir;
using nlohmann::json;

namespace {

constexpr int kUByte = 5121, kUShort = 5123, kUInt = 5125, kFloat = 5126;

struct GltfBuilder {
    json doc = {{"asset", {{"version", "2.0"}}}, {"scene", 0}};
    std::vector<std::uint8_t> bin;

    template <class T>
    int view(const std::vector<T>& data)
    {
        bin.resize((bin.size() + 3) / 4 * 4, 0);
        doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", data.size() * sizeof(T)}});
        const auto* bytes = reinterpret_cast<const std::uint8_t*>(data.data());
        bin.insert(bin.end(), bytes, bytes + data.size() * sizeof(T));
        return int(doc["bufferViews"].size() - 1);
    }
    int accessor(int view, int componentType, std::size_t count, const char* type, bool normalized = false)
    {
        json a = {{"componentType", componentType}, {"count", count}, {"type", type}};
        if (view >= 0)
            a["bufferView"] = view;
        if (normalized)
            a["normalized"] = true;
        doc["accessors"].push_back(a);
        return int(doc["accessors"].size() - 1);
    }
    json& primitive() { return doc["meshes"][0]["primitives"][0]; }
};

// One triangle in the z = 0 plane facing +Z: accessors 0 POSITION, 1 TEXCOORD_0,
// 2 indices (unsigned short), one node, one scene, no material.
GltfBuilder triangle()
{
    GltfBuilder b;
    const int position = b.accessor(b.view(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0}), kFloat, 3, "VEC3");
    const int uv = b.accessor(b.view(std::vector<float>{0, 1, 1, 1, 0, 0}), kFloat, 3, "VEC2");
    const int indices = b.accessor(b.view(std::vector<std::uint16_t>{0, 1, 2}), kUShort, 3, "SCALAR");
    const json primitive = {{"attributes", {{"POSITION", position}, {"TEXCOORD_0", uv}}}, {"indices", indices}};
    b.doc["meshes"] = json::array({json::object({{"primitives", json::array({primitive})}})});
    b.doc["nodes"] = {{{"mesh", 0}}};
    b.doc["scenes"] = {{{"nodes", {0}}}};
    return b;
}

void writeBytes(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

// A .gltf with its buffer in "<name>.bin" beside it, unless the document already says
// where its buffers are.
std::string writeGltf(const TempDir& dir, GltfBuilder b, const std::string& name = "model.gltf")
{
    if (!b.doc.contains("buffers")) {
        const std::string binName = name.substr(0, name.find('.')) + ".bin";
        writeBytes(dir.file(binName), std::string(b.bin.begin(), b.bin.end()));
        b.doc["buffers"] = {{{"uri", binName}, {"byteLength", b.bin.size()}}};
    }
    writeBytes(dir.file(name), b.doc.dump());
    return dir.file(name);
}

void appendU32(std::string& s, std::uint32_t v) { s.append(reinterpret_cast<const char*>(&v), 4); }

std::string glbBytes(GltfBuilder b)
{
    b.doc["buffers"] = {{{"byteLength", b.bin.size()}}};
    std::string text = b.doc.dump();
    text.resize((text.size() + 3) / 4 * 4, ' ');
    b.bin.resize((b.bin.size() + 3) / 4 * 4, 0);
    std::string out = "glTF";
    appendU32(out, 2);
    appendU32(out, std::uint32_t(12 + 8 + text.size() + 8 + b.bin.size()));
    appendU32(out, std::uint32_t(text.size()));
    appendU32(out, 0x4E4F534A);
    out += text;
    appendU32(out, std::uint32_t(b.bin.size()));
    appendU32(out, 0x004E4942);
    out.append(b.bin.begin(), b.bin.end());
    return out;
}

std::string writeGlb(const TempDir& dir, const GltfBuilder& b, const std::string& name = "model.glb")
{
    writeBytes(dir.file(name), glbBytes(b));
    return dir.file(name);
}

// Loads `path` expecting an Error: one line, starting with the path, containing every
// fragment. Returns the message.
std::string expectLoadError(const std::string& path, std::initializer_list<std::string> fragments,
                            const ModelLoadOptions& options = {})
{
    try {
        const ModelData m = loadGltfModel(path, options);
        ADD_FAILURE() << path << " loaded (" << m.instances.size() << " instances) but should not";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.rfind(path + ": ", 0), 0u) << "does not start with the path: " << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        for (const std::string& f : fragments) EXPECT_NE(what.find(f), std::string::npos) << "'" << f << "' not in: " << what;
        return what;
    } catch (const std::exception& e) {
        ADD_FAILURE() << "not an iblab::Error: " << e.what();
    }
    return "";
}

std::string joined(const std::vector<std::string>& lines)
{
    std::string out;
    for (const std::string& line : lines) out += line + "\n";
    return out;
}

bool anyWarningContains(const ModelData& m, std::initializer_list<std::string> fragments)
{
    return std::any_of(m.warnings.begin(), m.warnings.end(), [&](const std::string& w) {
        return std::all_of(fragments.begin(), fragments.end(), [&](const std::string& f) { return w.find(f) != std::string::npos; });
    });
}

double secondsSince(std::chrono::steady_clock::time_point start)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Adds a material whose base colour texture is the image at `uri`.
void addTexturedMaterial(GltfBuilder& b, const std::string& uri)
{
    b.doc["images"] = {{{"uri", uri}}};
    b.doc["textures"] = {{{"source", 0}}};
    b.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}, {"baseColorFactor", {0.5, 0.5, 0.5, 1.0}}}}}};
    b.primitive()["material"] = 0;
}

void writePng(const std::string& path, int w, int h, const std::vector<std::uint8_t>& rgba)
{
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out);
    ASSERT_TRUE(out->open(path, OIIO::ImageSpec(w, h, 4, OIIO::TypeDesc::UINT8)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, rgba.data()));
    ASSERT_TRUE(out->close());
}

} // namespace

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
    b = triangle();
    b.doc["accessors"][0]["byteOffset"] = 4;
    expectLoadError(writeGltf(dir, b), {"accessors[0]", "out of range"});
    // Even a count near 2^64 must not overflow the range arithmetic.
    b = triangle();
    b.doc["accessors"][2]["count"] = 18446744073709551615ull;
    expectLoadError(writeGltf(dir, b), {"indices (accessors[2])"});
}

TEST(GltfCorpus, BufferViewOutOfRangeOfItsBuffer)
{
    TempDir dir;
    GltfBuilder b = triangle();
    b.doc["bufferViews"][2]["byteLength"] = 10000;
    expectLoadError(writeGltf(dir, b), {"bufferViews[2] (bytes 60..10060) runs past the end of buffers[0] (66 bytes)"});
    b = triangle();
    b.doc["bufferViews"][0]["buffer"] = 3;
    expectLoadError(writeGltf(dir, b), {"bufferViews[0].buffer 3 does not exist"});
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
    GltfBuilder b = triangle();
    b.doc["accessors"][0]["type"] = "VEC2";
    expectLoadError(writeGltf(dir, b), {"POSITION (accessors[0]) is VEC2, expected VEC3"});
    b = triangle();
    b.doc["accessors"][0]["componentType"] = kUInt;
    expectLoadError(writeGltf(dir, b), {"POSITION (accessors[0]) has component type 5125"});
    b = triangle();
    b.doc["accessors"][2]["componentType"] = kFloat;
    expectLoadError(writeGltf(dir, b), {"indices (accessors[2]) has component type 5126"});
    b = triangle();
    b.doc["accessors"][1]["count"] = 2;
    expectLoadError(writeGltf(dir, b), {"TEXCOORD_0 (accessors[1]) has 2 elements, POSITION has 3"});
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
