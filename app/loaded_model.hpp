#pragma once
// The glTF model of SceneKind::Model: loading it into the renderer (a failed load, or a model
// with nothing to draw, keeps the model shown), its status line, and writing a copy whose
// materials carry the material panel's factors. The caller puts a loaded model's path in its
// settings.
#include <string>
#include <vector>

#include "frame/renderer.hpp"
#include "scene/material.hpp"
#include "status_report.hpp"

namespace iblab::app {

class LoadedModel {
public:
    explicit LoadedModel(Renderer& renderer) : renderer_(renderer) {}

    // Loads a .gltf/.glb into the renderer. On failure, or when its scene has no triangles,
    // the current model stays; when the scene shows it (modelShown), the report names it.
    StatusReport load(const std::string& path, bool modelShown);
    // The loaded model's status line ("material_spheres.glb: 3 primitives, ..."), or "".
    const std::string& line() const { return line_; }
    // What its loader skipped or could not find (a missing texture, a primitive with
    // non-finite positions), also in line(): `render` prints them, which shows no status line.
    const std::vector<std::string>& warnings() const { return warnings_; }

    // Writes a copy of the glTF at settings.scene.modelPath whose materials carry the material
    // panel's factors.
    StatusReport exportWithPanelMaterial(const std::string& outPath, const FrameSettings& settings) const;

private:
    Renderer& renderer_;
    std::vector<PbrMaterial> materials_; // of the loaded model, for export
    std::string line_;                   // its status line, kept under a failed load's error
    std::vector<std::string> warnings_;  // its loader's
};

} // namespace iblab::app
