#pragma once
// The mesh pass (mesh.vert + pbr.frag): every draw of the scene, shaded with the split sum
// or the fitted lobe (METHOD 0; a #define of the program tells them apart) or N importance samples
// (METHOD 1, the first N Hammersley points rotated by the frame's Cranley-Patterson offset),
// or written as the reference renderer's G-buffer (METHOD 2). Depth-tested, so it runs
// before the sky pass.
//   reads:  the scene (built for SceneSettings on first use), the camera, MaterialSettings,
//           SamplingSettings, the environment and the bake, the fitted lobe's table
//   writes: radiance and coverage 1 (shaded), or the ReferenceLayer attachments of the
//           bound G-buffer; depth
#include <glm/vec2.hpp>

#include "frame/gpu_scene.hpp"
#include "frame/lighting.hpp"

namespace iblab {

class MeshPass {
public:
    enum class Output { Shaded, GBuffer };

    explicit MeshPass(gl::ShaderLibrary& shaders);
    // Draws nothing until there is a bake. Returns whether a draw used the sampled method
    // with a sample set that rotates under accumulation (the frame can still refine).
    bool draw(SceneSlot& scene, const FrameSettings& settings, const Lighting& lighting, float aspect, glm::vec2 sampleRotation, Output output);

private:
    void ensureHammersley(int n);

    gl::ShaderLibrary& shaders_;
    gl::Buffer hammersley_ = gl::createBuffer();
    int hammersleyCount_ = 0;
    // fittedLobeTable() as an RGBA32F texture, uploaded once: it depends on no environment.
    gl::Texture lobeFit_;
    int lobeFitLayout_ = 0;
};

} // namespace iblab
