// The frame renderer's coordinator: it owns the inputs the setters give it (environment,
// bakes, scene), the render targets and the passes, and runs the passes in this order:
//
//   pass            reads                                          writes
//   mesh            scene, camera, material, sampling, the bake    HDR frame (MSAA):
//                   (the furnace bake in the furnace view)         radiance, coverage 1, depth
//   sky             camera, ViewSettings' background, the          HDR frame where depth is
//                   environment, the bake                          still far: radiance, coverage 0
//   A/B split       ViewSettings::split, splitPosition, compare    mesh + sky for side A over the
//                                                                  frame, then for B scissored
//   debug view      the bake's prefiltered cube or LUTs            HDR frame, every pixel, in
//                                                                  place of mesh + sky
//   MSAA resolve    HDR frame (MSAA)                               HDR frame (RGBA16F)
//   reference       each side drawn with ShadingMethod::Reference, HDR frame: the finished part of
//   method          the reference renderer's frame                 that side's reference over its
//                                                                  columns (the mesh pass previewed
//                                                                  it with the split sum)
//   accumulation    HDR frame, the frame's FrameKey                running mean (RGBA32F)
//   tone map        HDR frame or running mean, ToneMapSettings     display (RGBA8, sRGB)
//   error view      HDR frame or running mean, the reference       display, in place of the
//                   frame and coverage, error space and scale      tone map
//
// The reference renderer (reference_renderer.hpp) runs when asked (advanceReference): the
// mesh pass into its G-buffer, its integral in slices, then the sky pass and its resolve.
// renderFrame never advances it: a frame shows the reference method's side as far as the
// last advanceReference took it.
// What read-back frames say (error, furnace spheres, debug texels) is frame_analysis.hpp.
#include "frame/renderer.hpp"

#include <algorithm>
#include <cmath>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

#include "bake/bake_result.hpp"
#include "frame/accumulation_pass.hpp"
#include "frame/camera.hpp"
#include "frame/debug_view_pass.hpp"
#include "frame/display_passes.hpp"
#include "frame/fullscreen_triangle.hpp"
#include "frame/gpu_scene.hpp"
#include "frame/mesh_pass.hpp"
#include "frame/reference_renderer.hpp"
#include "frame/sky_pass.hpp"
#include "frame/texture_readback.hpp"
#include "frame/texture_units.hpp"
#include "gl/render_target.hpp"
#include "gl/texture_upload.hpp"

namespace iblab {
namespace {

void assignSamplerUnits(const gl::ShaderProgram& program)
{
    for (const auto& [name, unit] : kSamplerUnits) gl::Uniform<int>(program, name).set(int(unit));
}

} // namespace

struct Renderer::Impl {
    gl::ShaderLibrary shaders;
    FullscreenTriangle triangle;
    MeshPass mesh{shaders};
    SkyPass sky{shaders, triangle};
    DebugViewPass debugView{shaders, triangle};
    AccumulationPass accumulation{shaders, triangle};
    ToneMapPass toneMap{shaders, triangle};
    ErrorViewPass errorView{shaders, triangle};
    ReferenceRenderer reference{shaders, triangle, mesh, sky};

    gl::Texture equirect;
    std::shared_ptr<const bake::BakeResult> bake;
    std::shared_ptr<const bake::BakeResult> furnaceBake; // builtin:white, for ViewMode::Furnace
    SceneSlot scene;
    // Counts every change of what a frame shows besides its settings (environment, bakes,
    // model), so that no running mean outlives what it was made from.
    std::uint64_t contentRevision = 0;

    gl::RenderTarget hdrFrame;       // RGBA16F + depth: the resolved frame
    gl::MultisampleTarget msaaFrame; // RGBA16F + depth, ViewSettings::msaaSamples per pixel
    gl::RenderTarget displayFrame;   // RGBA8: exposure, tone curve and sRGB applied

