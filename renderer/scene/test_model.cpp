#include "scene/test_model.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

#include "io/atomic_file.hpp"
#include "scene/internal/glb_container.hpp"
#include "scene/internal/gltf_document.hpp"
#include "scene/internal/image_codec.hpp"
#include "scene/sphere.hpp"

namespace iblab {
namespace {

namespace sd = scene_detail;
using nlohmann::json;

constexpr int kSize = 64;
constexpr int kTilesU = 8, kTilesV = 4;
constexpr int kTileW = kSize / kTilesU, kTileH = kSize / kTilesV;

std::uint8_t toByte(double v) { return std::uint8_t(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); }

// Fills a kSize x kSize RGBA8 image from a function of the texel's tile (column, row)
// and its position inside the tile, (s, t) in [0, 1]^2 at texel centres.
TextureImage makeTexture(const char* name, bool srgb,
                         const std::function<glm::dvec4(int column, int row, double s, double t)>& texel)
{
    TextureImage image;
    image.name = name;
    image.width = image.height = kSize;
    image.srgb = srgb;
    image.rgba8.resize(std::size_t(kSize) * kSize * 4);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const glm::dvec4 v = texel(x / kTileW, y / kTileH, (x % kTileW + 0.5) / kTileW, (y % kTileH + 0.5) / kTileH);
            for (int c = 0; c < 4; ++c) image.rgba8[(std::size_t(y) * kSize + std::size_t(x)) * 4 + std::size_t(c)] = toByte(v[c]);
        }
    return image;
}

// Distance from the tile border, 0 at the edge and 1 at the centre.
double interior(double s, double t) { return std::min({s, 1.0 - s, t, 1.0 - t}) * 2.0; }

glm::dvec3 hue(double h)
{
    const glm::dvec3 k = glm::mod(glm::dvec3(0.0, 2.0 / 3.0, 1.0 / 3.0) + h, 1.0);
    return glm::clamp(glm::abs(k * 6.0 - 3.0) - 1.0, 0.0, 1.0);
}

int addAccessor(json& root, int view, int componentType, std::size_t count, const char* type)
{
    json& accessors = root["accessors"];
    accessors.push_back({{"bufferView", view}, {"componentType", componentType}, {"count", count}, {"type", type}});
    return int(accessors.size() - 1);
}

template <class T>
int addVertexData(json& root, std::vector<std::uint8_t>& bin, const std::vector<T>& data, const char* type)
{
    const int view = sd::appendBufferView(root, bin, reinterpret_cast<const std::uint8_t*>(data.data()), data.size() * sizeof(T),
                                          34962 /* ARRAY_BUFFER */);
    return addAccessor(root, view, 5126 /* FLOAT */, data.size(), type);
}

} // namespace

std::vector<TextureImage> materialSpheresTextures()
{
    std::vector<TextureImage> textures;
    textures.push_back(makeTexture("baseColor", true, [](int column, int row, double s, double t) {
        const glm::dvec3 colour = hue(column / double(kTilesU)) * (row % 2 ? 0.55 : 0.9) + 0.08;
        return glm::dvec4(colour * (interior(s, t) < 0.15 ? 0.25 : 1.0), 1.0);
    }));
    textures.push_back(makeTexture("metallicRoughness", false, [](int column, int row, double, double) {
        return glm::dvec4(0.0, (column + 0.5) / kTilesU, row % 2 ? 1.0 : 0.0, 1.0);
    }));
    textures.push_back(makeTexture("normal", false, [](int, int, double s, double t) {
        // Height h = cos^2 of the distance from the tile centre (a dome), sampled per
        // texel; x grows with u (tangent), image y grows down, so up (bitangent) is -t.
        const double dx = s - 0.5, dy = t - 0.5, r = std::sqrt(dx * dx + dy * dy) * 2.0;
        double dhdr = r < 1.0 ? -std::numbers::pi * std::cos(r * std::numbers::pi / 2.0) * std::sin(r * std::numbers::pi / 2.0) : 0.0;
        dhdr *= 0.6; // bump strength
        const double gx = r > 0.0 ? dhdr * dx * 2.0 / r : 0.0, gy = r > 0.0 ? dhdr * dy * 2.0 / r : 0.0;
        const glm::dvec3 n = glm::normalize(glm::dvec3(-gx, gy, 1.0));
        return glm::dvec4(n * 0.5 + 0.5, 1.0);
    }));
    textures.push_back(makeTexture("occlusion", false, [](int, int, double s, double t) {
        const double ao = 0.35 + 0.65 * std::min(1.0, interior(s, t) * 3.0);
        return glm::dvec4(ao, ao, ao, 1.0);
    }));
    textures.push_back(makeTexture("emissive", true, [](int, int row, double, double t) {
        const bool lit = int(t * kTileH) / 4 % 2 == 0;
        return lit ? glm::dvec4(1.0, 0.78, 0.47, 1.0) * (row % 2 ? 0.6 : 1.0) + glm::dvec4(0, 0, 0, 1) : glm::dvec4(0, 0, 0, 1);
    }));
    return textures;
}

