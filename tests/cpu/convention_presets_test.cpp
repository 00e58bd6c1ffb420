// The convention presets (renderer/conventions.hpp): each names a valid bake preset, bakes
// only the LUT it shades with, and reproduces the published choices that make viewers differ.
#include <cmath>
#include <numbers>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "bake/bake_settings.hpp"
#include "ibl/prefilter_lod.hpp"
#include "frame/conventions.hpp"

namespace iblab {
namespace {

const ConventionPreset& preset(std::string_view name)
{
    const ConventionPreset* found = findConvention(name);
    EXPECT_NE(found, nullptr) << name;
    return *found;
}

TEST(ConventionPresets, EveryPresetBakesValidlyAndOnlyItsOwnLut)
{
    std::set<std::string_view> names;
    for (const ConventionPreset& c : conventionPresets()) {
        EXPECT_TRUE(names.insert(c.name).second) << "duplicate " << c.name;
        const bake::BakeSettings bake = conventionBakeSettings(c);
        EXPECT_NO_THROW(bake::validate(bake)) << c.name;
        EXPECT_TRUE(bake.lut.wants(c.geometry)) << c.name;
        EXPECT_FALSE(bake.lut.wants(c.geometry == GeometryTerm::SchlickGGX ? GeometryTerm::HeightCorrelatedSmith : GeometryTerm::SchlickGGX)) << c.name;
        EXPECT_EQ(conventionChoices(c).size(), conventionChoices(conventionPresets().front()).size());
    }
    EXPECT_EQ(findConvention("unreal"), nullptr);
}

TEST(ConventionPresets, ReproduceWhatEachViewerChose)
{
    const bake::BakeSettings learnOpenGl = conventionBakeSettings(preset("learnopengl"));
    EXPECT_EQ(learnOpenGl.prefilter.layout, bake::RoughnessLayout::Linear);
    // 2.2.1.prefilter.fs lines 92-96: each sample reads mip 0.5 log2(saSample / saTexel),
    // saTexel = 4 pi / (6 512^2), saSample = 1 / (N pdf) (its 0.0001 guards aside:
    // source_samples_test), mip 0 at roughness 0; not source mip 0 throughout.
    EXPECT_TRUE(learnOpenGl.prefilter.mipFiltering);
    EXPECT_FALSE(learnOpenGl.exactTexelSolidAngle);
    EXPECT_EQ(learnOpenGl.cube.faceSize, 512);
    {
        const float resolution = 512.0f, n = 1024.0f, pdf = 0.37f;
        const float saTexel = 4.0f * std::numbers::pi_v<float> / (6.0f * resolution * resolution);
        const float saSample = 1.0f / (n * pdf);
        EXPECT_NEAR(sourceLodFromPdf(pdf, n, float(learnOpenGl.cube.faceSize), learnOpenGl.prefilter.mipBias),
                    0.5f * std::log2(saSample / saTexel), 1e-3f);
    }
    EXPECT_EQ(preset("learnopengl").geometry, GeometryTerm::SchlickGGX);
    EXPECT_TRUE(preset("learnopengl").roughFresnelOnLut);
    // 2.2.1.pbr.fs: prefilteredColor * (F * brdf.x + brdf.y), nothing for multiple scattering.
    EXPECT_FALSE(preset("learnopengl").multiscatter);

    // Filament: quadratic lod, K = 4 (one mip blurrier), energy compensation.
    const bake::BakeSettings filament = conventionBakeSettings(preset("filament"));
    EXPECT_EQ(filament.prefilter.layout, bake::RoughnessLayout::Quadratic);
    EXPECT_FLOAT_EQ(filament.prefilter.mipBias, 1.0f);
    EXPECT_TRUE(preset("filament").multiscatter);
    EXPECT_EQ(preset("filament").multiscatterModel, MultiscatterModel::Filament);
    EXPECT_FALSE(preset("filament").roughFresnelOnLut);
    // getReflectedVector: the prefiltered cube is read at mix(R, N, alpha^2), not at R.
    EXPECT_EQ(preset("filament").specularDirection, SpecularDirection::Filament);
    EXPECT_EQ(preset("learnopengl").specularDirection, SpecularDirection::Reflection);
    // Its shading reads roughness 0.5 at lod 4 x 0.75 = 3 of its 5 levels.
    EXPECT_FLOAT_EQ(prefilterMipFromRoughness(0.5f, float(filament.prefilter.levels), int(filament.prefilter.layout)), 3.0f);

    // glTF Sample Viewer: lod = 0.5 log2(6 w^2 / (N pdf)), the face-average formula without
    // 4 pi: a bias of 0.5 log2(4 pi).
    const bake::BakeSettings gltf = conventionBakeSettings(preset("gltf-viewer"));
    EXPECT_EQ(gltf.prefilter.layout, bake::RoughnessLayout::Linear);
    EXPECT_FALSE(gltf.exactTexelSolidAngle);
    const float w = float(gltf.cube.faceSize), n = 1024.0f, pdf = 3.7f;
    const float theirs = 0.5f * std::log2(6.0f * w * w / (n * pdf));
    EXPECT_NEAR(sourceLodFromPdf(pdf, n, w, gltf.prefilter.mipBias), theirs, 1e-3f);
    EXPECT_TRUE(preset("gltf-viewer").roughFresnelOnLut);
    // getIBLGGXFresnel returns FssEss + FmsEms (Fdez-Aguera), the specular times
    // 1 / (1 - F_avg E_ms).
    EXPECT_TRUE(preset("gltf-viewer").multiscatter);
    EXPECT_EQ(preset("gltf-viewer").multiscatterModel, MultiscatterModel::FdezAguera);
    // The lab's default compensates as the engines do; the reference applies the same factor.
    EXPECT_TRUE(preset("iblab").multiscatter);
    EXPECT_EQ(preset("iblab").multiscatter, SamplingSettings{}.multiscatter);
}

TEST(ConventionPresets, ApplyingOneSetsTheSplitSumShadingItUses)
{
    SamplingSettings sampling;
    sampling.method = ShadingMethod::Sampled;
    sampling.forcedMip = 3;
    sampling.samples = 77;
    sampling.specularDirection = SpecularDirection::Frostbite;
    applyConvention(preset("learnopengl"), sampling);
    EXPECT_EQ(sampling.method, ShadingMethod::SplitSum);
    EXPECT_EQ(sampling.forcedMip, -1);
    EXPECT_EQ(sampling.geometry, GeometryTerm::SchlickGGX);
    EXPECT_TRUE(sampling.roughFresnelOnLut);
    EXPECT_EQ(sampling.diffuse, DiffuseSource::IrradianceCube);
    EXPECT_EQ(sampling.specularDirection, SpecularDirection::Reflection);
    EXPECT_EQ(sampling.samples, 77); // not the convention's business
    applyConvention(preset("filament"), sampling);
    EXPECT_EQ(sampling.specularDirection, SpecularDirection::Filament);
    EXPECT_EQ(sampling.method, ShadingMethod::SplitSum);
    // iblab's own convention is its default shading, the fitted lobe.
    applyConvention(preset("iblab"), sampling);
    EXPECT_EQ(sampling.method, ShadingMethod::FittedLobe);
}

// "iblab default" in the Conventions panel puts back what the lab starts with: every choice a
// convention makes is the default's, energy compensation (Filament's form) included.
TEST(ConventionPresets, IblabsOwnIsWhatTheLabStartsWith)
{
    SamplingSettings sampling;
    applyConvention(preset("iblab"), sampling);
    EXPECT_EQ(sampling, SamplingSettings{});
    EXPECT_EQ(conventionBakeSettings(preset("iblab")).prefilter, bake::defaultPreset().prefilter);
}

} // namespace
} // namespace iblab
