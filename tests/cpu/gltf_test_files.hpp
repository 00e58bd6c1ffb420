#pragma once
// The glTF robustness tests' material: a one-triangle model to mutate, built with
// nlohmann_json and written as .gltf (+ .bin) or .glb by a hand-rolled writer, independent
// of the code under test; and the expectations every broken file is held to (an
// iblab::Error of one line that starts with the file's path) or that a usable one meets
// (warnings that name the problem).
#include <chrono>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/gltf_model.hpp"
#include "temp_dir.hpp"

namespace iblab::testing {

inline constexpr int kUByte = 5121, kUShort = 5123, kUInt = 5125, kFloat = 5126;

struct GltfBuilder {
    nlohmann::json doc = {{"asset", {{"version", "2.0"}}}, {"scene", 0}};
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
    int accessor(int view, int componentType, std::size_t count, const char* type, bool normalized = false);
    nlohmann::json& primitive() { return doc["meshes"][0]["primitives"][0]; }
};

// One triangle in the z = 0 plane facing +Z: accessors 0 POSITION, 1 TEXCOORD_0,
// 2 indices (unsigned short), one node, one scene, no material.
GltfBuilder triangle();

void writeBytes(const std::string& path, const std::string& bytes);

// A .gltf with its buffer in "<name>.bin" beside it, unless the document already says
// where its buffers are.
std::string writeGltf(const TempDir& dir, GltfBuilder b, const std::string& name = "model.gltf");

// The model as a .glb: its bin becomes the BIN chunk.
std::string glbBytes(GltfBuilder b);
std::string writeGlb(const TempDir& dir, const GltfBuilder& b, const std::string& name = "model.glb");

// Loads `path` expecting an Error: one line, starting with the path, containing every
// fragment. Returns the message.
std::string expectLoadError(const std::string& path, std::initializer_list<std::string> fragments,
                            const ModelLoadOptions& options = {});

// The triangle with the member at `pointer` (a JSON pointer, "/accessors/0/count") set to
// `value`, written as model.gltf, must fail to load as expectLoadError says.
void expectTriangleWithFails(const TempDir& dir, const std::string& pointer, const nlohmann::json& value,
                             std::initializer_list<std::string> fragments);

// True when one warning contains every fragment.
bool anyWarningContains(const ModelData& m, std::initializer_list<std::string> fragments);

// The warnings one a line, for failure messages.
std::string joined(const std::vector<std::string>& lines);

double secondsSince(std::chrono::steady_clock::time_point start);

// Adds a material whose base colour texture is the image at `uri`.
void addTexturedMaterial(GltfBuilder& b, const std::string& uri);

// An RGBA8 PNG written with OpenImageIO.
void writePng(const std::string& path, int w, int h, const std::vector<std::uint8_t>& rgba);

} // namespace iblab::testing
