// glTF materials and textures -> PbrMaterial and decoded TextureImage, with warnings
// rather than errors for everything that leaves the model viewable.
#include "scene/internal/gltf_materials.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>

#include "scene/internal/image_codec.hpp"

namespace iblab::scene_detail {
namespace {

float clamp01(double v, float fallback) { return std::isfinite(v) ? float(std::clamp(v, 0.0, 1.0)) : fallback; }

class MaterialConverter {
public:
    MaterialConverter(const ModelLoadOptions& options, const tinygltf::Model& gltf, const std::vector<ImageSource>& images,
                      ModelData& out)
        : options_(options), gltf_(gltf), images_(images), out_(out)
    {
    }

    PbrMaterial convertMaterial(std::size_t index)
    {
        const tinygltf::Material& m = gltf_.materials[index];
        const std::string what = indexed("materials", index);
        const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
        PbrMaterial p;
        p.name = m.name.empty() ? what : m.name;
        if (pbr.baseColorFactor.size() == 4)
            for (int c = 0; c < 4; ++c) p.baseColorFactor[c] = clamp01(pbr.baseColorFactor[std::size_t(c)], 1.0f);
        p.metallicFactor = clamp01(pbr.metallicFactor, 1.0f);
        p.roughnessFactor = clamp01(pbr.roughnessFactor, 1.0f);
        if (m.emissiveFactor.size() == 3)
            for (int c = 0; c < 3; ++c) p.emissiveFactor[c] = clamp01(m.emissiveFactor[std::size_t(c)], 0.0f);
        if (const auto ext = m.extensions.find("KHR_materials_emissive_strength"); ext != m.extensions.end()) {
            const tinygltf::Value& strength = ext->second.Get("emissiveStrength");
            const double s = strength.IsNumber() ? strength.GetNumberAsDouble() : 1.0;
            if (std::isfinite(s) && s >= 0.0)
                p.emissiveFactor *= float(s);
        }
        p.occlusionStrength = clamp01(m.occlusionTexture.strength, 1.0f);
        p.normalScale = std::isfinite(m.normalTexture.scale) ? float(m.normalTexture.scale) : 1.0f;
        if (m.alphaMode == "MASK")
            p.alphaMode = AlphaMode::Mask;
        else if (m.alphaMode == "BLEND")
            p.alphaMode = AlphaMode::Blend;
        else if (m.alphaMode != "OPAQUE")
            warn(what + ".alphaMode '" + m.alphaMode + "' is not OPAQUE, MASK or BLEND; OPAQUE used");
        p.alphaCutoff = std::isfinite(m.alphaCutoff) && m.alphaCutoff >= 0.0 ? float(m.alphaCutoff) : 0.5f;
        p.doubleSided = m.doubleSided;

        p.baseColorTexture = textureRef(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, true,
                                        what + ".baseColorTexture");
        p.metallicRoughnessTexture = textureRef(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                                                false, what + ".metallicRoughnessTexture");
        p.normalTexture = textureRef(m.normalTexture.index, m.normalTexture.texCoord, false, what + ".normalTexture");
        p.occlusionTexture = textureRef(m.occlusionTexture.index, m.occlusionTexture.texCoord, false,
                                        what + ".occlusionTexture");
        p.emissiveTexture = textureRef(m.emissiveTexture.index, m.emissiveTexture.texCoord, true, what + ".emissiveTexture");
        return p;
    }

private:
    void warn(const std::string& text) { out_.warnings.push_back(text); }

    // The ModelData texture for image `source` read as sRGB or linear, decoded on first
    // use; -1 (with one warning per image) when it cannot be had.
    int decodedTexture(std::size_t source, bool srgb)
    {
        const auto key = std::make_pair(source, srgb);
        if (const auto it = textureSlots_.find(key); it != textureSlots_.end())
            return it->second;
        int& slot = textureSlots_[key];
        slot = -1;
        const ImageSource& image = images_[source];
        if (failedImages_.count(source))
            return slot;
        const auto fallBack = [&](const std::string& problem) {
            warn("texture image " + image.label + " " + problem + "; textures using it fall back to their factors");
            failedImages_.insert(source);
            return slot;
        };
        if (image.encoded.empty())
            return fallBack(image.problem);

        std::optional<TextureImage> decoded;
        if (const auto other = textureSlots_.find(std::make_pair(source, !srgb));
            other != textureSlots_.end() && other->second >= 0) {
            decoded = out_.textures[std::size_t(other->second)]; // same pixels, other interpretation
        } else {
            std::string problem, note;
            decoded = decodeImage(image.encoded, options_.maxTextureDimension, problem, note);
            if (!decoded)
                return fallBack(problem);
            if (!note.empty())
                warn("texture image " + image.label + " " + note);
        }
        const std::uint64_t bytes = decoded->rgba8.size();
        if (bytes > options_.maxTextureBytes - std::min(textureBytesUsed_, options_.maxTextureBytes))
            return fallBack("would exceed the " + std::to_string(options_.maxTextureBytes) +
                            "-byte texture budget (ModelLoadOptions::maxTextureBytes); dropped");
        textureBytesUsed_ += bytes;
        decoded->name = image.name;
        decoded->srgb = srgb;
        out_.textures.push_back(std::move(*decoded));
        slot = int(out_.textures.size() - 1);
        return slot;
    }

    TextureRef textureRef(int textureIndex, int texCoord, bool srgb, const std::string& what)
    {
        if (textureIndex < 0)
            return {};
        if (std::size_t(textureIndex) >= gltf_.textures.size()) {
            warn(what + " refers to textures[" + std::to_string(textureIndex) + "], which does not exist; ignored");
            return {};
        }
        const int source = gltf_.textures[std::size_t(textureIndex)].source;
        if (source < 0 || std::size_t(source) >= images_.size()) {
            warn(what + ": textures[" + std::to_string(textureIndex) + "] has no image iblab can read; ignored");
            return {};
        }
        if (texCoord != 0 && texCoord != 1) {
            warn(what + " uses TEXCOORD_" + std::to_string(texCoord) + "; iblab reads sets 0 and 1, using 0");
            texCoord = 0;
        }
        TextureRef ref;
        ref.index = decodedTexture(std::size_t(source), srgb);
        ref.texCoord = texCoord;
        return ref;
    }

    const ModelLoadOptions& options_;
    const tinygltf::Model& gltf_;
    const std::vector<ImageSource>& images_;
    ModelData& out_;
    std::map<std::pair<std::size_t, bool>, int> textureSlots_;
    std::set<std::size_t> failedImages_;
    std::uint64_t textureBytesUsed_ = 0;
};

} // namespace

void convertMaterials(const ModelLoadOptions& options, const tinygltf::Model& gltf, const std::vector<ImageSource>& images,
                      ModelData& out)
{
    MaterialConverter converter(options, gltf, images, out);
    for (std::size_t i = 0; i < gltf.materials.size(); ++i) out.materials.push_back(converter.convertMaterial(i));
}

} // namespace iblab::scene_detail
