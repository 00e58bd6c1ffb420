#include "frame/renderer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <span>

#include <epoxy/gl.h>
#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "bake/bake_result.hpp"
#include "frame/camera.hpp"
#include "frame/debug_layout.hpp"
#include "gl/handles.hpp"
#include "gl/render_target.hpp"
#include "gl/shader_library.hpp"
#include "gl/texture_upload.hpp"
#include "frame/gpu_scene.hpp"
#include "ibl/reference.hpp"
#include "ibl/sampling.hpp"
#include "ibl/tonemap.hpp"
#include "frame/reference_integral.hpp"
#include "frame/texture_units.hpp"

namespace iblab {
namespace {

// Cube-cross cell -> GL face, as debug_views.frag lays them out (row 0 at the bottom).
int crossFace(int column, int row)
{
    if (row == 1) return column == 0 ? 1 : column == 1 ? 4 : column == 2 ? 0 : 5;
    if (column != 1) return -1;
    return row == 2 ? 2 : row == 0 ? 3 : -1;
}

constexpr const char* kFaceNames[] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};

void assignSamplerUnits(const gl::ShaderProgram& program)
{
    for (const auto& [name, unit] : kSamplerUnits) program.set(name, int(unit));
}


std::vector<float> mipRoughnessOf(const bake::BakeResult& bake)
{
    std::vector<float> roughness;
    for (int level = 0; level < bake.prefiltered.levels; ++level)
        roughness.push_back(bake::prefilterMipRoughness(bake.settings.prefilter, level));
    return roughness;
}

// What an image was made from, compared by value: its settings (reduced to those it
// depends on), its size, and the revision of what the setters gave the renderer.
struct FrameKey {
    FrameSettings settings;
    int width = 0;
    int height = 0;
    std::uint64_t revision = 0;
    bool operator==(const FrameKey&) const = default;
};

// The split view's right side: the frame's settings with the comparison's sampling.
FrameSettings compareSide(const FrameSettings& settings)
{
    FrameSettings b = settings;
    b.sampling = settings.view.compare;
    return b;
}

} // namespace

struct Renderer::Impl {
    gl::ShaderLibrary shaders;
    gl::VertexArray emptyVertexArray = gl::createVertexArray();
    gl::Texture equirect;
    std::shared_ptr<const bake::BakeResult> bake;
    std::shared_ptr<const bake::BakeResult> furnaceBake; // builtin:white, for ViewMode::Furnace
    const bake::BakeResult* active = nullptr;            // the bake this frame lights with
    GpuScene scene;
    bool sceneBuilt = false;
    SceneSettings builtFor;
    gl::Buffer hammersley = gl::createBuffer();
    int hammersleyCount = 0;
    // The linear frame. Its alpha is coverage: surfaces write 1 and the sky 0, so that after
    // the MSAA resolve it is the fraction of a pixel's samples on surfaces.
    gl::RenderTarget hdrFrame;          // RGBA16F + depth: the resolved frame the tone mapper reads
    gl::MultisampleTarget msaaFrame;    // RGBA16F + depth, ViewSettings::msaaSamples per pixel
    int frameSamples = 1;               // of the last frame
    gl::RenderTarget displayFrame; // RGBA8: exposure, tone curve and sRGB applied
    gl::RenderTarget accumulation; // RGBA32F running mean of hdrFrame over accumulated frames
    std::optional<FrameKey> accumulationKey; // what the running mean belongs to
    int accumulatedFrames = 0;
    bool sampledDraws = false; // the last frame drew with the sampled method and rotating sample sets
    const gl::RenderTarget* resolved = &hdrFrame; // what the tone mapper read last
    std::optional<FrameKey> frameKey; // referenceKeyFor() the last frame, to match it with the reference

    // Revisions of what the setters change, so that no image outlives what it was made
    // from: contentRevision counts every change of what a frame shows (environment, bakes,
    // model); referenceRevision only those the reference integrates (the loaded map and the
    // meshes: it never reads a bake, so a re-bake keeps it).
    std::uint64_t contentRevision = 0;
    std::uint64_t referenceRevision = 0;

    // The reference renderer.
    ImageRGB32F environmentSource; // the loaded map, the reference environment's parent
    int environmentGeneration = 0; // environments set, for the cache of its downsampled copy
    ImageRGB32F referenceEnvironment;
    std::pair<int, int> referenceEnvironmentFor{-1, -1}; // (generation, requested width)
    GBuffer gbuffer;
    ReferenceIntegral reference;
    gl::RenderTarget referenceFrame; // RGBA32F + depth: the sky, then the resolved surfaces
    std::optional<FrameKey> referenceKey;
    ReferenceSlicing referenceSlicing;
    GeometryTerm referenceGeometry = GeometryTerm::HeightCorrelatedSmith;
    bool referenceResolved = false;

