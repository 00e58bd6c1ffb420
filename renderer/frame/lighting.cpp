#include "frame/lighting.hpp"

#include <array>
#include <cmath>

#include <glm/trigonometric.hpp>

#include "bake/bake_result.hpp"
#include "frame/texture_units.hpp"
#include "ibl/specular_approximations.hpp"

namespace iblab {

// The shader reads SamplingSettings::specularDirection by common/specular_lobe.glsl's numbers.
static_assert(int(SpecularDirection::Reflection) == SPECULAR_DIRECTION_REFLECTION);
static_assert(int(SpecularDirection::Frostbite) == SPECULAR_DIRECTION_FROSTBITE);
static_assert(int(SpecularDirection::Filament) == SPECULAR_DIRECTION_FILAMENT);

IblUniforms::IblUniforms(const gl::ShaderProgram& p)
    : environmentYaw(p, "uEnvironmentYaw"), environmentIntensity(p, "uEnvironmentIntensity"), shIrradiance(p, "uShIrradiance"),
      prefilteredLevels(p, "uPrefilteredLevels"), prefilteredLayout(p, "uPrefilteredLayout"), environmentFaceSize(p, "uEnvironmentFaceSize"),
      environmentLevels(p, "uEnvironmentLevels"), geometry(p, "uGeometry"), multiscatter(p, "uMultiscatter"),
      multiscatterModel(p, "uMultiscatterModel"),
      roughFresnelOnLut(p, "uRoughFresnelOnLut"), specularDirection(p, "uSpecularDirection"), forcedMip(p, "uForcedMip"), pdfMipFiltering(p, "uPdfMipFiltering"), mipBias(p, "uMipBias")
{
}

void IblUniforms::bind(const Lighting& lighting, const FrameSettings& settings) const
{
    environmentYaw.set(glm::radians(settings.environment.yawDegrees));
    environmentIntensity.set(std::exp2(settings.environment.intensityEv));
    glBindTextureUnit(kUnitEquirect, lighting.equirect);
    if (!lighting.bake) return;
    const bake::BakeResult& b = *lighting.bake;
    glBindTextureUnit(kUnitEnvironmentCube, b.environmentCube.id());
    glBindTextureUnit(kUnitPrefiltered, b.prefiltered.id());
    const bake::BakedTexture& irradiance = b.irradianceCube;
    glBindTextureUnit(kUnitIrradianceCube, irradiance.id());
    // The frame's geometry term when the bake has its LUT, else whichever LUT it has.
    const bake::BakedTexture& lut = b.lut(settings.sampling.geometry)   ? b.lut(settings.sampling.geometry)
                                    : b.lut(GeometryTerm::SchlickGGX) ? b.lut(GeometryTerm::SchlickGGX)
                                                                      : b.lut(GeometryTerm::HeightCorrelatedSmith);
    glBindTextureUnit(kUnitBrdfLut, lut.id());
    std::array<glm::vec3, 9> sh{};
    // Plain or windowed SH9 is the settings' choice: the bake holds both and stays as it is.
    const SH9Color& shCoefficients = settings.sampling.diffuse == DiffuseSource::Sh9Plain ? b.sh.irradiance : b.sh.irradianceWindowed;
    for (std::size_t i = 0; i < 9; ++i) sh[i] = glm::vec3(shCoefficients.c[i]);
    shIrradiance.set(sh);
    prefilteredLevels.set(float(b.prefiltered.levels));
    prefilteredLayout.set(int(b.settings.prefilter.layout));
    environmentFaceSize.set(float(b.environmentCube.size));
    environmentLevels.set(float(b.environmentCube.levels));
    geometry.set(int(settings.sampling.geometry));
    multiscatter.set(settings.sampling.multiscatter);
    multiscatterModel.set(int(settings.sampling.multiscatterModel));
    roughFresnelOnLut.set(settings.sampling.roughFresnelOnLut);
    specularDirection.set(int(settings.sampling.specularDirection));
    forcedMip.set(float(settings.sampling.forcedMip));
    pdfMipFiltering.set(settings.sampling.pdfMipFiltering);
    mipBias.set(settings.sampling.mipBias);
}

gl::ShaderDefine diffuseSourceDefine(const Lighting& lighting, const FrameSettings& settings)
{
    const bool cube = settings.sampling.diffuse == DiffuseSource::IrradianceCube && lighting.bake && bool(lighting.bake->irradianceCube);
    return {"DIFFUSE_SOURCE", cube ? "1" : "0"};
}

std::vector<float> prefilterMipRoughnessOf(const bake::BakeResult& bake)
{
    std::vector<float> roughness;
    for (int level = 0; level < bake.prefiltered.levels; ++level) roughness.push_back(bake::prefilterMipRoughness(bake.settings.prefilter, level));
    return roughness;
}

} // namespace iblab