    // The last frame's.
    int frameSamples = 1;
    bool sampledDraws = false; // drew with the sampled method and rotating sample sets
    const gl::RenderTarget* resolved = &hdrFrame; // what the display pass read: the frame or the running mean
    std::optional<FrameKey> frameKey;             // reference.keyFor() it, to match it with the reference

    // Whether every side drawn with the reference method shows its complete reference: until
    // then the side changes as tiles finish, and a running mean of it would mix the stages.
    bool referenceSidesFinal(const FrameSettings& settings, int width, int height) const
    {
        if (!referenceMethodSide(settings)) return true;
        bool final = true;
        forEachVisibleSide(settings, width, [&](const FrameSettings& side, int, int) {
            if (side.sampling.method == ShadingMethod::Reference) final = final && reference.completeFor(reference.keyFor(side, width, height));
        });
        return final;
    }

    // The reference method's sides: their finished reference over the split-sum preview.
    void copyReferenceSides(const FrameSettings& settings, int width, int height)
    {
        if (!referenceMethodSide(settings)) return;
        forEachVisibleSide(settings, width, [&](const FrameSettings& side, int x0, int x1) {
            if (side.sampling.method == ShadingMethod::Reference) reference.copyFinished(reference.keyFor(side, width, height), hdrFrame, x0, x1);
        });
    }

    explicit Impl(std::filesystem::path shaderDirectory) : shaders(std::move(shaderDirectory)) { shaders.setProgramInitializer(assignSamplerUnits); }