    explicit Impl(std::filesystem::path shaderDirectory) : shaders(std::move(shaderDirectory))
    {
        shaders.setProgramInitializer(assignSamplerUnits);
        glNamedBufferStorage(hammersley.id(), kMaxSampleCount * sizeof(float) * 2, nullptr, GL_DYNAMIC_STORAGE_BIT);
    }

    void drawFullscreenTriangle() const
    {
        glBindVertexArray(emptyVertexArray.id());
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }

    // The first n Hammersley points, uploaded only when N changes (std140 packs two per vec4).
    void ensureHammersley(int n)
    {
        if (n == hammersleyCount) return;
        std::vector<float> points(std::size_t(n) * 2);
        for (int i = 0; i < n; ++i) {
            const glm::dvec2 p = iblab::hammersley(std::uint32_t(i), std::uint32_t(n));
            points[std::size_t(i) * 2] = float(p.x);
            points[std::size_t(i) * 2 + 1] = float(p.y);
        }
        glNamedBufferSubData(hammersley.id(), 0, GLsizeiptr(points.size() * sizeof(float)), points.data());
        hammersleyCount = n;
    }

    void ensureScene(const SceneSettings& settings)
    {
        const bool wantsProcedural = settings.kind != SceneKind::Model;
        if (wantsProcedural && (!sceneBuilt || scene.kind != settings.kind ||
                                builtFor.countingSpheres != settings.countingSpheres)) {
            scene = buildProceduralScene(settings);
            sceneBuilt = true;
            builtFor = settings;
        }
        if (!sceneBuilt) {
            scene = buildProceduralScene(settings); // a model was asked for but none is loaded yet
            sceneBuilt = true;
            builtFor = settings;
        }
    }

    void bindIbl(const gl::ShaderProgram& p, const FrameSettings& settings) const
    {
        p.set("uEnvironmentYaw", glm::radians(settings.environment.yawDegrees));
        p.set("uEnvironmentIntensity", std::exp2(settings.environment.intensityEv));
        glBindTextureUnit(kUnitEquirect, equirect.id());
        if (!active) return;
        const bake::BakeResult& b = *active;
        glBindTextureUnit(kUnitEnvironmentCube, b.environmentCube.id());
        glBindTextureUnit(kUnitPrefiltered, b.prefiltered.id());
        const bake::BakedTexture& irradiance = b.irradianceCube();
        glBindTextureUnit(kUnitIrradianceCube, irradiance.id());
        const bake::BakedTexture& lut = b.lut(settings.sampling.geometry) ? b.lut(settings.sampling.geometry)
                                                                         : b.lut(GeometryTerm::SchlickGGX) ? b.lut(GeometryTerm::SchlickGGX)
                                                                                                           : b.lut(GeometryTerm::HeightCorrelatedSmith);
        glBindTextureUnit(kUnitBrdfLut, lut.id());
        std::array<glm::vec3, 9> sh{};
        // Plain or windowed SH9 is the settings' choice: the bake holds both and stays as it is.
        const SH9Color& shIrradiance = settings.sampling.diffuse == DiffuseSource::Sh9Plain ? b.sh.irradiance : b.sh.irradianceWindowed;
        for (std::size_t i = 0; i < 9; ++i) sh[i] = glm::vec3(shIrradiance.c[i]);
        glProgramUniform3fv(p.id(), p.uniformLocation("uShIrradiance"), 9, glm::value_ptr(sh[0]));
        p.set("uPrefilteredLevels", float(b.prefiltered.levels));
        p.set("uPrefilteredLayout", int(b.settings.prefilter.layout));
        p.set("uEnvironmentFaceSize", float(b.environmentCube.size));
        p.set("uEnvironmentLevels", float(b.environmentCube.levels));
        p.set("uGeometry", int(settings.sampling.geometry));
        const bool haveCube = bool(irradiance);
        p.set("uDiffuseSource", settings.sampling.diffuse == DiffuseSource::IrradianceCube && haveCube ? 1 : 0);
        p.set("uMultiscatter", int(settings.sampling.multiscatter));
        p.set("uRoughFresnelOnLut", int(settings.sampling.roughFresnelOnLut));
        p.set("uForcedMip", float(settings.sampling.forcedMip));
        p.set("uPdfMipFiltering", int(settings.sampling.pdfMipFiltering));
        p.set("uMipBias", settings.sampling.mipBias);
    }

