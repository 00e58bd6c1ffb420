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
#include "frame/shading_lights_texture.hpp"
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
    std::unique_ptr<ShadingLightsTexture> bakeLights;    // of `bake`; null without lights (the furnace's white has none)
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

    // A frame drawn in bands over several calls (renderFrameSlice): what it is of, and how
    // far it got.
    struct SlicedFrame {
        FrameKey key;
        bool accumulate = false;
        glm::vec2 rotation{0.0f};
        int nextRow = 0;
        bool sampled = false;
        double spentMs = 0.0;
    };
    std::optional<SlicedFrame> sliced;
    gl::RenderTarget workFrame; // RGBA16F + depth: a sliced frame's bands without MSAA
    double msPerRow = 0.0;      // of the last band drawn, to size the next
    double slicedFrameMs = 0.0; // the bands of the last sliced frame, summed

    // What a frame of these settings, size and options draws.
    struct FrameShape {
        int width = 0, height = 0;
        bool accumulate = false;
        bool debugView = false;
        bool multisampled = false;
        int msaaSamples = 1;
    };
    FrameShape shapeOf(const FrameSettings& settings, int fullWidth, int fullHeight, const Options& options) const
    {
        FrameShape shape;
        const float scale = std::clamp(options.resolutionScale, 0.05f, 1.0f);
        shape.width = std::max(1, int(std::lround(float(fullWidth) * scale)));
        shape.height = std::max(1, int(std::lround(float(fullHeight) * scale)));
        // A new running mean whenever anything that changes the image changes. Where every
        // side keeps its exact sample count, more frames would only average copies: none.
        shape.accumulate = options.accumulate && !everySideKeepsExactSampleCount(settings) && referenceSidesFinal(settings, shape.width, shape.height);
        const Lighting lighting = lightingFor(settings);
        shape.debugView = lighting.bake && (settings.view.mode == ViewMode::PrefilterMips || settings.view.mode == ViewMode::Lut);
        // Debug views fill every pixel with one full-screen triangle: samples would add nothing.
        shape.multisampled = !shape.debugView && settings.view.msaaSamples > 1;
        shape.msaaSamples = settings.view.msaaSamples;
        return shape;
    }

    // The target the frame's passes draw into (the MSAA frame, or single-sampled `single`),
    // allocated and its depth cleared.
    void beginTarget(const FrameShape& shape, const gl::RenderTarget& single)
    {
        if (shape.multisampled) msaaFrame.ensure(GL_RGBA16F, shape.width, shape.height, shape.msaaSamples);
        glDisable(GL_SCISSOR_TEST);
        glBindFramebuffer(GL_FRAMEBUFFER, shape.multisampled ? msaaFrame.framebuffer() : single.framebuffer());
        glViewport(0, 0, shape.width, shape.height);
        glClear(GL_DEPTH_BUFFER_BIT);
    }

    // Rows [y0, y1) of the frame: the debug view, or mesh and sky for each side. Returns
    // whether a draw used the sampled method with rotating sample sets.
    bool drawRows(const FrameSettings& settings, const FrameShape& shape, glm::vec2 rotation, int y0, int y1)
    {
        const Lighting lighting = lightingFor(settings);
        const float aspect = float(shape.width) / float(shape.height);
        glDisable(GL_BLEND);
        glDisable(GL_CULL_FACE);
        glDisable(GL_DEPTH_TEST);
        glBindFramebuffer(GL_FRAMEBUFFER, shape.multisampled ? msaaFrame.framebuffer() : sliced ? workFrame.framebuffer() : hdrFrame.framebuffer());
        glViewport(0, 0, shape.width, shape.height);
        bool sampled = false;
        if (shape.debugView) {
            glEnable(GL_SCISSOR_TEST);
            glScissor(0, y0, shape.width, y1 - y0);
            debugView.draw(settings, lighting, shape.width, shape.height);
            glDisable(GL_SCISSOR_TEST);
            return false;
        }
        drawSides(
            settings, shape.width, shape.height,
            [&](const FrameSettings& side) {
                // The reference method's preview where its reference is not finished: the split sum.
                FrameSettings shaded = side;
                if (shaded.sampling.method == ShadingMethod::Reference) shaded.sampling.method = ShadingMethod::SplitSum;
                // Meshes first, then the sky behind them: llvmpipe shades only the uncovered pixels.
                sampled = mesh.draw(scene, shaded, lighting, aspect, rotation, MeshPass::Output::Shaded) || sampled;
                sky.draw(shaded, lighting, aspect);
            },
            y0, y1);
        return sampled;
    }

    // The drawn frame, complete in `frame` (resolved from MSAA first): the reference
    // method's sides over it, into the running mean, then tone-mapped (or the error view)
    // into the display image.
    void finish(const FrameSettings& settings, const FrameShape& shape, const gl::RenderTarget& frame)
    {
        frameSamples = shape.multisampled ? msaaFrame.samples() : 1;
        if (shape.multisampled) msaaFrame.resolveInto(frame);
        copyReferenceSides(settings, shape.width, shape.height);
        frameKey = reference.keyFor(settings, shape.width, shape.height);
        resolved = &accumulation.add(frame);
        displayFrame.ensure(GL_RGBA8, shape.width, shape.height);
        glBindFramebuffer(GL_FRAMEBUFFER, displayFrame.framebuffer());
        glViewport(0, 0, shape.width, shape.height);
        if (settings.view.mode == ViewMode::Error && reference.completeFor(frameKey))
            errorView.draw(resolved->texture(), reference.frameTexture(), reference.layerTexture(ReferenceLayer::Normal), settings);
        else
            toneMap.draw(resolved->texture(), settings.toneMap, shape.debugView && settings.view.mode == ViewMode::Lut);
        glUseProgram(0);
        glBindVertexArray(0);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }

    explicit Impl(std::filesystem::path shaderDirectory) : shaders(std::move(shaderDirectory)) { shaders.setProgramInitializer(assignSamplerUnits); }

    // The furnace view lights with the furnace bake; every other view with the bake.
    Lighting lightingFor(const FrameSettings& settings) const
    {
        if (settings.view.mode == ViewMode::Furnace) return {equirect.id(), furnaceBake.get(), nullptr};
        return {equirect.id(), bake.get(), bakeLights.get()};
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
    // Another map's bake can come before that map's pixels (the session shows a bake read
    // from the cache while the file decodes): the reference of the old map, its sky
    // included, is stale from now on, not only once setEnvironment brings the pixels.
    const bool otherMap = bake && impl_->bake && bake->contentHash != impl_->bake->contentHash;
    if (otherMap) impl_->reference.environmentChanged();
    impl_->bake = std::move(bake);
    impl_->bakeLights = impl_->bake ? makeShadingLightsTexture(impl_->shaders, *impl_->bake) : nullptr;
    ++impl_->contentRevision;
}
bool Renderer::hasBake() const { return bool(impl_->bake); }
Renderer::ShadingLightsInfo Renderer::shadingLights() const
{
    if (!impl_->bakeLights) return {};
    return {int(impl_->bakeLights->lights.size()), impl_->bakeLights->milliseconds};
}

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
    r.sliced.reset(); // a whole frame replaces whatever was under way
    const Impl::FrameShape shape = r.shapeOf(settings, fullWidth, fullHeight, options);
    r.hdrFrame.ensure(GL_RGBA16F, shape.width, shape.height, /*withDepth=*/true);
    r.beginTarget(shape, r.hdrFrame);
    const glm::vec2 rotation = r.accumulation.begin(shape.accumulate ? std::optional<FrameKey>(FrameKey{settings, shape.width, shape.height, r.contentRevision})
                                                                     : std::nullopt);
    r.sampledDraws = r.drawRows(settings, shape, rotation, 0, shape.height);
    r.finish(settings, shape, r.hdrFrame);
}