void writeMaterialSpheresGlb(const std::string& path)
{
    const MeshData sphere = makeUvSphere(1.0f, 64, 32);
    json root = {{"asset", {{"version", "2.0"}, {"generator", "iblab writeMaterialSpheresGlb (renderer/scene/test_model.cpp)"}}},
                 {"scene", 0}};
    std::vector<std::uint8_t> bin;

    const Bounds bounds = computeBounds(sphere);
    const int position = addVertexData(root, bin, sphere.positions, "VEC3");
    root["accessors"][std::size_t(position)]["min"] = {bounds.min.x, bounds.min.y, bounds.min.z}; // required by the spec
    root["accessors"][std::size_t(position)]["max"] = {bounds.max.x, bounds.max.y, bounds.max.z};
    const int normal = addVertexData(root, bin, sphere.normals, "VEC3");
    const int tangent = addVertexData(root, bin, sphere.tangents, "VEC4");
    const int uv = addVertexData(root, bin, sphere.uvs, "VEC2");
    // 16-bit indices: smaller, and the loader's USHORT path gets exercised.
    const std::vector<std::uint16_t> indices(sphere.indices.begin(), sphere.indices.end());
    const int indexView = sd::appendBufferView(root, bin, reinterpret_cast<const std::uint8_t*>(indices.data()),
                                               indices.size() * sizeof(std::uint16_t), 34963 /* ELEMENT_ARRAY_BUFFER */);
    const int index = addAccessor(root, indexView, 5123 /* UNSIGNED_SHORT */, indices.size(), "SCALAR");

    root["samplers"] = {{{"magFilter", 9729}, {"minFilter", 9987}, {"wrapS", 10497}, {"wrapT", 10497}}};
    for (const TextureImage& texture : materialSpheresTextures()) {
        const std::vector<std::uint8_t> png = sd::encodePng(texture.width, texture.height, texture.rgba8);
        const int view = sd::appendBufferView(root, bin, png.data(), png.size());
        root["images"].push_back({{"name", texture.name}, {"bufferView", view}, {"mimeType", "image/png"}});
        root["textures"].push_back({{"sampler", 0}, {"source", root["images"].size() - 1}});
    }

    root["materials"] = {
        {{"name", "textured"},
         {"pbrMetallicRoughness",
          {{"baseColorTexture", {{"index", 0}}}, {"metallicRoughnessTexture", {{"index", 1}}}, {"metallicFactor", 1.0}, {"roughnessFactor", 1.0}}},
         {"normalTexture", {{"index", 2}, {"scale", 1.0}}},
         {"occlusionTexture", {{"index", 3}, {"strength", 1.0}}}},
        {{"name", "gold"},
         {"pbrMetallicRoughness", {{"baseColorFactor", {1.0, 0.766, 0.336, 1.0}}, {"metallicFactor", 1.0}, {"roughnessFactor", 0.3}}}},
        {{"name", "emissive"},
         {"pbrMetallicRoughness", {{"baseColorFactor", {0.05, 0.05, 0.05, 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.6}}},
         {"emissiveTexture", {{"index", 4}}},
         {"emissiveFactor", {1.0, 0.5, 0.1}}},
    };
    const json attributes = {{"POSITION", position}, {"NORMAL", normal}, {"TANGENT", tangent}, {"TEXCOORD_0", uv}};
    const char* names[] = {"textured", "gold", "emissive"};
    for (int i = 0; i < 3; ++i) {
        root["meshes"].push_back({{"name", std::string("sphere_") + names[i]},
                                  {"primitives", {{{"attributes", attributes}, {"indices", index}, {"material", i}, {"mode", 4}}}}});
        root["nodes"].push_back({{"name", names[i]}, {"mesh", i}, {"translation", {2.5 * (i - 1), 0.0, 0.0}}});
    }
    root["scenes"] = {{{"name", "material spheres"}, {"nodes", {0, 1, 2}}}};
    sd::setSingleBuffer(root, bin, false);
    writeTextFileAtomic(path, sd::serializeGlb(root, bin));
}

} // namespace iblab
