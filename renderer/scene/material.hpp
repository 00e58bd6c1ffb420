#pragma once
// Materials with glTF 2.0 metallic-roughness semantics, so that what an artist tunes is
// exactly what a glTF file can store (and what exportGltfWithMaterial() writes back).
// A default-constructed PbrMaterial is glTF's default material (what a primitive without
// a "material" gets): white, fully metallic, fully rough.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace iblab {

enum class AlphaMode { Opaque, Mask, Blend };

// "OPAQUE", "MASK", "BLEND": glTF's spelling.
std::string_view alphaModeName(AlphaMode mode);

// A texture slot: `index` into the owning model's texture list (ModelData::textures),
// or -1 for none, in which case the factor alone applies. `texCoord` picks the uv set
// (0 = MeshData::uvs, 1 = MeshData::uvs1).
struct TextureRef {
    int index = -1;
    int texCoord = 0;
    bool valid() const { return index >= 0; }
};

struct PbrMaterial {
    std::string name;

    // Linear RGBA multiplier of the base colour texture (sRGB-decoded before multiplying).
    glm::vec4 baseColorFactor{1.0f};
    float metallicFactor = 1.0f;   // multiplies the metallicRoughness texture's B channel
    float roughnessFactor = 1.0f;  // perceptual roughness; multiplies its G channel
    // Linear RGB emitted radiance multiplier. May exceed 1: glTF stores such values as a
    // factor <= 1 times KHR_materials_emissive_strength, which the loader folds in here
    // and the exporter splits out again.
    glm::vec3 emissiveFactor{0.0f};
    float occlusionStrength = 1.0f; // 0 = ignore the occlusion texture, 1 = full effect
    float normalScale = 1.0f;       // scales the normal map's X and Y
    AlphaMode alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f;       // used by AlphaMode::Mask only
    bool doubleSided = false;

    TextureRef baseColorTexture;         // sRGB RGBA
    TextureRef metallicRoughnessTexture; // linear: G = roughness, B = metallic (R unused)
    TextureRef normalTexture;            // linear tangent-space normal, see mesh.hpp
    TextureRef occlusionTexture;         // linear: R = ambient occlusion
    TextureRef emissiveTexture;          // sRGB RGB
};

// A decoded texture, ready to upload: width x height RGBA8 texels, row 0 at the top of
// the image (which uv v = 0 addresses). `srgb` says how the renderer must sample it:
// true for base colour and emissive, false for data (metallic-roughness, normal,
// occlusion). An image a model uses both ways appears twice, once per interpretation.
struct TextureImage {
    std::string name; // where it came from (file name, image name or "images[3]"), for UI and messages
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba8;
    bool srgb = false;
};

} // namespace iblab
