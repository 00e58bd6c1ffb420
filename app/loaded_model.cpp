#include "loaded_model.hpp"

#include "io/error.hpp"
#include "scene/gltf_model.hpp"

namespace iblab::app {

StatusReport LoadedModel::load(const std::string& path, bool modelShown)
{
    try {
        const ModelData model = loadDrawableGltfModel(path);
        renderer_.setModel(model, path);
        materials_ = model.materials;
        warnings_ = model.warnings;
        std::string text = displayName(path) + ": " + std::to_string(model.instances.size()) + " primitives, " +
                           std::to_string(model.materials.size()) + " materials, " + std::to_string(model.textures.size()) + " textures";
        for (const auto& warning : model.warnings) text += "; " + warning;
        line_ = text;
        return {text, false};
    } catch (const Error& e) {
        // The model on screen stays (a model with nothing to draw is refused too): say which,
        // as a failed environment load does (the error replaced its line, and with it the
        // only sign of what was still shown).
        StatusReport status{e.what(), true};
        if (modelShown && !line_.empty()) status.notes.push_back("still showing " + line_);
        return status;
    }
}

StatusReport LoadedModel::exportWithPanelMaterial(const std::string& outPath, const FrameSettings& settings) const
{
    if (settings.scene.kind != SceneKind::Model || settings.scene.modelPath.empty()) return {"export: no glTF model is loaded", true};
    const MaterialSettings& m = settings.material;
    auto tuned = [&](PbrMaterial material) {
        material.baseColorFactor = glm::vec4(m.baseColor, material.baseColorFactor.a);
        material.metallicFactor = m.metallic;
        material.roughnessFactor = m.roughness;
        return material;
    };
    std::vector<MaterialEdit> edits;
    for (std::size_t i = 0; i < materials_.size(); ++i) edits.push_back({int(i), tuned(materials_[i])});
    if (edits.empty()) edits.push_back({-1, tuned(PbrMaterial{})}); // primitives without a material get one
    try {
        const std::vector<std::string> warnings = exportGltfWithMaterials(settings.scene.modelPath, outPath, edits);
        std::string text = "exported " + outPath + " (" + std::to_string(edits.size()) + " materials)";
        for (const auto& warning : warnings) text += "; " + warning;
        return {text, false};
    } catch (const Error& e) {
        return {e.what(), true};
    }
}

} // namespace iblab::app