    void drawDebugView(const FrameSettings& settings, int width, int height)
    {
        const std::vector<DebugTile> tiles = debugTiles(settings.view.mode, mipRoughnessOf(*active), width, height);
        const gl::ShaderProgram& p = shaders.program({"fullscreen.vert", "debug_views.frag"}, {{"VIEW", settings.view.mode == ViewMode::Lut ? "2" : "1"}});
        glUseProgram(p.id());
        bindIbl(p, settings);
        glBindTextureUnit(kUnitLutSchlick, active->lut(GeometryTerm::SchlickGGX).id());
        glBindTextureUnit(kUnitLutCorrelated, active->lut(GeometryTerm::HeightCorrelatedSmith).id());
        std::vector<glm::vec4> rects;
        for (const DebugTile& tile : tiles) rects.push_back(tile.rect);
        p.set("uTileCount", int(rects.size()));
        glProgramUniform4fv(p.id(), p.uniformLocation("uTiles"), GLsizei(rects.size()), glm::value_ptr(rects[0]));
        drawFullscreenTriangle();
    }

    void drawSky(const FrameSettings& settings, float aspect)
    {
        const glm::mat4 viewRotation = glm::mat4(glm::mat3(cameraView(settings.camera)));
        const glm::mat4 inverseViewProjection = glm::inverse(cameraProjection(settings.camera, aspect) * viewRotation);
        const gl::ShaderProgram& sky = shaders.program({"fullscreen.vert", "sky.frag"}, {{"AT_FAR_PLANE", "1"}});
        glUseProgram(sky.id());
        bindIbl(sky, settings);
        sky.set("uInverseViewProjection", inverseViewProjection);
        // Views of baked data fall back to the environment until a bake exists.
        int background = int(settings.view.background);
        if (!active && (background == int(BackgroundMode::Irradiance) || background == int(BackgroundMode::PrefilterMip))) background = 0;
        if (settings.view.mode == ViewMode::Irradiance && active) background = int(BackgroundMode::Irradiance);
        glm::vec3 solid = settings.view.solidColour;
        if (settings.view.mode == ViewMode::Furnace) {
            // The furnace's environment is uniform radiance 1 (times the intensity).
            background = int(BackgroundMode::SolidColour);
            solid = glm::vec3(std::exp2(settings.environment.intensityEv));
        }
        sky.set("uBackground", background);
        sky.set("uBackgroundMip", float(std::clamp(settings.view.backgroundMip, 0, active ? active->prefiltered.levels - 1 : 0)));
        sky.set("uSolidColour", solid);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LEQUAL);
        glDepthMask(GL_FALSE);
        drawFullscreenTriangle();
        glDepthMask(GL_TRUE);
        glDisable(GL_DEPTH_TEST);
    }

    void bindMaterial(const gl::ShaderProgram& p, const SceneDraw& draw, const FrameSettings& settings) const
    {
        const MaterialSettings& m = settings.material;
        PbrMaterial material = draw.material;
        const bool fromSliders = scene.kind != SceneKind::Model || m.overrideModel;
        if (fromSliders) {
            material.baseColorFactor = glm::vec4(m.baseColor, 1.0f);
            if (!draw.materialFromScene) {
                material.metallicFactor = m.metallic;
                material.roughnessFactor = m.roughness;
            }
        }
        p.set("uBaseColorFactor", material.baseColorFactor);
        p.set("uMetallicFactor", material.metallicFactor);
        p.set("uRoughnessFactor", material.roughnessFactor);
        p.set("uEmissiveFactor", material.emissiveFactor);
        p.set("uOcclusionStrength", material.occlusionStrength);
        p.set("uNormalScale", material.normalScale);
        p.set("uSpecular", m.specular);
        p.set("uAmbientOcclusion", m.ambientOcclusion);
        auto bindSlot = [&](const TextureRef& ref, TextureUnit unit, const char* flag) {
            const bool present = ref.valid() && std::size_t(ref.index) < scene.textures.size();
            p.set(flag, int(present));
            glBindTextureUnit(unit, present ? scene.textures[std::size_t(ref.index)].id() : 0);
        };
        bindSlot(material.baseColorTexture, kUnitBaseColor, "uHasBaseColorTexture");
        bindSlot(material.metallicRoughnessTexture, kUnitMetallicRoughness, "uHasMetallicRoughnessTexture");
        bindSlot(material.normalTexture, kUnitNormal, "uHasNormalTexture");
        bindSlot(material.occlusionTexture, kUnitOcclusion, "uHasOcclusionTexture");
        bindSlot(material.emissiveTexture, kUnitEmissive, "uHasEmissiveTexture");
        glProgramUniform4i(p.id(), p.uniformLocation("uTexCoordSets"), material.baseColorTexture.texCoord,
                           material.metallicRoughnessTexture.texCoord, material.normalTexture.texCoord, material.occlusionTexture.texCoord);
        p.set("uEmissiveTexCoordSet", material.emissiveTexture.texCoord);
    }

    // What the mesh pass writes: shaded radiance, or the reference renderer's G-buffer.
    enum class MeshOutput { Shaded, GBuffer };

    void drawScene(const FrameSettings& settings, float aspect, glm::vec2 sampleRotation, MeshOutput output = MeshOutput::Shaded)
    {
        if (!active) return;
        ensureScene(settings.scene);
        const bool rotating = !keepsExactSampleCount(settings);
        if (!rotating) sampleRotation = glm::vec2(0.0f);
        const glm::mat4 viewProjection = cameraProjection(settings.camera, aspect) * cameraView(settings.camera);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
        glBindBufferBase(GL_UNIFORM_BUFFER, 0, hammersley.id());
        const bool gbufferPass = output == MeshOutput::GBuffer;
        // Per program: the IBL and camera state once; per draw only what differs. The
        // G-buffer has one program for every draw (the first round takes them all).
        for (const bool sampled : {false, true}) {
            const gl::ShaderProgram* p = nullptr;
            for (const SceneDraw& draw : scene.draws) {
                if (gbufferPass && sampled) break;
                if (!gbufferPass && (draw.forceSampled || settings.sampling.method == ShadingMethod::Sampled) != sampled) continue;
                if (!p) {
                    sampledDraws = sampledDraws || (sampled && !gbufferPass && rotating);
                    p = &shaders.program({"mesh.vert", "pbr.frag"}, {{"METHOD", gbufferPass ? "2" : sampled ? "1" : "0"}});
                    glUseProgram(p->id());
                    bindIbl(*p, settings);
                    p->set("uViewProjection", viewProjection);
                    p->set("uCameraPosition", cameraPosition(settings.camera));
                    p->set("uSampleRotation", sampleRotation);
                    p->set("uNormalizeByAccepted", int(settings.sampling.normalizeByAccepted));
                    p->set("uCosineSampledDiffuse", int(settings.sampling.cosineSampledDiffuse));
                }
                p->set("uModel", draw.model);
                p->set("uNormalMatrix", glm::transpose(glm::inverse(glm::mat3(draw.model))));
                bindMaterial(*p, draw, settings);
                if (sampled && !gbufferPass) {
                    const int n = std::clamp(draw.sampleCount > 0 ? draw.sampleCount : settings.sampling.samples, 1, kMaxSampleCount);
                    ensureHammersley(n);
                    p->set("uSampleCount", n);
                }
                scene.meshes[std::size_t(draw.mesh)].draw();
            }
        }
        glDisable(GL_DEPTH_TEST);
    }

    // Everything the reference image depends on: not the tone map, the view's error and
    // split controls, nor the estimators' sampling (only the BRDF's geometry term and the
    // energy compensation are part of the shading model it shares), nor the frame's MSAA
    // (the reference shades pixel centres, single-sampled).
    FrameKey referenceKeyFor(const FrameSettings& settings, int width, int height) const
    {
        FrameSettings s = settings;
        s.toneMap = {};
        SamplingSettings model;
        model.geometry = settings.sampling.geometry;
        model.multiscatter = settings.sampling.multiscatter;
        s.sampling = model;
        s.view.mode = ViewMode::Error;
        s.view.errorSpace = {};
        s.view.errorScale = {};
        s.view.split = false;
        s.view.splitPosition = {};
        s.view.compare = {};
        s.view.msaaSamples = 1;
        return {std::move(s), width, height, referenceRevision};
    }

    const ImageRGB32F& referenceEnvironmentOfWidth(int width)
    {
        const std::pair<int, int> wanted{environmentGeneration, width};
        if (referenceEnvironmentFor != wanted) {
            referenceEnvironment = downsampleEquirectToWidth(environmentSource, std::max(width, 2));
            referenceEnvironmentFor = wanted;
        }
        return referenceEnvironment;
    }

    FrameReadback readTexture(GLuint texture, int width, int height) const
    {
        FrameReadback result{width, height, {}};
        result.rgba.resize(std::size_t(width) * std::size_t(height) * 4);
        glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, GLsizei(result.rgba.size() * sizeof(float)), result.rgba.data());
        return result;
    }

    std::vector<std::uint8_t> readCoverage() const
    {
        const FrameReadback normal = readTexture(gbuffer.texture(ReferenceLayer::Normal), gbuffer.width(), gbuffer.height());
        std::vector<std::uint8_t> coverage(normal.rgba.size() / 4);
        for (std::size_t i = 0; i < coverage.size(); ++i) coverage[i] = normal.rgba[i * 4 + 3] != 0.0f;
        return coverage;
    }

    // The mesh pass into the G-buffer, then a fresh integral over the environment.
    void startReference(const FrameSettings& settings, int width, int height, const ReferenceSlicing& slicing, FrameKey key)
    {
        gbuffer.ensure(width, height);
        gbuffer.bindCleared();
        glDisable(GL_BLEND);
        glDisable(GL_SCISSOR_TEST);
        drawScene(settings, float(width) / float(height), glm::vec2(0.0f), MeshOutput::GBuffer);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        reference.start(referenceEnvironmentOfWidth(settings.view.referenceWidth), width, height, readCoverage(), slicing);
        referenceKey = std::move(key);
        referenceSlicing = slicing;
        referenceGeometry = settings.sampling.geometry;
        referenceResolved = false;
    }

    // The environment behind, through the frame's own sky pass; the surfaces from the sums.
    void resolveReference(const FrameSettings& settings)
    {
        const int width = gbuffer.width(), height = gbuffer.height();
        referenceFrame.ensure(GL_RGBA32F, width, height, /*withDepth=*/true);
        glBindFramebuffer(GL_FRAMEBUFFER, referenceFrame.framebuffer());
        glViewport(0, 0, width, height);
        glClear(GL_DEPTH_BUFFER_BIT);
        glDisable(GL_BLEND);
        glDisable(GL_SCISSOR_TEST);
        drawSky(settings, float(width) / float(height));
        const gl::ShaderProgram& p = shaders.program({"fullscreen.vert", "reference_resolve.frag"});
        glUseProgram(p.id());
        bindIbl(p, settings);
        for (int layer = 0; layer < int(ReferenceLayer::Count); ++layer)
            glBindTextureUnit(kUnitGNormal + GLuint(layer), gbuffer.texture(ReferenceLayer(layer)));
        glBindTextureUnit(kUnitSpecularSum, reference.specularSum());
        glBindTextureUnit(kUnitIrradianceSum, reference.irradianceSum());
        drawFullscreenTriangle();
        glUseProgram(0);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        referenceResolved = true;
    }

    bool referenceReadyFor(const std::optional<FrameKey>& key) const { return referenceResolved && key && key == referenceKey; }

    // ViewMode::Error's last pass, in place of the tone mapper.
    void drawErrorView(const FrameSettings& settings)
    {
        const gl::ShaderProgram& p = shaders.program({"fullscreen.vert", "error_view.frag"});
        glUseProgram(p.id());
        p.set("uExposureEv", settings.toneMap.exposureEv);
        p.set("uToneMapOperator", int(settings.toneMap.op));
        p.set("uDisplaySpace", int(settings.view.errorSpace == ErrorSpace::Display));
        p.set("uErrorScale", std::max(settings.view.errorScale, 1e-6f));
        glBindTextureUnit(kUnitHdrFrame, resolved->texture());
        glBindTextureUnit(kUnitReferenceFrame, referenceFrame.texture());
        glBindTextureUnit(kUnitGNormal, gbuffer.texture(ReferenceLayer::Normal));
        drawFullscreenTriangle();
    }
};

