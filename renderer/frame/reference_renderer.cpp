#include "frame/reference_renderer.hpp"

#include <algorithm>

#include "frame/texture_readback.hpp"
#include "frame/texture_units.hpp"
#include "gl/fence.hpp"
#include "ibl/equirect.hpp"
#include "ibl/reference.hpp"

namespace iblab {

void ReferenceRenderer::setEnvironment(const ImageRGB32F& image)
{
    source_ = image;
    ++sourceGeneration_;
    ++revision_;
}

FrameKey ReferenceRenderer::keyFor(const FrameSettings& settings, int width, int height) const
{
    FrameSettings s = settings;
    s.toneMap = {};
    SamplingSettings model;
    model.geometry = settings.sampling.geometry;
    model.multiscatter = settings.sampling.multiscatter;
    model.multiscatterModel = settings.sampling.multiscatterModel;
    s.sampling = model;
    s.view.mode = ViewMode::Error;
    s.view.errorSpace = {};
    s.view.errorScale = {};
    s.view.split = false;
    s.view.splitPosition = {};
    s.view.compare = {};
    s.view.msaaSamples = 1;
    return {std::move(s), width, height, revision_};
}

const ImageRGB32F& ReferenceRenderer::environmentOfWidth(int width)
{
    const std::pair<int, int> wanted{sourceGeneration_, width};
    if (environmentFor_ != wanted) {
        // A map narrower than the width asked for is summed as its bilinear upsample, at most
        // that wide: the map as the sky shows it and as the bake reads a map too coarse for
        // its mip 1 (bake_settings.hpp, bakeSourceUpsampleFactor), finely enough for the
        // lobes the width resolves.
        int upsample = 1;
        while (upsample < 16 && source_.width * upsample * 2 <= width) upsample *= 2;
        environment_ = upsample > 1 ? upsampleEquirectBilinear(source_, upsample) : downsampleEquirectToWidth(source_, std::max(width, 2));
        environmentFor_ = wanted;
    }
    return environment_;
}

ReferenceStatus ReferenceRenderer::advance(const FrameSettings& settings, int width, int height, std::chrono::steady_clock::duration budget,
                                           const ReferenceSlicing& slicing, SceneSlot& scene, const Lighting& lighting)
{
    if (!lighting.bake || source_.empty()) return {};
    FrameKey key = keyFor(settings, width, height);
    if (key != key_ || slicing != slicing_) start(settings, width, height, slicing, std::move(key), scene, lighting);
    // Each slice waits for the one before it (a fence, not glFinish): the budget counts GPU
    // work, and at most one slice is still queued when the frame goes on.
    const auto begin = std::chrono::steady_clock::now();
    gl::Fence previousSlice;
    while (!integral_.complete() && std::chrono::steady_clock::now() - begin < budget) {
        integral_.runSlice(shaders_, gbuffer_, geometry_);
        gl::Fence slice = gl::Fence::afterIssuedCommands();
        previousSlice.wait();
        previousSlice = std::move(slice);
    }
    // A resolve is a full-screen pass: cheap next to a slice, so it runs whenever tiles
    // finished, not only at the end.
    if (integral_.finishedTiles() != resolvedTiles_ || (integral_.complete() && !resolved_)) resolve(settings, lighting);
    return status(settings, width, height);
}

ReferenceStatus ReferenceRenderer::status(const FrameSettings& settings, int width, int height) const
{
    ReferenceStatus status;
    status.current = key_ == keyFor(settings, width, height);
    if (!status.current) return status;
    status.complete = resolved_;
    status.run = runs_;
    status.progress = integral_.progress();
    status.environmentWidth = integral_.environmentWidth();
    status.environmentHeight = integral_.environmentHeight();
    status.texelDegrees = 360.0 / double(std::max(status.environmentWidth, 1));
    status.minResolvedRoughness = referenceMinResolvedRoughness(status.environmentWidth);
    return status;
}

// The mesh pass into the G-buffer, then a fresh integral over the environment.
void ReferenceRenderer::start(const FrameSettings& settings, int width, int height, const ReferenceSlicing& slicing, FrameKey key,
                              SceneSlot& scene, const Lighting& lighting)
{
    gbuffer_.ensure(width, height);
    gbuffer_.bindCleared();
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    mesh_.draw(scene, settings, lighting, float(width) / float(height), glm::vec2(0.0f), MeshPass::Output::GBuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    // Tiles without a surface pixel (coverage: the normal layer's alpha) are skipped.
    const FrameReadback normals = readLayer(ReferenceLayer::Normal);
    std::vector<std::uint8_t> coverage(normals.rgba.size() / 4);
    for (std::size_t i = 0; i < coverage.size(); ++i) coverage[i] = normals.rgba[i * 4 + 3] != 0.0f;
    integral_.start(environmentOfWidth(settings.view.referenceWidth), width, height, coverage, slicing);
    key_ = std::move(key);
    ++runs_;
    slicing_ = slicing;
    geometry_ = settings.sampling.geometry;
    resolved_ = false;
    resolvedTiles_ = 0;
}

// The environment behind, through the frame's own sky pass; the surfaces from the sums.
void ReferenceRenderer::resolve(const FrameSettings& settings, const Lighting& lighting)
{
    const int width = gbuffer_.width(), height = gbuffer_.height();
    frame_.ensure(GL_RGBA32F, width, height, /*withDepth=*/true);
    glBindFramebuffer(GL_FRAMEBUFFER, frame_.framebuffer());
    glViewport(0, 0, width, height);
    glClear(GL_DEPTH_BUFFER_BIT);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    sky_.draw(settings, lighting, float(width) / float(height));
    const gl::ShaderProgram& program = shaders_.program({"fullscreen.vert", "reference_resolve.frag"});
    glUseProgram(program.id());
    program.uniforms<IblUniforms>().bind(lighting, settings);
    for (int layer = 0; layer < int(ReferenceLayer::Count); ++layer)
        glBindTextureUnit(kUnitGNormal + GLuint(layer), gbuffer_.texture(ReferenceLayer(layer)));
    glBindTextureUnit(kUnitSpecularSum, integral_.specularSum());
    glBindTextureUnit(kUnitIrradianceSum, integral_.irradianceSum());
    triangle_.draw();
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    resolved_ = integral_.complete();
    resolvedTiles_ = integral_.finishedTiles();
}

void ReferenceRenderer::copyFinished(const FrameKey& key, const gl::RenderTarget& target, int x0, int x1) const
{
    if (key != key_ || target.width() != frame_.width() || target.height() != frame_.height()) return;
    const auto copy = [&](glm::ivec4 rect) {
        rect.x = std::max(rect.x, x0);
        rect.z = std::min(rect.z, x1);
        if (rect.x >= rect.z || rect.y >= rect.w) return;
        glBlitNamedFramebuffer(frame_.framebuffer(), target.framebuffer(), rect.x, rect.y, rect.z, rect.w, rect.x, rect.y, rect.z, rect.w,
                               GL_COLOR_BUFFER_BIT, GL_NEAREST);
    };
    if (resolved_) {
        copy({0, 0, frame_.width(), frame_.height()});
        return;
    }
    for (int tile = 0; tile < resolvedTiles_; ++tile) copy(integral_.tileRect(tile));
}

FrameReadback ReferenceRenderer::readFrame() const
{
    if (!resolved_) return {};
    return readFloatTexture(frame_.texture(), frame_.width(), frame_.height());
}

FrameReadback ReferenceRenderer::readLayer(ReferenceLayer layer) const
{
    if (gbuffer_.width() == 0) return {};
    return readFloatTexture(gbuffer_.texture(layer), gbuffer_.width(), gbuffer_.height());
}

} // namespace iblab
