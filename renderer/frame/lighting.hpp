#pragma once
// What every lit pass reads (sky, mesh, debug views, the reference's resolve): the loaded
// environment and the bake that lights the frame, bound as the uniforms and texture units
// that common/environment_lookup.glsl and common/ibl_lighting.glsl declare.
#include <vector>

#include <epoxy/gl.h>
#include <glm/vec3.hpp>

#include "frame/settings.hpp"
#include "gl/uniform.hpp"

namespace iblab {

namespace bake {
struct BakeResult;
}

struct ShadingLightsTexture;

struct Lighting {
    GLuint equirect = 0;                    // the loaded map with mips
    const bake::BakeResult* bake = nullptr; // the bake this frame lights with; null until one is set
    // The bake's shading lights and its cube less them, for the fitted lobe; null without lights.
    const ShadingLightsTexture* shadingLights = nullptr;
};

// The shared IBL uniforms of one program; every lit pass's uniforms include them.
struct IblUniforms {
    explicit IblUniforms(const gl::ShaderProgram& program);
    // The environment always; the bake's textures and parameters when there is one.
    void bind(const Lighting& lighting, const FrameSettings& settings) const;

    gl::Uniform<float> environmentYaw;
    gl::Uniform<float> environmentIntensity;
    gl::UniformArray<glm::vec3> shIrradiance;
    gl::Uniform<float> prefilteredLevels;
    gl::Uniform<int> prefilteredLayout;
    gl::Uniform<float> environmentFaceSize;
    gl::Uniform<float> environmentLevels;
    gl::Uniform<int> geometry;
    gl::Uniform<bool> multiscatter;
    gl::Uniform<int> multiscatterModel;
    gl::Uniform<bool> roughFresnelOnLut;
    gl::Uniform<int> specularDirection;
    gl::Uniform<float> forcedMip;
    gl::Uniform<bool> pdfMipFiltering;
    gl::Uniform<float> mipBias;
};

// Where diffuse irradiance comes from (ibl_lighting.glsl's DIFFUSE_SOURCE, compiled into the
// programs that shade with it): 1 the bake's irradiance cube when the settings ask for it and
// the bake has one, else 0, SH9.
gl::ShaderDefine diffuseSourceDefine(const Lighting& lighting, const FrameSettings& settings);

// The roughness of each prefiltered mip of the bake, as its layout put them.
std::vector<float> prefilterMipRoughnessOf(const bake::BakeResult& bake);

} // namespace iblab