// The divider is a pixel column; positions are clamped so that both sides can be empty.
int splitColumn(const ViewSettings& view, int width)
{
    return std::clamp(int(std::lround(double(view.splitPosition) * double(width))), 0, width);
}

Renderer::Renderer(std::filesystem::path shaderDirectory) : impl_(std::make_unique<Impl>(std::move(shaderDirectory))) {}
Renderer::~Renderer() = default;

void Renderer::setEnvironment(const ImageRGB32F& image)
{
    impl_->environmentSource = image;
    ++impl_->environmentGeneration;
    ++impl_->referenceRevision;
    ++impl_->contentRevision;
    // Repeat in u (longitude wraps), clamp in v (the poles do not).
    impl_->equirect = gl::createMipmappedTexture2D(
        {GL_RGB32F, image.width, image.height, GL_RGB, GL_FLOAT, image.texels.data(), 4, GL_REPEAT, GL_CLAMP_TO_EDGE});
}

void Renderer::setBake(std::shared_ptr<const bake::BakeResult> bake)
{
    impl_->bake = std::move(bake);
    ++impl_->contentRevision;
}
void Renderer::setFurnaceBake(std::shared_ptr<const bake::BakeResult> bake)
{
    impl_->furnaceBake = std::move(bake);
    ++impl_->contentRevision;
}
std::uint64_t Renderer::contentRevision() const { return impl_->contentRevision; }
bool Renderer::hasFurnaceBake() const { return bool(impl_->furnaceBake); }