    // The furnace view lights with the furnace bake; every other view with the bake.
    Lighting lightingFor(const FrameSettings& settings) const
    {
        return {equirect.id(), settings.view.mode == ViewMode::Furnace ? furnaceBake.get() : bake.get()};
    }
};

Renderer::Renderer(std::filesystem::path shaderDirectory) : impl_(std::make_unique<Impl>(std::move(shaderDirectory))) {}
Renderer::~Renderer() = default;

void Renderer::setEnvironment(const ImageRGB32F& image)
{
    impl_->reference.setEnvironment(image);
    // The frame reads the map only as the sky before a bake exists (the sky pass): with a
    // bake, a new map changes nothing drawn until its own bake is set.
    if (!impl_->bake) ++impl_->contentRevision;
    // Repeat in u (longitude wraps), clamp in v (the poles do not).
    impl_->equirect = gl::createMipmappedTexture2D(
        {GL_RGB32F, image.width, image.height, GL_RGB, GL_FLOAT, image.texels.data(), 4, GL_REPEAT, GL_CLAMP_TO_EDGE});
}

void Renderer::setBake(std::shared_ptr<const bake::BakeResult> bake)
{
    impl_->bake = std::move(bake);
    ++impl_->contentRevision;
}
bool Renderer::hasBake() const { return bool(impl_->bake); }

void Renderer::setFurnaceBake(std::shared_ptr<const bake::BakeResult> bake)
{
    impl_->furnaceBake = std::move(bake);
    ++impl_->contentRevision;
}
bool Renderer::hasFurnaceBake() const { return bool(impl_->furnaceBake); }

void Renderer::setModel(const ModelData& model, const std::string& path)
{
    impl_->scene.setModel(model, path);
    impl_->reference.sceneChanged();
    ++impl_->contentRevision;
}
std::uint64_t Renderer::contentRevision() const { return impl_->contentRevision; }

std::vector<SphereReading> Renderer::measureSpheres(const FrameSettings& settings) const
{
    const Impl& r = *impl_;
    const GpuScene& scene = r.scene.current();
    if (scene.kind == SceneKind::Model || r.hdrFrame.width() == 0) return {};
    std::vector<SphereInstance> spheres;
    for (const SceneDraw& draw : scene.draws)
        spheres.push_back({draw.model, draw.materialFromScene ? draw.material.metallicFactor : settings.material.metallic,
                           draw.materialFromScene ? draw.material.roughnessFactor : settings.material.roughness});
    return sphereReadings(readHdrFrame(), settings.camera, spheres);
}

SceneInfo Renderer::sceneInfo(const FrameSettings& settings)
{
    const GpuScene& scene = impl_->scene.ensure(settings.scene);
    return {scene.draws.size(), scene.gpuBytes, scene.bounds.center(), glm::max(0.5f * scene.bounds.size(), glm::vec3(1e-3f))};
}

void Renderer::renderFrame(const FrameSettings& settings, int fullWidth, int fullHeight, const Options& options)
{
    Impl& r = *impl_;
    const float scale = std::clamp(options.resolutionScale, 0.05f, 1.0f);
    const int width = std::max(1, int(std::lround(float(fullWidth) * scale)));
    const int height = std::max(1, int(std::lround(float(fullHeight) * scale)));
    r.hdrFrame.ensure(GL_RGBA16F, width, height, /*withDepth=*/true);
    r.displayFrame.ensure(GL_RGBA8, width, height);
    const float aspect = float(width) / float(height);

    // A new running mean whenever anything that changes the image changes. Where every
    // side keeps its exact sample count, more frames would only average copies: none.
    const bool accumulate = options.accumulate && !everySideKeepsExactSampleCount(settings) && r.referenceSidesFinal(settings, width, height);
    const glm::vec2 rotation = r.accumulation.begin(accumulate ? std::optional<FrameKey>(FrameKey{settings, width, height, r.contentRevision})
                                                               : std::nullopt);

    const Lighting lighting = r.lightingFor(settings);
    r.sampledDraws = false;
    const bool debugView = lighting.bake && (settings.view.mode == ViewMode::PrefilterMips || settings.view.mode == ViewMode::Lut);
    // Debug views fill every pixel with one full-screen triangle: samples would add nothing.
    const bool multisampled = !debugView && settings.view.msaaSamples > 1;
    if (multisampled) r.msaaFrame.ensure(GL_RGBA16F, width, height, settings.view.msaaSamples);
    r.frameSamples = multisampled ? r.msaaFrame.samples() : 1;

    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, multisampled ? r.msaaFrame.framebuffer() : r.hdrFrame.framebuffer());
    glViewport(0, 0, width, height);
    glClear(GL_DEPTH_BUFFER_BIT);
    if (debugView) {
        r.debugView.draw(settings, lighting, width, height);
    } else {
        drawSides(settings, width, height, [&](const FrameSettings& side) {
            // The reference method's preview where its reference is not finished: the split sum.
            FrameSettings shaded = side;
            if (shaded.sampling.method == ShadingMethod::Reference) shaded.sampling.method = ShadingMethod::SplitSum;
            // Meshes first, then the sky behind them: llvmpipe shades only the uncovered pixels.
            const bool sampled = r.mesh.draw(r.scene, shaded, lighting, aspect, rotation, MeshPass::Output::Shaded);
            r.sampledDraws = r.sampledDraws || sampled;
            r.sky.draw(shaded, lighting, aspect);
        });
    }
    if (multisampled) r.msaaFrame.resolveInto(r.hdrFrame);
    r.copyReferenceSides(settings, width, height);
    r.frameKey = r.reference.keyFor(settings, width, height);
    r.resolved = &r.accumulation.add(r.hdrFrame);

