#include "frame/gpu_scene.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "gl/texture_upload.hpp"
#include "scene/sphere.hpp"

namespace iblab {
namespace {

// Enough segments that the silhouette of a sphere filling the window stays round (64 x 32,
// 4k triangles); scenes of many small spheres use 32 x 16, because llvmpipe's triangle
// setup, not shading, dominates a frame of 49 spheres at full tessellation.
MeshData unitSphere(SceneKind kind)
{
    return kind == SceneKind::Sphere ? makeUvSphere(1.0f, 64, 32) : makeUvSphere(1.0f, 32, 16);
}

// Between the centres of the strips' neighbouring unit spheres: a gap of half a diameter.
constexpr float kStripSpacing = 2.5f;

Bounds sphereBounds(const glm::mat4& model)
{
    Bounds b;
    const glm::vec3 centre(model[3]);
    b.extend(centre - glm::vec3(1.0f));
    b.extend(centre + glm::vec3(1.0f));
    return b;
}

gl::Texture uploadTexture(const TextureImage& image)
{
    // TextureImage row 0 is the top of the picture, which glTF's v = 0 addresses: uploading
    // it as GL's row 0 (t = 0) makes uv map to texels with no flip.
    return gl::createMipmappedTexture2D({image.srgb ? GLenum(GL_SRGB8_ALPHA8) : GLenum(GL_RGBA8), image.width, image.height, GL_RGBA,
                                         GL_UNSIGNED_BYTE, image.rgba8.data(), 1, GL_REPEAT, GL_REPEAT});
}

} // namespace

GpuScene buildProceduralScene(const SceneSettings& settings)
{
    GpuScene scene;
    scene.kind = settings.kind;
    scene.meshes.emplace_back(unitSphere(settings.kind));
    auto add = [&](const glm::mat4& model, SceneDraw draw) {
        draw.mesh = 0;
        draw.model = model;
        scene.bounds.extend(sphereBounds(model));
        scene.draws.push_back(draw);
    };
    switch (settings.kind) {
    case SceneKind::Grid: {
        const SphereGrid grid = sphereGrid(7, 7, 2.5f);
        for (const GridSphere& sphere : grid.spheres) {
            SceneDraw draw;
            draw.material.metallicFactor = sphere.metallic;
            draw.material.roughnessFactor = sphere.roughness;
            draw.materialFromScene = true;
            add(sphere.transform, draw);
        }
        scene.labels = grid.labels;
        // The row axis's title sits left of the tick values and is as wide as two sphere
        // diameters: one more unit to the left keeps the two from overlapping.
        for (GridLabel& label : scene.labels)
            if (label.axisTitle && label.position.x < grid.spheres.front().transform[3].x) label.position.x -= 1.0f;
        break;
    }
    case SceneKind::Counting: {
        const int k = std::clamp(settings.countingSpheres, 1, 64);
        const std::vector<glm::mat4> strip = countingStrip(k, kStripSpacing);
        std::vector<std::string> texts;
        for (int i = 0; i < k; ++i) {
            SceneDraw draw;
            draw.sampleCount = i + 1; // sphere i shows i reflections of a single light
            draw.forceSampled = true;
            add(strip[std::size_t(i)], draw);
            texts.push_back("N = " + std::to_string(draw.sampleCount));
        }
        scene.labels = stripLabels(texts, kStripSpacing);
        break;
    }
    case SceneKind::Sweep: {
        const int k = std::clamp(settings.countingSpheres, 2, 64);
        const std::vector<glm::mat4> strip = countingStrip(k, kStripSpacing);
        std::vector<std::string> texts;
        for (int i = 0; i < k; ++i) {
            SceneDraw draw;
            draw.material.metallicFactor = 1.0f;
            draw.material.roughnessFactor = float(i) / float(k - 1);
            draw.materialFromScene = true;
            draw.forceSampled = true;
            add(strip[std::size_t(i)], draw);
            texts.push_back("r = " + tickText(draw.material.roughnessFactor));
        }
        scene.labels = stripLabels(texts, kStripSpacing);
        break;
    }
    case SceneKind::None:
        scene.bounds.extend(glm::vec3(-1.0f));
        scene.bounds.extend(glm::vec3(1.0f));
        break;
    case SceneKind::Sphere:
    case SceneKind::Model: // no model loaded yet: show the sphere
        add(glm::mat4(1.0f), SceneDraw{});
        break;
    }
    // Frame the labels too.
    for (const GridLabel& label : scene.labels) {
        const float halfWidth = label.axisTitle ? 2.0f : 0.6f;
        scene.bounds.extend(label.position - glm::vec3(halfWidth, 0.4f, 0.0f));
        scene.bounds.extend(label.position + glm::vec3(halfWidth, 0.4f, 0.0f));
    }
    for (const GpuMesh& mesh : scene.meshes) scene.gpuBytes += mesh.byteSize();
    return scene;
}

GpuScene buildModelScene(const ModelData& model, const std::string& path)
{
    GpuScene scene;
    scene.kind = SceneKind::Model;
    scene.modelPath = path;
    for (const TextureImage& image : model.textures) {
        scene.textures.push_back(uploadTexture(image));
        scene.gpuBytes += image.rgba8.size() * 4 / 3; // with the mip chain
    }
    for (const MeshInstance& instance : model.instances) {
        scene.meshes.emplace_back(instance.mesh);
        scene.gpuBytes += scene.meshes.back().byteSize();
        SceneDraw draw;
        draw.mesh = int(scene.meshes.size()) - 1;
        draw.model = glm::mat4(1.0f); // instance meshes are already in world space
        draw.material = model.material(instance.materialIndex);
        scene.draws.push_back(draw);
    }
    scene.bounds = model.bounds;
    return scene;
}

const GpuScene& SceneSlot::ensure(const SceneSettings& settings)
{
    const bool wantsProcedural = settings.kind != SceneKind::Model;
    const bool stale = !built_ || scene_.kind != settings.kind || builtFor_.countingSpheres != settings.countingSpheres;
    if ((wantsProcedural && stale) || !built_) {
        scene_ = buildProceduralScene(settings);
        built_ = true;
        builtFor_ = settings;
    }
    return scene_;
}

void SceneSlot::setModel(const ModelData& model, const std::string& path)
{
    scene_ = buildModelScene(model, path);
    built_ = true;
    builtFor_.kind = SceneKind::Model;
}

} // namespace iblab
