#pragma once
// "Why viewers differ": how LearnOpenGL, Filament and the Khronos glTF Sample Viewer each set
// up image-based lighting, as presets of the lab. A convention is a bake preset (cube and
// prefilter sizes, roughness-per-mip layout, source-mip bias, LUT; bake_settings.cpp says
// where each value comes from) plus the split-sum shading choices that go with it (geometry
// term, Fresnel on the LUT, energy compensation, diffuse source, where the cube is read). Rendering one material under
// each shows where the differences come from: `iblab conventions`, or the GUI's combo.
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "bake/bake_settings.hpp"
#include "frame/settings.hpp"

namespace iblab {

struct ConventionPreset {
    std::string_view name;       // "learnopengl", "filament", "gltf-viewer", "iblab"
    std::string_view title;      // for labels: "LearnOpenGL"
    std::string_view bakePreset; // bake::presetByName
    GeometryTerm geometry = GeometryTerm::HeightCorrelatedSmith;
    bool roughFresnelOnLut = false;
    bool multiscatter = false;
    MultiscatterModel multiscatterModel = MultiscatterModel::Filament;
    DiffuseSource diffuse = DiffuseSource::Sh9;
    SpecularDirection specularDirection = SpecularDirection::Reflection;
    // The engines read the prefiltered cube once (the split sum); iblab's default reads it
    // where the fitted table says (ShadingMethod::FittedLobe, docs/accuracy-study.md).
    ShadingMethod method = ShadingMethod::SplitSum;
};

std::span<const ConventionPreset> conventionPresets();
// nullptr for an unknown name.
const ConventionPreset* findConvention(std::string_view name);
std::string conventionNames(); // "learnopengl, filament, gltf-viewer, iblab"

bake::BakeSettings conventionBakeSettings(const ConventionPreset& convention);
// Split-sum shading as the convention does it; the other sampling fields stay.
void applyConvention(const ConventionPreset& convention, SamplingSettings& sampling);

// What the convention chose, one (aspect, choice) per row: geometry term, roughness per mip,
// source-mip bias, prefilter, LUT, Fresnel, energy compensation, diffuse, specular direction.
std::vector<std::pair<std::string, std::string>> conventionChoices(const ConventionPreset& convention);

} // namespace iblab
