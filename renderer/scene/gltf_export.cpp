// Export works on the JSON document itself rather than on tinygltf structs: only the
// edited material members change, and whatever iblab does not model (extensions,
// extras, animations, skins, cameras, unknown members) passes through untouched.
#include <algorithm>
#include <cmath>
#include <optional>

#include "io/atomic_file.hpp"
#include "io/error.hpp"
#include "scene/gltf_model.hpp"
#include "scene/internal/glb_container.hpp"
#include "scene/internal/gltf_document.hpp"

namespace iblab {
namespace {

namespace sd = scene_detail;
using nlohmann::json;

// JSON has no NaN or infinity (nlohmann would write null, making the file invalid).
double finiteOr(float v, double fallback) { return std::isfinite(v) ? double(v) : fallback; }
double unit(float v, double fallback) { return std::clamp(finiteOr(v, fallback), 0.0, 1.0); }

json& objectMember(json& parent, const char* key)
{
    json& member = parent[key];
    if (!member.is_object())
        member = json::object();
    return member;
}

void addExtensionUsed(json& root, const char* name)
{
    json& used = root["extensionsUsed"];
    if (!used.is_array())
        used = json::array();
    if (std::find(used.begin(), used.end(), name) == used.end())
        used.push_back(name);
}

void applyMaterial(json& root, json& m, const PbrMaterial& p)
{
    if (!m.is_object())
        m = json::object();
    json& pbr = objectMember(m, "pbrMetallicRoughness");
    pbr["baseColorFactor"] = {unit(p.baseColorFactor.r, 1.0), unit(p.baseColorFactor.g, 1.0), unit(p.baseColorFactor.b, 1.0),
                              unit(p.baseColorFactor.a, 1.0)};
    pbr["metallicFactor"] = unit(p.metallicFactor, 1.0);
    pbr["roughnessFactor"] = unit(p.roughnessFactor, 1.0);

    // emissiveFactor is limited to [0, 1]; brighter emission is factor x strength.
    const glm::dvec3 emissive(std::max(finiteOr(p.emissiveFactor.r, 0.0), 0.0), std::max(finiteOr(p.emissiveFactor.g, 0.0), 0.0),
                              std::max(finiteOr(p.emissiveFactor.b, 0.0), 0.0));
    const double peak = std::max({emissive.r, emissive.g, emissive.b});
    if (peak > 1.0) {
        m["emissiveFactor"] = {emissive.r / peak, emissive.g / peak, emissive.b / peak};
        objectMember(objectMember(m, "extensions"), "KHR_materials_emissive_strength")["emissiveStrength"] = peak;
        addExtensionUsed(root, "KHR_materials_emissive_strength");
    } else {
        m["emissiveFactor"] = {emissive.r, emissive.g, emissive.b};
        if (m.contains("extensions") && m["extensions"].is_object()) {
            m["extensions"].erase("KHR_materials_emissive_strength");
            if (m["extensions"].empty())
                m.erase("extensions");
        }
    }
    // Strength and scale belong to their texture slots; without the texture there is
    // nowhere to store them (and they would have no effect).
    if (m.contains("occlusionTexture") && m["occlusionTexture"].is_object())
        m["occlusionTexture"]["strength"] = unit(p.occlusionStrength, 1.0);
    if (m.contains("normalTexture") && m["normalTexture"].is_object())
        m["normalTexture"]["scale"] = finiteOr(p.normalScale, 1.0);
    m["alphaMode"] = std::string(alphaModeName(p.alphaMode));
    if (p.alphaMode == AlphaMode::Mask)
        m["alphaCutoff"] = std::max(finiteOr(p.alphaCutoff, 0.5), 0.0);
    m["doubleSided"] = p.doubleSided;
}

// A new material for every primitive that has none (they render with the default
// material); returns its index.
std::size_t addMaterialForUnassigned(json& root, json& materials)
{
    materials.push_back(json::object({{"name", "iblab"}}));
    const std::size_t index = materials.size() - 1;
    if (root.contains("meshes") && root["meshes"].is_array())
        for (json& mesh : root["meshes"])
            if (mesh.is_object() && mesh.contains("primitives") && mesh["primitives"].is_array())
                for (json& primitive : mesh["primitives"])
                    if (primitive.is_object() && !primitive.contains("material"))
                        primitive["material"] = index;
    return index;
}

// Moves every image with a URI (external file or data URI) into the buffer, so that
// the copy depends on nothing next to it.
void embedImages(sd::GltfDocument& doc, std::vector<std::string>& warnings)
{
    if (!doc.json.contains("images") || !doc.json["images"].is_array())
        return;
    json& images = doc.json["images"];
    for (std::size_t i = 0; i < images.size() && i < doc.images.size(); ++i) {
        json& image = images[i];
        const sd::ImageSource& source = doc.images[i];
        if (!image.contains("uri"))
            continue;
        std::string mime = source.mimeType;
        if (mime != "image/png" && mime != "image/jpeg")
            mime = sd::sniffImageMimeType(source.encoded);
        if (source.encoded.empty() || mime.empty()) {
            warnings.push_back("texture image " + source.label +
                               (source.encoded.empty() ? " " + source.problem : " is of an unknown type") +
                               "; the copy keeps its URI and is not self-contained");
            continue;
        }
        image["bufferView"] = sd::appendBufferView(doc.json, doc.bin, source.encoded.data(), source.encoded.size());
        image["mimeType"] = mime;
        image.erase("uri");
    }
}

} // namespace

std::vector<std::string> exportGltfWithMaterials(const std::string& sourcePath, const std::string& outPath,
                                                 const std::vector<MaterialEdit>& edits, const ModelLoadOptions& options)
{
    const std::string ext = sd::lowerExtension(outPath);
    if (ext != ".glb" && ext != ".gltf")
        throw Error(outPath, "exports are written as .glb or .gltf, not '" + ext + "'");
    std::vector<std::string> warnings;
    const std::string bytes = rethrowAsError(sourcePath, "exporting", "cannot be exported", [&] {
        sd::GltfDocument doc = sd::readGltfDocument(sourcePath, {options.maxInputBytes, options.maxJsonDepth});
        const bool hadMaterials = doc.json.contains("materials");
        json& materials = doc.json["materials"];
        if (!hadMaterials)
            materials = json::array();
        if (!materials.is_array())
            throw Error(sourcePath, "\"materials\" is not an array");
        const std::size_t fileMaterials = materials.size();
        std::optional<std::size_t> added;
        for (const MaterialEdit& edit : edits) {
            if (edit.materialIndex < -1 || edit.materialIndex >= int(fileMaterials))
                throw Error(sourcePath, "materials[" + std::to_string(edit.materialIndex) + "] does not exist (the model has " +
                                            std::to_string(fileMaterials) + " materials; -1 adds one)");
            if (edit.materialIndex == -1 && !added)
                added = addMaterialForUnassigned(doc.json, materials);
            applyMaterial(doc.json, materials[edit.materialIndex == -1 ? *added : std::size_t(edit.materialIndex)],
                          edit.material);
        }
        if (!hadMaterials && materials.empty())
            doc.json.erase("materials");
        embedImages(doc, warnings);
        sd::setSingleBuffer(doc.json, doc.bin, ext == ".gltf");
        return ext == ".glb" ? sd::serializeGlb(doc.json, doc.bin) : doc.json.dump(2, ' ', false, json::error_handler_t::replace) + "\n";
    });
    writeTextFileAtomic(outPath, bytes);
    return warnings;
}

std::vector<std::string> exportGltfWithMaterial(const std::string& sourcePath, const std::string& outPath,
                                                int materialIndex, const PbrMaterial& tuned)
{
    return exportGltfWithMaterials(sourcePath, outPath, {MaterialEdit{materialIndex, tuned}});
}

} // namespace iblab
