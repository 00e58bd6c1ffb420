#pragma once
// What the material pass draws: meshes on the GPU, their materials and textures, and one
// draw per instance. Built from a procedural layout (sphere, grid, counting strip) or a
// loaded glTF model; rebuilt only when the scene changes, never per frame.
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>

#include "gl/handles.hpp"
#include "frame/gpu_mesh.hpp"
#include "scene/gltf_model.hpp"
#include "scene/material.hpp"
#include "scene/sphere.hpp"
#include "frame/settings.hpp"

namespace iblab {

struct SceneDraw {
    int mesh = 0;            // into GpuScene::meshes
    glm::mat4 model{1.0f};
    PbrMaterial material;    // factors and texture slots (indices into GpuScene::textures)
    bool materialFromScene = false; // procedural grid values that the material sliders must not override
    int sampleCount = 0;     // > 0: this draw's N for the sampled method (the counting strip)
    bool forceSampled = false; // the counting strip and the sweep exist to show the sampled method
};

struct GpuScene {
    SceneKind kind = SceneKind::Sphere;
    std::string modelPath;
    std::vector<GpuMesh> meshes;
    std::vector<gl::Texture> textures; // sRGB or linear per TextureImage::srgb, mipmapped
    std::vector<SceneDraw> draws;
    Bounds bounds;
    std::vector<GridLabel> labels;     // grid axes, strip captions (N, roughness) in world space, drawn by the UI
    std::size_t gpuBytes = 0;
};

// A unit sphere, the 7x7 metallic x roughness grid, or the N = 1..k strip.
GpuScene buildProceduralScene(const SceneSettings& settings);
GpuScene buildModelScene(const ModelData& model, const std::string& path);

// The scene the frame draws: the procedural layout the settings ask for, rebuilt only when
// they ask for another kind or strip length, or the loaded model, which stays until the
// settings ask for a procedural kind.
class SceneSlot {
public:
    // The scene for these settings (the sphere while a model is asked for but none is loaded).
    const GpuScene& ensure(const SceneSettings& settings);
    void setModel(const ModelData& model, const std::string& path);
    // The scene last built or loaded, without building one (empty before the first).
    const GpuScene& current() const { return scene_; }

private:
    GpuScene scene_;
    bool built_ = false;
    SceneSettings builtFor_;
};

} // namespace iblab