std::vector<SphereReading> Renderer::measureSpheres(const FrameSettings& settings) const
{
    const Impl& r = *impl_;
    std::vector<SphereReading> readings;
    if (r.scene.kind == SceneKind::Model || r.hdrFrame.width() == 0) return readings;
    const FrameReadback frame = readHdrFrame();
    const glm::mat4 view = cameraView(settings.camera);
    const glm::mat4 projection = cameraProjection(settings.camera, float(frame.width) / float(frame.height));
    for (const SceneDraw& draw : r.scene.draws) {
        // The unit sphere's centre and apparent radius in pixels; readings average the
        // inner half of the disc, where n.v > 0.87: the near-normal reflectance.
        const glm::vec3 centreView = glm::vec3(view * draw.model[3]);
        const glm::vec4 clip = projection * glm::vec4(centreView, 1.0f);
        const glm::vec2 pixel = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(frame.width, frame.height);
        const float radiusPixels = projection[1][1] / -centreView.z * 0.5f * float(frame.height);
        const float reach = 0.5f * radiusPixels;
        glm::dvec3 sum(0.0);
        int count = 0;
        for (int y = int(pixel.y - reach); y <= int(pixel.y + reach); ++y)
            for (int x = int(pixel.x - reach); x <= int(pixel.x + reach); ++x) {
                if (x < 0 || y < 0 || x >= frame.width || y >= frame.height) continue;
                if (glm::length(glm::vec2(x + 0.5f, y + 0.5f) - pixel) > reach) continue;
                const float* p = &frame.rgba[(std::size_t(y) * std::size_t(frame.width) + std::size_t(x)) * 4];
                sum += glm::dvec3(p[0], p[1], p[2]);
                ++count;
            }
        if (count == 0) continue;
        const glm::vec3 mean = glm::vec3(sum / double(count));
        readings.push_back({pixel, mean, draw.materialFromScene ? draw.material.metallicFactor : settings.material.metallic,
                            draw.materialFromScene ? draw.material.roughnessFactor : settings.material.roughness});
    }
    return readings;
}
bool Renderer::hasBake() const { return bool(impl_->bake); }

