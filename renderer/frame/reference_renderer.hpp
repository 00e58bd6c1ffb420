#pragma once
// The reference renderer: the frame of given settings at a given size with the full
// integral over the (downsampled) environment's texels, no split sum and no N = V = R.
//   start:   the mesh pass writes the G-buffer (ReferenceLayer: N, V, F0, base colour,
//            emissive); its coverage picks the tiles ReferenceIntegral sums over
//   advance: ReferenceIntegral slices (reference_integral.comp: one tile x one band of
//            environment rows each) add into RGBA32F specular and irradiance sums
//   resolve: the sky pass, then reference_resolve.frag combines G-buffer and sums into the
//            RGBA32F reference frame; also while it runs, whenever tiles have finished, so
//            that ShadingMethod::Reference can show each tile as soon as it is final
// It never reads a bake's textures for its surfaces (only the environment it was given and
// the frame's shading model), so a re-bake keeps it; a new environment or model does not.
#include <chrono>
#include <optional>

#include "frame/frame_key.hpp"
#include "frame/fullscreen_triangle.hpp"
#include "frame/lighting.hpp"
#include "frame/mesh_pass.hpp"
#include "frame/readback.hpp"
#include "frame/reference_integral.hpp"
#include "frame/sky_pass.hpp"
#include "gl/render_target.hpp"

namespace iblab {

class ReferenceRenderer {
public:
    ReferenceRenderer(gl::ShaderLibrary& shaders, const FullscreenTriangle& triangle, MeshPass& mesh, SkyPass& sky)
        : shaders_(shaders), triangle_(triangle), mesh_(mesh), sky_(sky)
    {
    }

    // The loaded map, the parent of the environment the reference sums over.
    void setEnvironment(const ImageRGB32F& image);
    // The meshes changed (a model was loaded): references of the old ones are stale.
    void sceneChanged() { ++revision_; }
    // Another map is shown (its bake), before setEnvironment brings its pixels: the
    // reference of the old one is stale.
    void environmentChanged() { ++revision_; }

    // Everything the reference image depends on: not the tone map, the view's error and
    // split controls, nor the estimators' sampling (only the BRDF's geometry term and the
    // energy compensation are part of the shading model it shares), nor the frame's MSAA
    // (the reference shades pixel centres, single-sampled).
    FrameKey keyFor(const FrameSettings& settings, int width, int height) const;

    // Starts the reference of keyFor(settings, width, height) when it is not the one under
    // way (or the slicing differs), then runs slices until budget is spent (each waits on
    // a fence after the one before it, so that it is GPU time) or it is complete, and resolves a complete one. Needs
    // lighting.bake (for the sky behind it and the frame's shading inputs) and an environment.
    ReferenceStatus advance(const FrameSettings& settings, int width, int height, std::chrono::steady_clock::duration budget,
                            const ReferenceSlicing& slicing, SceneSlot& scene, const Lighting& lighting);
    ReferenceStatus status(const FrameSettings& settings, int width, int height) const;
    // Whether the resolved reference is the one of a frame made with this key.
    bool completeFor(const std::optional<FrameKey>& frameKey) const { return resolved_ && frameKey && frameKey == key_; }

    // Copies what is final of the reference made with `key` into columns [x0, x1) of target
    // (of the reference's size): all of them once it is complete, else the finished tiles
    // (the background and the unfinished tiles are left as they are). Nothing when the
    // reference under way is not of that key.
    void copyFinished(const FrameKey& key, const gl::RenderTarget& target, int x0, int x1) const;

    GLuint frameTexture() const { return frame_.texture(); }
    GLuint layerTexture(ReferenceLayer layer) const { return gbuffer_.texture(layer); }
    FrameReadback readFrame() const; // empty until resolved
    FrameReadback readLayer(ReferenceLayer layer) const; // empty before the first start

private:
    void start(const FrameSettings& settings, int width, int height, const ReferenceSlicing& slicing, FrameKey key, SceneSlot& scene,
               const Lighting& lighting);
    void resolve(const FrameSettings& settings, const Lighting& lighting);
    const ImageRGB32F& environmentOfWidth(int width);

    gl::ShaderLibrary& shaders_;
    const FullscreenTriangle& triangle_;
    MeshPass& mesh_;
    SkyPass& sky_;

    std::uint64_t revision_ = 0;   // moves with what it integrates: the loaded map and the meshes
    ImageRGB32F source_;           // the loaded map
    int sourceGeneration_ = 0;     // environments set, for the cache of its downsampled copy
    ImageRGB32F environment_;      // source_ downsampled to the requested width
    std::pair<int, int> environmentFor_{-1, -1}; // (generation, requested width)
    GBuffer gbuffer_;
    ReferenceIntegral integral_;
    gl::RenderTarget frame_; // RGBA32F + depth: the sky, then the resolved surfaces
    std::optional<FrameKey> key_;
    ReferenceSlicing slicing_;
    GeometryTerm geometry_ = GeometryTerm::HeightCorrelatedSmith;
    bool resolved_ = false;   // complete, and frame_ holds all of it
    unsigned long long runs_ = 0; // references started (ReferenceStatus::run)
    int resolvedTiles_ = 0;   // the integral's finished tiles that frame_ holds
};

} // namespace iblab
