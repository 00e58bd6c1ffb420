// Lab settings are the preset format and the screenshot metadata: every field must survive
// a round trip, and a bad preset must say which key is wrong.
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "frame/settings.hpp"

namespace iblab {
namespace {

TEST(Settings, EveryFieldSurvivesJson)
{
    FrameSettings s;
    s.environment = {"builtin:sun?elevation=10", 33.0f, -1.5f};
    s.toneMap = {ToneMapOperator::PbrNeutral, 1.25f};
    s.camera = {12.0f, -7.0f, 70.0f, 5.5f, glm::vec3(0.1f, 0.2f, 0.3f)};
    s.material = {false, glm::vec3(0.2f, 0.4f, 0.6f), 0.25f, 0.75f, 0.5f, 0.35f};
    s.sampling.method = ShadingMethod::Sampled;
    s.sampling.samples = 64;
    s.sampling.forcedMip = 2;
    s.sampling.pdfMipFiltering = false;
    s.sampling.mipBias = 0.0f;
    s.sampling.geometry = GeometryTerm::SchlickGGX;
    s.sampling.diffuse = DiffuseSource::IrradianceCube;
    s.sampling.cosineSampledDiffuse = true;
    s.sampling.multiscatter = false; // not the default (on)
    s.sampling.multiscatterModel = MultiscatterModel::FdezAguera;
    s.sampling.normalizeByAccepted = true;
    s.sampling.freezeSampleSet = true;
    s.scene = {SceneKind::Model, "a/b.glb", 5};
    s.view.background = BackgroundMode::PrefilterMip;
    s.view.backgroundMip = 3;
    s.view.solidColour = glm::vec3(0.5f);
    s.view.mode = ViewMode::Error;
    s.view.errorSpace = ErrorSpace::Display;
    s.view.errorScale = 0.05f;
    s.view.referenceWidth = 64;
    s.view.split = true;
    s.view.splitPosition = 0.3f;
    s.view.compare.method = ShadingMethod::Sampled;
    s.view.compare.samples = 3;
    s.view.compare.geometry = GeometryTerm::SchlickGGX;
    s.view.compare.multiscatter = false;
    s.view.compare.freezeSampleSet = true;
    s.view.msaaSamples = 8;

    const FrameSettings r = frameSettingsFromJsonText(toJsonText(s));
    EXPECT_EQ(toJsonText(r), toJsonText(s));
    EXPECT_EQ(r, s);
    EXPECT_EQ(r.sampling.method, ShadingMethod::Sampled);
    EXPECT_EQ(r.scene.modelPath, "a/b.glb");
    EXPECT_EQ(r.camera.target, glm::vec3(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(r.material.baseColor, glm::vec3(0.2f, 0.4f, 0.6f));
    EXPECT_EQ(r.view.errorSpace, ErrorSpace::Display);
    EXPECT_EQ(r.view.compare.samples, 3);
    EXPECT_EQ(r.view.compare.geometry, GeometryTerm::SchlickGGX);
    EXPECT_FLOAT_EQ(r.view.splitPosition, 0.3f);
    EXPECT_TRUE(r.sampling.freezeSampleSet);
    EXPECT_TRUE(r.view.compare.freezeSampleSet);
    EXPECT_FALSE(r.sampling.multiscatter);
    EXPECT_EQ(r.sampling.multiscatterModel, MultiscatterModel::FdezAguera);
    EXPECT_EQ(r.view.msaaSamples, 8);
}

TEST(Settings, SpecularReadsSurviveJsonInTheirOneSpelling)
{
    FrameSettings s;
    s.sampling.method = ShadingMethod::FittedLobe;
    s.sampling.specularDirection = SpecularDirection::Filament;
    s.view.compare.specularDirection = SpecularDirection::Frostbite;
    const std::string json = toJsonText(s);
    EXPECT_EQ(frameSettingsFromJsonText(json), s);
    EXPECT_NE(json.find("\"method\": \"fitted-lobe\""), std::string::npos) << json;
    EXPECT_NE(json.find("\"specular_direction\": \"filament\""), std::string::npos) << json;
    EXPECT_NE(json.find("\"specular_direction\": \"frostbite\""), std::string::npos) << json;
    // A preset written before the setting existed reads at R.
    EXPECT_EQ(frameSettingsFromJsonText("{}").sampling.specularDirection, SpecularDirection::Reflection);
}

// The renderer keys its images on settings compared by value: every field must take part
// (a field left out of operator== would let a stale image survive its change).
TEST(Settings, EqualityComparesEveryField)
{
    const FrameSettings base;
    EXPECT_EQ(base, FrameSettings{});
    std::vector<FrameSettings> changed(12, base);
    changed[0].environment.source = "builtin:sky";
    changed[1].toneMap.exposureEv = 1.0f;
    changed[2].camera.target.z = 0.5f;
    changed[3].material.baseColor.g = 0.1f;
    changed[4].material.specular = 0.3f;
    changed[5].sampling.freezeSampleSet = true;
    changed[6].sampling.normalizeByAccepted = true;
    changed[7].scene.countingSpheres = 3;
    changed[8].view.msaaSamples = 1;
    changed[9].view.compare.samples = 3;
    changed[10].view.solidColour.b = 0.5f;
    changed[11].view.splitPosition = 0.25f;
    for (std::size_t i = 0; i < changed.size(); ++i) EXPECT_NE(changed[i], base) << i;
}

TEST(Settings, CountingStripAlwaysKeepsItsExactSampleCount)
{
    FrameSettings s;
    EXPECT_FALSE(keepsExactSampleCount(s));
    s.sampling.freezeSampleSet = true;
    EXPECT_TRUE(keepsExactSampleCount(s));
    s.sampling.freezeSampleSet = false;
    s.scene.kind = SceneKind::Counting;
    EXPECT_TRUE(keepsExactSampleCount(s));
    s.scene.kind = SceneKind::Sweep;
    EXPECT_FALSE(keepsExactSampleCount(s));
}

TEST(Settings, MissingKeysKeepDefaults)
{
    const FrameSettings r = frameSettingsFromJsonText(R"({"material": {"roughness": 0.9}})");
    EXPECT_FLOAT_EQ(r.material.roughness, 0.9f);
    EXPECT_EQ(toJsonText(frameSettingsFromJsonText("{}")), toJsonText(FrameSettings{}));
    EXPECT_EQ(frameSettingsFromJsonText("{}").view.msaaSamples, 4);
}

TEST(Settings, BadValuesNameTheKey)
{
    auto messageOf = [](const char* text) {
        try {
            frameSettingsFromJsonText(text);
        } catch (const std::runtime_error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(messageOf(R"({"sampling": {"method": "magic"}})").find("settings.sampling.method"), std::string::npos);
    EXPECT_NE(messageOf(R"({"material": {"roughness": "high"}})").find("settings.material.roughness"), std::string::npos);
    EXPECT_NE(messageOf(R"({"material": {"base_color": [1, 2]}})").find("settings.material.base_color"), std::string::npos);
    EXPECT_NE(messageOf(R"({"tone_map": {"operator": "filmic"}})").find("settings.tone_map.operator"), std::string::npos);
    EXPECT_NE(messageOf(R"({"view": {"compare": {"method": "magic"}}})").find("settings.view.compare.method"), std::string::npos);
    EXPECT_NE(messageOf(R"({"view": {"error_space": "log"}})").find("settings.view.error_space"), std::string::npos);
    EXPECT_EQ(messageOf(R"({"material": {"roughness": -5}})"), "settings.material.roughness: must be 0..1, got -5.0");
    EXPECT_EQ(messageOf(R"({"view": {"msaa_samples": 3}})"), "settings.view.msaa_samples: must be a power of two in 1..8, got 3");
    EXPECT_NE(messageOf("{not json").find("not JSON"), std::string::npos);
    EXPECT_NE(messageOf("[1, 2]").find("object"), std::string::npos);
}

// The GUI's slider edits are bounded by the same ranges the command line and presets check.
TEST(Settings, ClampToRangesMovesNumbersToTheNearestEndOfTheirRange)
{
    FrameSettings s;
    s.material.roughness = -5.0f;
    s.material.metallic = 1e30f;
    s.material.specular = std::numeric_limits<float>::quiet_NaN();
    s.camera.pitchDegrees = 120.0f;
    s.sampling.samples = 0;
    s.sampling.forcedMip = -1;   // the special value "auto", outside 0..16 but valid
    s.camera.distance = 0.0f;    // the special value "frame the scene"
    s.view.msaaSamples = 3;      // power-of-two fields have no nearest valid end: left as they are
    EXPECT_TRUE(clampToRanges(frameSettingsFields(), s));
    EXPECT_EQ(s.material.roughness, 0.0f);
    EXPECT_EQ(s.material.metallic, 1.0f);
    EXPECT_EQ(s.material.specular, 0.0f);
    EXPECT_EQ(s.camera.pitchDegrees, 89.0f);
    EXPECT_EQ(s.sampling.samples, 1);
    EXPECT_EQ(s.sampling.forcedMip, -1);
    EXPECT_EQ(s.camera.distance, 0.0f);
    EXPECT_EQ(s.view.msaaSamples, 3);

    FrameSettings defaults;
    EXPECT_FALSE(clampToRanges(frameSettingsFields(), defaults));
    EXPECT_EQ(toJsonText(defaults), toJsonText(FrameSettings{}));
}

// A model shows its own materials unless asked otherwise, on the command line as in the GUI
// (which turned the override off on loading a model while the command line's default was
// on, and the help text named the opposite option).
TEST(Settings, AModelShowsItsOwnMaterialsUnlessAsked)
{
    EXPECT_FALSE(FrameSettings{}.material.overrideModel);
    for (const auto& field : frameSettingsFields())
        if (std::string(field.key) == "material.override_model") {
            EXPECT_EQ(std::string(field.cli), "--override-model");
            EXPECT_EQ(field.cliForm, CliForm::Flag);
            EXPECT_NE(std::string(field.help).find("(--override-model)"), std::string::npos) << field.help;
            EXPECT_NE(std::string(field.help).find("by default the model's own materials"), std::string::npos) << field.help;
        }
}

} // namespace
} // namespace iblab