void Renderer::setModel(const ModelData& model, const std::string& path)
{
    impl_->scene = buildModelScene(model, path);
    ++impl_->referenceRevision;
    ++impl_->contentRevision;
    impl_->sceneBuilt = true;
    impl_->builtFor.kind = SceneKind::Model;
}

SceneInfo Renderer::sceneInfo(const FrameSettings& settings)
{
    impl_->ensureScene(settings.scene);
    const GpuScene& scene = impl_->scene;
    return {scene.draws.size(), scene.gpuBytes, scene.bounds.center(), glm::max(0.5f * scene.bounds.size(), glm::vec3(1e-3f))};
}

// The n-th point of the R2 sequence (Roberts 2018): a low-discrepancy sequence of
// Cranley-Patterson rotations, so frame n's sample set fills the gaps of frames 0..n-1.
static glm::vec2 r2Rotation(int n)
{
    constexpr double g = 1.32471795724474602596; // the plastic number
    return glm::vec2(float(std::fmod(double(n) / g, 1.0)), float(std::fmod(double(n) / (g * g), 1.0)));
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
    const bool accumulate = options.accumulate && !(keepsExactSampleCount(settings) &&
                                                    (!settings.view.split || keepsExactSampleCount(compareSide(settings))));
    FrameKey key{settings, width, height, r.contentRevision};
    if (!accumulate || key != r.accumulationKey) r.accumulatedFrames = 0;
    r.accumulationKey = accumulate ? std::optional<FrameKey>(std::move(key)) : std::nullopt;
    const glm::vec2 rotation = r.accumulatedFrames == 0 ? glm::vec2(0.0f) : r2Rotation(r.accumulatedFrames);

    r.active = settings.view.mode == ViewMode::Furnace ? r.furnaceBake.get() : r.bake.get();
    r.sampledDraws = false;
    const bool debugView = r.active && (settings.view.mode == ViewMode::PrefilterMips || settings.view.mode == ViewMode::Lut);
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
        r.drawDebugView(settings, width, height);
    } else {
        // Meshes first, then the sky behind them: llvmpipe shades only the uncovered pixels.
        r.drawScene(settings, aspect, rotation);
        r.drawSky(settings, aspect);
        if (settings.view.split) {
            // B over the right part: the same passes with the other sampling settings,
            // confined by the scissor (which the depth clear respects too).
            const FrameSettings b = compareSide(settings);
            const int x0 = splitColumn(settings.view, width);
            glEnable(GL_SCISSOR_TEST);
            glScissor(x0, 0, width - x0, height);
            glClear(GL_DEPTH_BUFFER_BIT);
            r.drawScene(b, aspect, rotation);
            r.drawSky(b, aspect);
            glDisable(GL_SCISSOR_TEST);
        }
    }
    if (multisampled) r.msaaFrame.resolveInto(r.hdrFrame);
    r.frameKey = r.referenceKeyFor(settings, width, height);

    r.resolved = &r.hdrFrame;
    if (accumulate) {
        r.accumulation.ensure(GL_RGBA32F, width, height);
        glBindFramebuffer(GL_FRAMEBUFFER, r.accumulation.framebuffer());
        const gl::ShaderProgram& program = r.shaders.program({"fullscreen.vert", "accumulate.frag"});
        glUseProgram(program.id());
        glBindTextureUnit(kUnitHdrFrame, r.hdrFrame.texture());
        glEnable(GL_BLEND);
        // Radiance into the running mean; coverage replaced, because a blend of equal
        // coverages is not always bit-exact and "fully covered" means exactly 1.
        glBlendFuncSeparate(GL_CONSTANT_ALPHA, GL_ONE_MINUS_CONSTANT_ALPHA, GL_ONE, GL_ZERO);
        glBlendColor(0.0f, 0.0f, 0.0f, 1.0f / float(r.accumulatedFrames + 1));
        r.drawFullscreenTriangle();
        glDisable(GL_BLEND);
        r.resolved = &r.accumulation;
    }
    r.accumulatedFrames = accumulate ? r.accumulatedFrames + 1 : 1;

    glBindFramebuffer(GL_FRAMEBUFFER, r.displayFrame.framebuffer());
    if (settings.view.mode == ViewMode::Error && r.referenceReadyFor(r.frameKey)) {
        r.drawErrorView(settings);
        glUseProgram(0);
        glBindVertexArray(0);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        return;
    }
    const gl::ShaderProgram& tonemap = r.shaders.program({"fullscreen.vert", "tonemap.frag"});
    glUseProgram(tonemap.id());
    // The LUT view shows data in [0, 1]: no exposure and no tone curve, just the display encoding.
    const bool lutView = debugView && settings.view.mode == ViewMode::Lut;
    tonemap.set("uExposureEv", lutView ? 0.0f : settings.toneMap.exposureEv);
    tonemap.set("uToneMapOperator", int(lutView ? ToneMapOperator::None : settings.toneMap.op));
    glBindTextureUnit(kUnitHdrFrame, r.resolved->texture());
    r.drawFullscreenTriangle();

    glUseProgram(0);
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

