#include "frame/shading_lights_texture.hpp"

#include <chrono>

#include "bake/bake_result.hpp"
#include "bake/bake_settings.hpp"

namespace iblab {

std::unique_ptr<ShadingLightsTexture> makeShadingLightsTexture(const bake::BakeResult& bake)
{
    const ShadingLights& lights = bake.shadingLights;
    if (lights.groups.empty() || !bake.prefiltered) return nullptr;
    // The bake's own GL work first, so that the time below is this function's (the first
    // read-back would wait for it anyway).
    glFinish();
    const auto start = std::chrono::steady_clock::now();
    auto out = std::make_unique<ShadingLightsTexture>();
    out->lights = lights.lights();
    out->minAlpha = lights.minAlpha();
    const bake::BakedTexture& full = bake.prefiltered;
    out->residual = bake::createCubeTexture(full.internalFormat, full.size, full.levels);
    for (int level = 0; level < full.levels; ++level) {
        const double roughness = bake::prefilterMipRoughness(bake.settings.prefilter, level);
        if (roughness > 0.0) {
            // shadingLightResidual's step for this mip, on a read-back (what the study measures).
            const bake::CubeImage image = bake::readCubeLevel(full, level);
            CubeLevelRgb rgb{image.size, std::vector<glm::vec3>(image.texels.size())};
            for (std::size_t i = 0; i < image.texels.size(); ++i) rgb.texels[i] = glm::vec3(image.texels[i]);
            subtractShadingLights(rgb, roughness, lights);
            bake::CubeImage residual(rgb.size);
            for (std::size_t i = 0; i < rgb.texels.size(); ++i) residual.texels[i] = glm::vec4(rgb.texels[i], 1.0f);
            bake::uploadCubeLevel(out->residual, level, residual);
            continue;
        }
        // The mirror: keepInMirror's step without reading it all back, only the lights' blocks
        // (the rest of a 256 face is 99.9% of its texels and stays as the bake made it).
        bake::copyCubeRows(full, level, out->residual, level, 0, 6, 0, full.levelSize(level));
        for (const ShadingLightGroup& g : lights.groups) {
            const MirrorBlock b = mirrorBlock(g, lights.grid, full.levelSize(level));
            std::vector<glm::vec4> block(std::size_t(b.texels) * std::size_t(b.texels));
            glGetTextureSubImage(full.id(), level, b.x, b.row, b.face, b.texels, b.texels, 1, GL_RGBA, GL_FLOAT, GLsizei(block.size() * sizeof(glm::vec4)),
                                 block.data());
            for (glm::vec4& t : block) t = glm::vec4(glm::vec3(t) * g.keep, t.a);
            glTextureSubImage3D(out->residual.id(), level, b.x, b.row, b.face, b.texels, b.texels, 1, GL_RGBA, GL_FLOAT, block.data());
        }
    }
    out->milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return out;
}

} // namespace iblab
