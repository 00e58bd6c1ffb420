#include "frame/shading_lights_texture.hpp"

#include <chrono>

#include "bake/bake_result.hpp"
#include "bake/bake_settings.hpp"
#include "bake/residual_irradiance.hpp"
#include "gl/handles.hpp"
#include "gl/shader_library.hpp"
#include "gl/uniform.hpp"

namespace iblab {

namespace {

constexpr const char* kResidualShader = "shading_lights_residual.comp";

struct ResidualUniforms {
    explicit ResidualUniforms(const gl::ShaderProgram& p)
        : size(p, "uSize"), alpha2(p, "uAlpha2"), scale(p, "uScale"), cosNear(p, "uCosNear"), groups(p, "uGroups")
    {
    }
    gl::Uniform<int> size;
    gl::Uniform<float> alpha2;
    gl::Uniform<float> scale;
    gl::Uniform<float> cosNear;
    gl::Uniform<int> groups;
};

// shading_lights_residual.comp's buffer: per group (centroid, index of its first point),
// (flux, point count); then every point as (direction, 0), (flux, 0).
std::vector<glm::vec4> residualShaderData(const ShadingLights& lights)
{
    std::vector<glm::vec4> data;
    std::size_t nextPoint = 2 * lights.groups.size();
    for (const ShadingLightGroup& g : lights.groups) {
        data.emplace_back(g.light.direction, float(nextPoint));
        data.emplace_back(g.light.flux, float(g.points.size()));
        nextPoint += 2 * g.points.size();
    }
    for (const ShadingLightGroup& g : lights.groups)
        for (const ShadingLight& p : g.points) {
            data.emplace_back(p.direction, 0.0f);
            data.emplace_back(p.flux, 0.0f);
        }
    return data;
}

// Every rough mip: subtractShadingLights's step on the GPU (the shader says how it keeps
// the CPU's digits), from the bake's mip into the residual's.
void subtractOnTheGpu(gl::ShaderLibrary& shaders, const bake::BakeResult& bake, const bake::BakedTexture& residual)
{
    const ShadingLights& lights = bake.shadingLights;
    const bake::BakedTexture& full = bake.prefiltered;
    const std::vector<glm::vec4> data = residualShaderData(lights);
    const gl::Buffer buffer = gl::createBufferWith<glm::vec4>(data);
    const gl::ShaderProgram& program = shaders.program({kResidualShader}, {{"FORMAT", bake::imageFormatName(full.internalFormat)}});
    const ResidualUniforms& u = program.uniforms<ResidualUniforms>();
    glUseProgram(program.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer.id());
    u.groups.set(int(lights.groups.size()));
    for (int level = 0; level < full.levels; ++level) {
        const double roughness = bake::prefilterMipRoughness(bake.settings.prefilter, level);
        if (roughness <= 0.0) continue;
        const ShadingLightKernel kernel = shadingLightKernel(roughness, lights.grid);
        const int size = full.levelSize(level);
        u.size.set(size);
        u.alpha2.set(float(kernel.alpha2));
        u.scale.set(float(kernel.scale));
        u.cosNear.set(float(kernel.cosNear));
        glBindImageTexture(1, full.id(), level, GL_TRUE, 0, GL_READ_ONLY, full.internalFormat);
        glBindImageTexture(0, residual.id(), level, GL_TRUE, 0, GL_WRITE_ONLY, residual.internalFormat);
        const GLuint groups = GLuint((size + 7) / 8);
        glDispatchCompute(groups, groups, 6);
    }
    // The mesh pass samples the residual.
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, residual.internalFormat);
    glBindImageTexture(1, 0, 0, GL_FALSE, 0, GL_READ_ONLY, full.internalFormat);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
    glUseProgram(0);
}

// The mirror: keepInMirror's step without reading it all back, only the lights' blocks
// (the rest of a 256 face is 99.9% of its texels and stays as the bake made it).
void keepInMirrorOnTheGpu(const bake::BakeResult& bake, const bake::BakedTexture& residual, int level)
{
    const ShadingLights& lights = bake.shadingLights;
    const bake::BakedTexture& full = bake.prefiltered;
    bake::copyCubeRows(full, level, residual, level, 0, 6, 0, full.levelSize(level));
    for (const ShadingLightGroup& g : lights.groups) {
        const MirrorBlock b = mirrorBlock(g, lights.grid, full.levelSize(level));
        std::vector<glm::vec4> block(std::size_t(b.texels) * std::size_t(b.texels));
        glGetTextureSubImage(full.id(), level, b.x, b.row, b.face, b.texels, b.texels, 1, GL_RGBA, GL_FLOAT, GLsizei(block.size() * sizeof(glm::vec4)),
                             block.data());
        for (glm::vec4& t : block) t = glm::vec4(glm::vec3(t) * g.keep, t.a);
        glTextureSubImage3D(residual.id(), level, b.x, b.row, b.face, b.texels, b.texels, 1, GL_RGBA, GL_FLOAT, block.data());
    }
}

SH9Color minus(const SH9Color& a, const SH9Color& b)
{
    SH9Color out;
    for (std::size_t i = 0; i < out.c.size(); ++i) out.c[i] = a.c[i] - b.c[i];
    return out;
}

} // namespace

std::unique_ptr<ShadingLightsTexture> makeShadingLightsTexture(gl::ShaderLibrary& shaders, const bake::BakeResult& bake)
{
    const ShadingLights& lights = bake.shadingLights;
    if (lights.groups.empty() || !bake.prefiltered) return nullptr;
    // The bake's own GL work first, so that the time below is this function's.
    glFinish();
    const auto start = std::chrono::steady_clock::now();
    auto out = std::make_unique<ShadingLightsTexture>();
    out->lights = lights.lights();
    out->minAlpha = lights.minAlpha();
    const bake::BakedTexture& full = bake.prefiltered;
    out->residual = bake::createCubeTexture(full.internalFormat, full.size, full.levels);
    for (int level = 0; level < full.levels; ++level)
        if (bake::prefilterMipRoughness(bake.settings.prefilter, level) <= 0.0) keepInMirrorOnTheGpu(bake, out->residual, level);
    subtractOnTheGpu(shaders, bake, out->residual);
    if (bake.irradianceCube) out->residualIrradiance = bake::residualIrradianceCube(bake.irradianceCube, out->lights);
    const SH9Color lightsSh = shadingLightsShIrradiance(out->lights);
    out->shResidual = minus(bake.sh.irradiance, lightsSh);
    out->shResidualWindowed = minus(bake.sh.irradianceWindowed, applyWindow(lightsSh, bake.sh.window, bake.sh.windowWidth));
    glFinish();
    out->milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return out;
}

} // namespace iblab
