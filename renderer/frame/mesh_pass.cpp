#include "frame/mesh_pass.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "frame/camera.hpp"
#include "frame/shading_lights_texture.hpp"
#include "frame/texture_units.hpp"
#include "ibl/sampling.hpp"
#include "ibl/specular_approximations.hpp"

namespace iblab {

namespace {

struct MeshUniforms {
    explicit MeshUniforms(const gl::ShaderProgram& p);
    IblUniforms ibl;
    gl::Uniform<glm::mat4> viewProjection;
    gl::Uniform<glm::vec3> cameraPosition;
    gl::Uniform<glm::vec2> sampleRotation;
    gl::Uniform<bool> normalizeByAccepted;
    gl::Uniform<bool> cosineSampledDiffuse;
    gl::Uniform<int> sampleCount;
    gl::Uniform<int> shadingLightCount;
    gl::UniformArray<glm::vec3> shadingLightDirection;
    gl::UniformArray<glm::vec3> shadingLightFlux;
    gl::Uniform<float> shadingLightMinAlpha;
    gl::Uniform<glm::mat4> model;
    gl::Uniform<glm::mat3> normalMatrix;
    // The material's factors and texture slots (glTF's).
    gl::Uniform<glm::vec4> baseColorFactor;
    gl::Uniform<float> metallicFactor;
    gl::Uniform<float> roughnessFactor;
    gl::Uniform<glm::vec3> emissiveFactor;
    gl::Uniform<float> occlusionStrength;
    gl::Uniform<float> normalScale;
    gl::Uniform<float> specular;
    gl::Uniform<float> ambientOcclusion;
    gl::Uniform<bool> hasBaseColorTexture;
    gl::Uniform<bool> hasMetallicRoughnessTexture;
    gl::Uniform<bool> hasNormalTexture;
    gl::Uniform<bool> hasOcclusionTexture;
    gl::Uniform<bool> hasEmissiveTexture;
    gl::Uniform<glm::ivec4> texCoordSets;
    gl::Uniform<int> emissiveTexCoordSet;
};

MeshUniforms::MeshUniforms(const gl::ShaderProgram& p)
    : ibl(p), viewProjection(p, "uViewProjection"), cameraPosition(p, "uCameraPosition"), sampleRotation(p, "uSampleRotation"),
      normalizeByAccepted(p, "uNormalizeByAccepted"), cosineSampledDiffuse(p, "uCosineSampledDiffuse"), sampleCount(p, "uSampleCount"),
      shadingLightCount(p, "uShadingLightCount"), shadingLightDirection(p, "uShadingLightDirection"),
      shadingLightFlux(p, "uShadingLightFlux"), shadingLightMinAlpha(p, "uShadingLightMinAlpha"), model(p, "uModel"), normalMatrix(p, "uNormalMatrix"),
      baseColorFactor(p, "uBaseColorFactor"), metallicFactor(p, "uMetallicFactor"),
      roughnessFactor(p, "uRoughnessFactor"), emissiveFactor(p, "uEmissiveFactor"), occlusionStrength(p, "uOcclusionStrength"),
      normalScale(p, "uNormalScale"), specular(p, "uSpecular"), ambientOcclusion(p, "uAmbientOcclusion"),
      hasBaseColorTexture(p, "uHasBaseColorTexture"), hasMetallicRoughnessTexture(p, "uHasMetallicRoughnessTexture"),
      hasNormalTexture(p, "uHasNormalTexture"), hasOcclusionTexture(p, "uHasOcclusionTexture"), hasEmissiveTexture(p, "uHasEmissiveTexture"),
      texCoordSets(p, "uTexCoordSets"), emissiveTexCoordSet(p, "uEmissiveTexCoordSet")
{
}

void bindMaterial(const MeshUniforms& u, const GpuScene& scene, const SceneDraw& draw, const MaterialSettings& sliders)
{
    PbrMaterial material = draw.material;
    // Procedural scenes take the sliders' material (the grid keeps its own metallic and
    // roughness); a model keeps its own unless the sliders override it.
    if (scene.kind != SceneKind::Model || sliders.overrideModel) {
        material.baseColorFactor = glm::vec4(sliders.baseColor, 1.0f);
        if (!draw.materialFromScene) {
            material.metallicFactor = sliders.metallic;
            material.roughnessFactor = sliders.roughness;
        }
    }
    u.baseColorFactor.set(material.baseColorFactor);
    u.metallicFactor.set(material.metallicFactor);
    u.roughnessFactor.set(material.roughnessFactor);
    u.emissiveFactor.set(material.emissiveFactor);
    u.occlusionStrength.set(material.occlusionStrength);
    u.normalScale.set(material.normalScale);
    u.specular.set(sliders.specular);
    u.ambientOcclusion.set(sliders.ambientOcclusion);
    auto bindSlot = [&](const TextureRef& ref, TextureUnit unit, const gl::Uniform<bool>& present) {
        const bool valid = ref.valid() && std::size_t(ref.index) < scene.textures.size();
        present.set(valid);
        glBindTextureUnit(unit, valid ? scene.textures[std::size_t(ref.index)].id() : 0);
    };
    bindSlot(material.baseColorTexture, kUnitBaseColor, u.hasBaseColorTexture);
    bindSlot(material.metallicRoughnessTexture, kUnitMetallicRoughness, u.hasMetallicRoughnessTexture);
    bindSlot(material.normalTexture, kUnitNormal, u.hasNormalTexture);
    bindSlot(material.occlusionTexture, kUnitOcclusion, u.hasOcclusionTexture);
    bindSlot(material.emissiveTexture, kUnitEmissive, u.hasEmissiveTexture);
    u.texCoordSets.set(glm::ivec4(material.baseColorTexture.texCoord, material.metallicRoughnessTexture.texCoord, material.normalTexture.texCoord,
                                  material.occlusionTexture.texCoord));
    u.emissiveTexCoordSet.set(material.emissiveTexture.texCoord);
}

// The table as the CPU core samples it (LobeFitTable::sample): bilinear between texel
// centres, clamped to the edge texels; its planes stacked along y (lobeFitPlaneY).
gl::Texture uploadLobeFit(const LobeFitTable& table)
{
    gl::Texture texture = gl::createTexture(GL_TEXTURE_2D);
    const int rows = table.roughnessSize * table.planes();
    glTextureStorage2D(texture.id(), 1, GL_RGBA32F, table.nvSize, rows);
    glTextureSubImage2D(texture.id(), 0, 0, 0, table.nvSize, rows, GL_RGBA, GL_FLOAT, table.cells.data());
    glTextureParameteri(texture.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(texture.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return texture;
}

// The fitted lobe's lights, with the cubes and SH9 less them in the prefiltered and
// irradiance units and the SH9 uniform (IblUniforms bound the bake's own there); none where
// the method does not sum them or the bake has none.
void bindShadingLights(const MeshUniforms& u, const Lighting& lighting, const FrameSettings& settings, bool wanted)
{
    const ShadingLightsTexture* lights = wanted ? lighting.shadingLights : nullptr;
    u.shadingLightCount.set(lights ? int(lights->lights.size()) : 0);
    if (!lights) return;
    std::vector<glm::vec3> directions, flux;
    for (const ShadingLight& light : lights->lights) directions.push_back(light.direction), flux.push_back(light.flux);
    u.shadingLightDirection.set(directions);
    u.shadingLightFlux.set(flux);
    u.shadingLightMinAlpha.set(lights->minAlpha);
    glBindTextureUnit(kUnitPrefiltered, lights->residual.id());
    if (lights->residualIrradiance) glBindTextureUnit(kUnitIrradianceCube, lights->residualIrradiance.id());
    const SH9Color& sh = settings.sampling.diffuse == DiffuseSource::Sh9Plain ? lights->shResidual : lights->shResidualWindowed;
    std::vector<glm::vec3> coefficients;
    for (const glm::dvec3& c : sh.c) coefficients.emplace_back(c);
    u.ibl.shIrradiance.set(coefficients);
}

} // namespace

MeshPass::MeshPass(gl::ShaderLibrary& shaders)
    : shaders_(shaders), lobeFit_(uploadLobeFit(fittedLobeTable())), lobeFitLayout_(fittedLobeTable().taps)
{
    glNamedBufferStorage(hammersley_.id(), kMaxSampleCount * sizeof(float) * 2, nullptr, GL_DYNAMIC_STORAGE_BIT);
}

// The first n Hammersley points, uploaded only when N changes (std140 packs two per vec4).
void MeshPass::ensureHammersley(int n)
{
    if (n == hammersleyCount_) return;
    std::vector<float> points(std::size_t(n) * 2);
    for (int i = 0; i < n; ++i) {
        const glm::dvec2 p = hammersley(std::uint32_t(i), std::uint32_t(n));
        points[std::size_t(i) * 2] = float(p.x);
        points[std::size_t(i) * 2 + 1] = float(p.y);
    }
    glNamedBufferSubData(hammersley_.id(), 0, GLsizeiptr(points.size() * sizeof(float)), points.data());
    hammersleyCount_ = n;
}

bool MeshPass::draw(SceneSlot& sceneSlot, const FrameSettings& settings, const Lighting& lighting, float aspect, glm::vec2 sampleRotation,
                    Output output)
{
    if (!lighting.bake) return false;
    const GpuScene& scene = sceneSlot.ensure(settings.scene);
    const bool rotating = !keepsExactSampleCount(settings);
    if (!rotating) sampleRotation = glm::vec2(0.0f);
    // The depth range follows the scene: a fixed far plane hid models measured in hundreds of units.
    const ClipPlanes planes = clipPlanesFor(settings.camera, scene.bounds.center(), scene.bounds.radius());
    const glm::mat4 viewProjection = cameraProjection(settings.camera, aspect, planes) * cameraView(settings.camera);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, hammersley_.id());
    const bool gbuffer = output == Output::GBuffer;
    bool sampledDraws = false;
    // Per program: the IBL and camera state once; per draw only what differs. The
    // G-buffer has one program for every draw (the first round takes them all).
    for (const bool sampled : {false, true}) {
        if (gbuffer && sampled) break;
        const int method = gbuffer ? 2 : sampled ? 1 : 0;
        const MeshUniforms* u = nullptr;
        for (const SceneDraw& draw : scene.draws) {
            if (!gbuffer && (draw.forceSampled || settings.sampling.method == ShadingMethod::Sampled) != sampled) continue;
            if (!u) {
                sampledDraws = sampledDraws || (sampled && rotating);
                // What the settings choose between is compiled in (ibl_lighting.glsl says why);
                // the G-buffer shades nothing, so one program serves every choice.
                gl::ShaderDefines defines{{"METHOD", std::to_string(method)}};
                if (!gbuffer) {
                    const bool fittedLobe = !sampled && settings.sampling.method == ShadingMethod::FittedLobe;
                    defines.push_back({"FITTED_LOBE", fittedLobe ? "1" : "0"});
                    if (fittedLobe) {
                        defines.push_back({"LOBE_FIT_LAYOUT", std::to_string(lobeFitLayout_)});
                        // Each light evaluates the visibility term; a uniform's choice would
                        // evaluate both.
                        defines.push_back({"SHADING_LIGHTS_GEOMETRY", std::to_string(int(settings.sampling.geometry))});
                    }
                    defines.push_back(diffuseSourceDefine(lighting, settings));
                }
                const gl::ShaderProgram& program = shaders_.program({"mesh.vert", "pbr.frag"}, defines);
                u = &program.uniforms<MeshUniforms>();
                glUseProgram(program.id());
                u->ibl.bind(lighting, settings);
                u->viewProjection.set(viewProjection);
                u->cameraPosition.set(cameraPosition(settings.camera));
                u->sampleRotation.set(sampleRotation);
                u->normalizeByAccepted.set(settings.sampling.normalizeByAccepted);
                u->cosineSampledDiffuse.set(settings.sampling.cosineSampledDiffuse);
                glBindTextureUnit(kUnitLobeFit, lobeFit_.id());
                bindShadingLights(*u, lighting, settings, !gbuffer && !sampled && settings.sampling.method == ShadingMethod::FittedLobe && settings.sampling.shadingLights);
            }
            u->model.set(draw.model);
            u->normalMatrix.set(glm::transpose(glm::inverse(glm::mat3(draw.model))));
            bindMaterial(*u, scene, draw, settings.material);
            if (sampled) {
                const int n = std::clamp(draw.sampleCount > 0 ? draw.sampleCount : settings.sampling.samples, 1, kMaxSampleCount);
                ensureHammersley(n);
                u->sampleCount.set(n);
            }
            scene.meshes[std::size_t(draw.mesh)].draw();
        }
    }
    glDisable(GL_DEPTH_TEST);
    return sampledDraws;
}

} // namespace iblab
