#include "frame/conventions.hpp"

#include <array>
#include <cstdio>

namespace iblab {
namespace {

// What each engine's shading does, from its source at the commits docs/engine-export.md
// pins (its table "Convention presets against today's engines" has every value with file
// and line; docs/bake.md the bake side):
// - LearnOpenGL (src/6.pbr/2.2.1.ibl_specular/2.2.1.pbr.fs lines 121-134): F_roughness(n.v)
//   on the LUT, lod = r (levels - 1) read at R, a Schlick-GGX LUT (2.2.1.brdf.fs line 51,
//   k = alpha / 2), an irradiance cube, and no energy compensation: it stays off here.
// - Filament (shaders/src/surface_light_indirect.fs): SH9 diffuse, the cube read at
//   getSpecularDominantDirection's mix(R, N, alpha^2), F0 A + B from the DFG LUT with the
//   height-correlated Smith term, and 1 + F0 (1 / E_ss - 1) energy compensation
//   (surface_shading_lit.fs, getEnergyCompensationPixelParams).
// - glTF Sample Viewer (its renderer, glTF-Sample-Renderer source/Renderer/shaders/ibl.glsl
//   lines 26-48): lod = r (levels - 1) at R, the roughness-aware Fresnel
//   k_S = F0 + (max(1 - r, F0) - F0) (1 - n.v)^5 on the LUT, and Fdez-Aguera's multiple
//   scattering FssEss + FmsEms (getIBLGGXFresnel), an irradiance cube (the Lambertian one).
// - iblab, the lab's default (what the GUI and `render` start with): the exact F0 A + B,
//   the fitted lobe's reads instead of the split sum's one, and Filament's compensation,
//   on as every engine above but the tutorial ships it; the reference it is measured
//   against applies the same factor with its own E_ss.
constexpr std::array kConventions{
    ConventionPreset{.name = "learnopengl",
                     .title = "LearnOpenGL",
                     .bakePreset = "tutorial",
                     .geometry = GeometryTerm::SchlickGGX,
                     .roughFresnelOnLut = true,
                     .multiscatter = false,
                     .diffuse = DiffuseSource::IrradianceCube},
    ConventionPreset{.name = "filament",
                     .title = "Filament",
                     .bakePreset = "filament",
                     .multiscatter = true,
                     .diffuse = DiffuseSource::Sh9,
                     .specularDirection = SpecularDirection::Filament},
    ConventionPreset{.name = "gltf-viewer",
                     .title = "glTF Sample Viewer",
                     .bakePreset = "gltf-viewer",
                     .roughFresnelOnLut = true,
                     .multiscatter = true,
                     .multiscatterModel = MultiscatterModel::FdezAguera,
                     .diffuse = DiffuseSource::IrradianceCube},
    ConventionPreset{.name = "iblab",
                     .title = "iblab default",
                     .bakePreset = "default",
                     .multiscatter = true,
                     .diffuse = DiffuseSource::IrradianceCube,
                     .method = ShadingMethod::FittedLobe},
};

std::string formatted(const char* format, double value)
{
    char text[64];
    std::snprintf(text, sizeof text, format, value);
    return text;
}

} // namespace

std::span<const ConventionPreset> conventionPresets() { return kConventions; }

const ConventionPreset* findConvention(std::string_view name)
{
    for (const ConventionPreset& c : kConventions)
        if (c.name == name) return &c;
    return nullptr;
}

std::string conventionNames()
{
    std::string names;
    for (const ConventionPreset& c : kConventions) names += (names.empty() ? "" : ", ") + std::string(c.name);
    return names;
}

bake::BakeSettings conventionBakeSettings(const ConventionPreset& convention)
{
    bake::BakeSettings settings = bake::presetByName(convention.bakePreset);
    // Bake only the LUT the convention shades with.
    settings.lut.schlickGgx = convention.geometry == GeometryTerm::SchlickGGX;
    settings.lut.heightCorrelatedSmith = convention.geometry == GeometryTerm::HeightCorrelatedSmith;
    return settings;
}

void applyConvention(const ConventionPreset& convention, SamplingSettings& sampling)
{
    sampling.method = convention.method;
    sampling.forcedMip = -1;
    sampling.geometry = convention.geometry;
    sampling.roughFresnelOnLut = convention.roughFresnelOnLut;
    sampling.multiscatter = convention.multiscatter;
    sampling.multiscatterModel = convention.multiscatterModel;
    sampling.diffuse = convention.diffuse;
    sampling.specularDirection = convention.specularDirection;
}

std::vector<std::pair<std::string, std::string>> conventionChoices(const ConventionPreset& convention)
{
    const bake::BakeSettings bake = conventionBakeSettings(convention);
    const bake::PrefilterSettings& p = bake.prefilter;
    std::vector<std::pair<std::string, std::string>> rows;
    rows.emplace_back("geometry term", std::string(enumName(convention.geometry)));
    rows.emplace_back("roughness per mip", p.layout == bake::RoughnessLayout::Quadratic ? "quadratic: lod = (L-1) r (2-r)" : "linear: lod = (L-1) r");
    std::string bias = p.mipFiltering ? formatted("%+.2f", p.mipBias) + (bake.exactTexelSolidAngle ? " (texel read)" : " (face average)") : "off (source mip 0)";
    rows.emplace_back("source-mip bias", bias);
    std::string samples;
    for (int level = 1; level < p.levels; ++level) samples += (samples.empty() ? "" : "/") + std::to_string(bake::prefilterSamples(p, level));
    rows.emplace_back("prefilter", std::to_string(p.faceSize) + "^2 x " + std::to_string(p.levels) + " mips, " + samples + " samples (mips 1+)");
    rows.emplace_back("LUT", std::to_string(bake.lut.size) + "^2 x " + std::to_string(bake.lut.samples) + " samples");
    rows.emplace_back("Fresnel on LUT", convention.roughFresnelOnLut ? "F_roughness(n.v) A + B" : "F0 A + B");
    rows.emplace_back("energy compensation", !convention.multiscatter ? "off"
                                             : convention.multiscatterModel == MultiscatterModel::FdezAguera
                                                 ? "on, Fdez-Aguera's 1 / (1 - F_avg E_ms)"
                                                 : "on, Filament's 1 + F0 (1/E_ss - 1)");
    rows.emplace_back("diffuse", convention.diffuse == DiffuseSource::Sh9              ? "SH9"
                                : bake.irradiance == bake::IrradianceMethod::Moments ? "moment cube"
                                : bake.irradiance == bake::IrradianceMethod::Riemann ? "Riemann cube"
                                                                                      : "cosine-sampled cube");
    if (convention.method == ShadingMethod::FittedLobe)
        rows.emplace_back("specular reads", "the fitted lobe's, per n.v and roughness (docs/accuracy-study.md)");
    else
        rows.emplace_back("specular direction", convention.specularDirection == SpecularDirection::Filament    ? "mix(R, N, alpha^2) (Filament)"
                                            : convention.specularDirection == SpecularDirection::Frostbite ? "lerp(N, R, s (sqrt(s) + alpha)), s = 1 - alpha (Frostbite)"
                                                                                                            : "R");
    return rows;
}

} // namespace iblab