bool Renderer::renderFrameSlice(const FrameSettings& settings, int fullWidth, int fullHeight, const Options& options,
                                std::chrono::steady_clock::duration budget)
{
    using Clock = std::chrono::steady_clock;
    Impl& r = *impl_;
    const Impl::FrameShape shape = r.shapeOf(settings, fullWidth, fullHeight, options);
    const FrameKey key{settings, shape.width, shape.height, r.contentRevision};
    if (!r.sliced || r.sliced->key != key || r.sliced->accumulate != shape.accumulate) {
        // The bands go to a target of their own: the image on screen (and what readbacks
        // read) stays the last complete frame until the last band is in.
        r.workFrame.ensure(GL_RGBA16F, shape.width, shape.height, /*withDepth=*/true);
        r.beginTarget(shape, r.workFrame);
        const glm::vec2 rotation = r.accumulation.begin(shape.accumulate ? std::optional<FrameKey>(key) : std::nullopt);
        r.sliced = Impl::SlicedFrame{key, shape.accumulate, rotation};
    }
    Impl::SlicedFrame& frame = *r.sliced;
    const auto start = Clock::now();
    do {
        // Bands sized from the cost per row so far, the higher of the last band's and the
        // frame's mean (the last frame's at the start): rows differ by far (a band of sky
        // costs a fraction of one through a sampled sphere), and a band sized from a cheap one
        // overran the budget by seconds. Whole 4-row steps, at least one.
        const double left = std::chrono::duration<double, std::milli>(budget - (Clock::now() - start)).count();
        const double meanMsPerRow = frame.nextRow > 0 ? frame.spentMs / double(frame.nextRow) : r.slicedFrameMs / double(shape.height);
        // A row through the scene costs a few times the mean row: twice the caller's mean.
        const double msPerRow = std::max({r.msPerRow, meanMsPerRow, 2.0 * options.expectedMs / double(shape.height)});
        int rows = msPerRow > 0.0 ? int(left / msPerRow) : shape.height / 16;
        rows = std::min(std::max(rows / 4 * 4, 4), shape.height - frame.nextRow);
        const auto bandStart = Clock::now();
        frame.sampled = r.drawRows(settings, shape, frame.rotation, frame.nextRow, frame.nextRow + rows) || frame.sampled;
        glFinish(); // the budget is GPU time, as the reference renderer's
        const double ms = std::chrono::duration<double, std::milli>(Clock::now() - bandStart).count();
        r.msPerRow = ms / double(rows);
        frame.spentMs += ms;
        frame.nextRow += rows;
    } while (frame.nextRow < shape.height && Clock::now() - start < budget);
    if (frame.nextRow < shape.height) return false;
    r.sampledDraws = frame.sampled;
    r.slicedFrameMs = frame.spentMs;
    if (!shape.multisampled) std::swap(r.hdrFrame, r.workFrame);
    else r.hdrFrame.ensure(GL_RGBA16F, shape.width, shape.height, /*withDepth=*/true);
    r.sliced.reset();
    r.finish(settings, shape, r.hdrFrame);
    return true;
}

float Renderer::sliceProgress() const
{
    const Impl& r = *impl_;
    return r.sliced ? float(r.sliced->nextRow) / float(std::max(r.sliced->key.height, 1)) : 0.0f;
}
double Renderer::lastSlicedFrameMs() const { return impl_->slicedFrameMs; }

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