    glBindFramebuffer(GL_FRAMEBUFFER, r.displayFrame.framebuffer());
    if (settings.view.mode == ViewMode::Error && r.reference.completeFor(r.frameKey))
        r.errorView.draw(r.resolved->texture(), r.reference.frameTexture(), r.reference.layerTexture(ReferenceLayer::Normal), settings);
    else
        r.toneMap.draw(r.resolved->texture(), settings.toneMap, debugView && settings.view.mode == ViewMode::Lut);
    glUseProgram(0);
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

int Renderer::accumulatedFrames() const { return impl_->accumulation.frames(); }
int Renderer::frameSamples() const { return impl_->frameSamples; }
bool Renderer::lastFrameWasSampled() const { return impl_->sampledDraws; }

ReferenceStatus Renderer::advanceReference(const FrameSettings& settings, int width, int height, std::chrono::steady_clock::duration budget,
                                           const ReferenceSlicing& slicing)
{
    Impl& r = *impl_;
    // The reference is of the lit frame, whatever the view: the bake, never the furnace's.
    return r.reference.advance(referenceSubject(settings), width, height, budget, slicing, r.scene, Lighting{r.equirect.id(), r.bake.get()});
}

ReferenceStatus Renderer::referenceStatus(const FrameSettings& settings, int width, int height) const
{
    return impl_->reference.status(referenceSubject(settings), width, height);
}
FrameReadback Renderer::readReferenceFrame() const { return impl_->reference.readFrame(); }
FrameReadback Renderer::readReferenceLayer(ReferenceLayer layer) const { return impl_->reference.readLayer(layer); }

ErrorReport Renderer::measureError(const FrameSettings& settings) const
{
    if (!impl_->reference.completeFor(impl_->frameKey)) return {};
    return frameErrorReport(readHdrFrame(), readReferenceFrame(), readReferenceLayer(ReferenceLayer::Normal), settings);
}

unsigned int Renderer::displayTexture() const { return impl_->displayFrame.texture(); }

void Renderer::presentTo(unsigned int framebuffer, int x0, int y0, int x1, int y1) const
{
    const gl::RenderTarget& display = impl_->displayFrame;
    glBlitNamedFramebuffer(display.framebuffer(), framebuffer, 0, 0, display.width(), display.height(), x0, y0, x1, y1, GL_COLOR_BUFFER_BIT, GL_LINEAR);
}

void Renderer::bindDisplayFramebuffer() const
{
    glBindFramebuffer(GL_FRAMEBUFFER, impl_->displayFrame.framebuffer());
    glViewport(0, 0, impl_->displayFrame.width(), impl_->displayFrame.height());
}

FrameReadback Renderer::readHdrFrame() const
{
    const gl::RenderTarget& hdr = *impl_->resolved;
    return readFloatTexture(hdr.texture(), hdr.width(), hdr.height());
}

DisplayReadback Renderer::readDisplayImage() const
{
    const gl::RenderTarget& display = impl_->displayFrame;
    return readByteTexture(display.texture(), display.width(), display.height());
}

std::vector<ScreenLabel> Renderer::sceneLabels(const FrameSettings& settings, int width, int height) const
{
    std::vector<ScreenLabel> labels;
    const glm::mat4 viewProjection = cameraProjection(settings.camera, float(width) / float(height)) * cameraView(settings.camera);
    for (const GridLabel& label : impl_->scene.current().labels) {
        const glm::vec4 clip = viewProjection * glm::vec4(label.position, 1.0f);
        if (clip.w <= 0.0f) continue; // behind the camera
        labels.push_back({clipToPixel(clip, width, height), label.text, label.axisTitle});
    }
    return labels;
}

std::vector<float> Renderer::prefilterMipRoughness() const { return impl_->bake ? prefilterMipRoughnessOf(*impl_->bake) : std::vector<float>{}; }

TexelProbe Renderer::probe(const FrameSettings& settings, int width, int height, float x, float y) const
{
    if (!impl_->bake) return {};
    return probeDebugView(settings, *impl_->bake, width, height, x, y);
}

gl::ShaderLibrary& Renderer::shaders() { return impl_->shaders; }
std::vector<std::string> Renderer::reloadShaders()
{
    const std::uint64_t before = impl_->shaders.reloads();
    std::vector<std::string> errors = impl_->shaders.reloadChanged();
    if (impl_->shaders.reloads() != before) {
        // An edited shader draws another image: no mean of the old one's frames, and the
        // reference (its integral and resolve are shaders too) starts again.
        ++impl_->contentRevision;
        impl_->reference.sceneChanged();
    }
    return errors;
}

} // namespace iblab