ReferenceStatus Renderer::advanceReference(const FrameSettings& settings, int width, int height, std::chrono::steady_clock::duration budget,
                                           const ReferenceSlicing& slicing)
{
    Impl& r = *impl_;
    if (!r.bake || r.environmentSource.empty()) return {};
    r.active = r.bake.get();
    FrameKey key = r.referenceKeyFor(settings, width, height);
    if (key != r.referenceKey || slicing != r.referenceSlicing) r.startReference(settings, width, height, slicing, std::move(key));
    const auto start = std::chrono::steady_clock::now();
    while (!r.reference.complete() && std::chrono::steady_clock::now() - start < budget) {
        r.reference.runSlice(r.shaders, r.gbuffer, r.referenceGeometry);
        glFinish();
    }
    if (r.reference.complete() && !r.referenceResolved) r.resolveReference(settings);
    return referenceStatus(settings, width, height);
}

ReferenceStatus Renderer::referenceStatus(const FrameSettings& settings, int width, int height) const
{
    const Impl& r = *impl_;
    ReferenceStatus status;
    status.current = r.referenceKey == r.referenceKeyFor(settings, width, height);
    if (!status.current) return status;
    status.complete = r.referenceResolved;
    status.progress = r.reference.progress();
    status.environmentWidth = r.reference.environmentWidth();
    status.environmentHeight = r.reference.environmentHeight();
    status.texelDegrees = 360.0 / double(std::max(status.environmentWidth, 1));
    status.minResolvedRoughness = referenceMinResolvedRoughness(status.environmentWidth);
    return status;
}

FrameReadback Renderer::readReferenceFrame() const
{
    const Impl& r = *impl_;
    if (!r.referenceResolved) return {};
    return r.readTexture(r.referenceFrame.texture(), r.referenceFrame.width(), r.referenceFrame.height());
}

FrameReadback Renderer::readReferenceLayer(ReferenceLayer layer) const
{
    const Impl& r = *impl_;
    if (r.gbuffer.width() == 0) return {};
    return r.readTexture(r.gbuffer.texture(layer), r.gbuffer.width(), r.gbuffer.height());
}

ErrorReport Renderer::measureError(const FrameSettings& settings) const
{
    const Impl& r = *impl_;
    ErrorReport report;
    if (!r.referenceReadyFor(r.frameKey)) return report;
    FrameReadback frame = readHdrFrame();
    FrameReadback reference = readReferenceFrame();
    if (settings.view.errorSpace == ErrorSpace::Display) {
        for (FrameReadback* image : {&frame, &reference})
            for (std::size_t i = 0; i < image->rgba.size(); i += 4) {
                const glm::vec3 shown = displayEncode(glm::vec3(image->rgba[i], image->rgba[i + 1], image->rgba[i + 2]), settings.toneMap.exposureEv,
                                                      settings.toneMap.op);
                for (int c = 0; c < 3; ++c) image->rgba[i + std::size_t(c)] = shown[c];
            }
    }
    const FrameReadback normals = readReferenceLayer(ReferenceLayer::Normal);
    const int x0 = settings.view.split ? splitColumn(settings.view, frame.width) : frame.width;
    auto side = [&](bool right) {
        std::vector<std::uint8_t> include(frame.rgba.size() / 4);
        for (std::size_t i = 0; i < include.size(); ++i)
            include[i] = isMeasuredPixel(frame.rgba[i * 4 + 3], normals.rgba[i * 4 + 3]) && ((int(i % std::size_t(frame.width)) >= x0) == right);
        return computeErrorMetrics(frame.rgba, reference.rgba, include);
    };
    report.valid = true;
    report.left = side(false);
    if (settings.view.split) report.right = side(true);
    return report;
}

