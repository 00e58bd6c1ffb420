#include "frame/conventions.hpp"

#include <array>
#include <cstdio>

namespace iblab {
namespace {

// Sources: LearnOpenGL's "Specular IBL" chapter code; Filament.md.html ("Image based
// lights") and its shading code (perceptualRoughnessToLod, DFG with energy compensation,
// SH irradiance); glTF-Sample-Viewer's ibl_sampler.js and ibl.glsl (getIBLRadianceGGX uses
// k_S = F0 + (max(1 - roughness, F0) - F0) (1 - n.v)^5, the roughness-aware Fresnel, on the
// LUT). iblab is the lab's own default, what the GUI and `render` start with: the exact
// F0 A + B, the fitted lobe's reads instead of the split sum's one, and no energy
// compensation (the exact references it is measured against are single-scattering; the
// Sampling panel's checkbox adds it).
// Where the cube is read: Filament's getReflectedVector leans R towards N by alpha^2
// (common/specular_lobe.glsl); LearnOpenGL's and the Sample Viewer's ibl code read at R.
constexpr std::array kConventions{
    ConventionPreset{"learnopengl", "LearnOpenGL", "tutorial", GeometryTerm::SchlickGGX, true, false, DiffuseSource::IrradianceCube,
                     SpecularDirection::Reflection},
    ConventionPreset{"filament", "Filament", "filament", GeometryTerm::HeightCorrelatedSmith, false, true, DiffuseSource::Sh9,
                     SpecularDirection::Filament},
    ConventionPreset{"gltf-viewer", "glTF Sample Viewer", "gltf-viewer", GeometryTerm::HeightCorrelatedSmith, true, false,
                     DiffuseSource::IrradianceCube, SpecularDirection::Reflection},
    ConventionPreset{"iblab", "iblab default", "default", GeometryTerm::HeightCorrelatedSmith, false, false, DiffuseSource::IrradianceCube,
                     SpecularDirection::Reflection, ShadingMethod::FittedLobe},
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
    rows.emplace_back("energy compensation", convention.multiscatter ? "on" : "off");
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