int Renderer::accumulatedFrames() const { return impl_->accumulatedFrames; }
int Renderer::frameSamples() const { return impl_->frameSamples; }
bool Renderer::lastFrameWasSampled() const { return impl_->sampledDraws; }

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
    FrameReadback result{hdr.width(), hdr.height(), {}};
    result.rgba.resize(std::size_t(hdr.width()) * std::size_t(hdr.height()) * 4);
    glGetTextureImage(hdr.texture(), 0, GL_RGBA, GL_FLOAT, GLsizei(result.rgba.size() * sizeof(float)), result.rgba.data());
    return result;
}

DisplayReadback Renderer::readDisplayImage() const
{
    const gl::RenderTarget& display = impl_->displayFrame;
    DisplayReadback result{display.width(), display.height(), {}};
    result.rgba.resize(std::size_t(display.width()) * std::size_t(display.height()) * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(display.texture(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(result.rgba.size()), result.rgba.data());
    return result;
}

std::vector<ScreenLabel> Renderer::sceneLabels(const FrameSettings& settings, int width, int height) const
{
    std::vector<ScreenLabel> labels;
    const glm::mat4 viewProjection = cameraProjection(settings.camera, float(width) / float(height)) * cameraView(settings.camera);
    for (const GridLabel& label : impl_->scene.labels) {
        const glm::vec4 clip = viewProjection * glm::vec4(label.position, 1.0f);
        if (clip.w <= 0.0f) continue; // behind the camera
        const glm::vec2 pixel = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(width, height);
        labels.push_back({pixel, label.text, label.axisTitle});
    }
    return labels;
}

std::vector<float> Renderer::prefilterMipRoughness() const { return impl_->bake ? mipRoughnessOf(*impl_->bake) : std::vector<float>{}; }

TexelProbe Renderer::probe(const FrameSettings& settings, int width, int height, float x, float y) const
{
    const Impl& r = *impl_;
    if (!r.bake) return {};
    const std::vector<DebugTile> tiles = debugTiles(settings.view.mode, mipRoughnessOf(*r.bake), width, height);
    const int t = debugTileAt(tiles, x, y);
    if (t < 0) return {};
    const DebugTile& tile = tiles[std::size_t(t)];
    const glm::vec2 local = (glm::vec2(x, y) - glm::vec2(tile.rect)) / (glm::vec2(tile.rect.z, tile.rect.w) - glm::vec2(tile.rect));
    glm::vec4 texel(0.0f);
    char text[256];
    if (settings.view.mode == ViewMode::PrefilterMips) {
        const glm::vec2 cell = local * glm::vec2(4.0f, 3.0f);
        const int face = crossFace(int(cell.x), int(cell.y));
        if (face < 0) return {};
        const int size = r.bake->prefiltered.levelSize(tile.index);
        const int column = std::min(int(glm::fract(cell.x) * float(size)), size - 1);
        const int row = std::min(int((1.0f - glm::fract(cell.y)) * float(size)), size - 1); // t = 0 at the top of the cell
        glGetTextureSubImage(r.bake->prefiltered.id(), tile.index, column, row, face, 1, 1, 1, GL_RGBA, GL_FLOAT, sizeof texel, &texel.x);
        std::snprintf(text, sizeof text, "%s, face %s, texel (%d, %d) of %d: %.4g %.4g %.4g", tile.label.c_str(), kFaceNames[face], column, row,
                      size, texel.r, texel.g, texel.b);
    } else {
        const bake::BakedTexture& lut = r.bake->lut(GeometryTerm(tile.index));
        if (!lut) return {};
        const int column = std::min(int(local.x * float(lut.size)), lut.size - 1);
        const int row = std::min(int(local.y * float(lut.size)), lut.size - 1);
        glGetTextureSubImage(lut.id(), 0, column, row, 0, 1, 1, 1, GL_RGBA, GL_FLOAT, sizeof texel, &texel.x);
        std::snprintf(text, sizeof text, "n.v %.3f, roughness %.3f: A %.4f, B %.4f, A+B %.4f", (column + 0.5f) / float(lut.size),
                      (row + 0.5f) / float(lut.size), texel.r, texel.g, texel.b);
    }
    return {true, text};
}

gl::ShaderLibrary& Renderer::shaders() { return impl_->shaders; }
std::vector<std::string> Renderer::reloadShaders() { return impl_->shaders.reloadChanged(); }

} // namespace iblab
