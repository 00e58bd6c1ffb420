#include "frame/settings.hpp"

#include <stdexcept>

#include <nlohmann/json.hpp>

namespace iblab {

bool sceneDemandsExactSampleCount(const SceneSettings& scene) { return scene.kind == SceneKind::Counting; }

bool keepsExactSampleCount(const FrameSettings& settings)
{
    return settings.sampling.freezeSampleSet || sceneDemandsExactSampleCount(settings.scene);
}

const FieldTable<SamplingSettings>& samplingSettingsFields()
{
    using S = SamplingSettings;
    constexpr CliForm value = CliForm::Value, flag = CliForm::Flag;
    static const FieldTable<S> fields{
        {"method", "Method", "Shading method: splitsum|sampled|fitted-lobe|reference (the full integral, slow)", fieldRef<S>([](S& s) -> auto& { return s.method; }), {}, "--method", value},
        {"samples", "N", "N, the samples per pixel of the sampled method",
         fieldRef<S>([](S& s) -> auto& { return s.samples; }), {.min = 1, .max = kMaxSampleCount, .ui = {.format = "N = %d", .logarithmic = true}},
         "--samples", value},
        // --mip takes "auto" for -1 (app/cli.cpp).
        {"forced_mip", "Forced mip", "Mip level every read takes (the prefiltered mip for the split sum, the source mip for sampled), or auto",
         fieldRef<S>([](S& s) -> auto& { return s.forcedMip; }), {0, 16, -1, "the lod follows roughness or the pdf"}, "--mip"},
        {"pdf_mip_filtering", "PDF mip filtering", "Sampled method: read each sample from the source mip its pdf chooses (--pdf-filtering) or from mip 0 (--no-pdf-filtering)",
         fieldRef<S>([](S& s) -> auto& { return s.pdfMipFiltering; }), {}, "--no-pdf-filtering", CliForm::NegatedFlag},
        {"mip_bias", "Mip bias", "Sampled method: levels added to the pdf-chosen source mip (0 as LearnOpenGL, 1 as Filament)",
         fieldRef<S>([](S& s) -> auto& { return s.mipBias; }),
         {.min = -16, .max = 16, .ui = {.format = "%+.2f", .min = -1, .max = 3}}, "--mip-bias", value}, // the slider: the useful part
        {"geometry", "Geometry term", "Geometry term: schlick-ggx|height-correlated-smith",
         fieldRef<S>([](S& s) -> auto& { return s.geometry; }), {}, "--geometry", value},
        {"diffuse", "Diffuse", "Split sum's diffuse source: sh9 (windowed)|sh9-plain|irradiance-cube", fieldRef<S>([](S& s) -> auto& { return s.diffuse; }), {}, "--diffuse",
         value},
        {"cosine_sampled_diffuse", "Cosine-sampled diffuse", "Sampled method: diffuse from N cosine samples (--cosine-diffuse) or from SH9 (--no-cosine-diffuse)",
         fieldRef<S>([](S& s) -> auto& { return s.cosineSampledDiffuse; }), {}, "--cosine-diffuse", flag},
        {"multiscatter", "Multiple-scattering compensation", "Multiple-scattering energy compensation from the LUT's third channel (Fdez-Aguera)",
         fieldRef<S>([](S& s) -> auto& { return s.multiscatter; }), {}, "--multiscatter", flag},
        {"multiscatter_model", "Multiscatter model",
         "Form of the compensation: filament (1 + F0 (1/E_ss - 1))|fdez-aguera (1 / (1 - F_avg (1 - E_ss)), the glTF Sample Viewer's and Bevy's)",
         fieldRef<S>([](S& s) -> auto& { return s.multiscatterModel; }), {}, "--multiscatter-model", value},
        {"shading_lights", "Shading lights exact",
         "Fitted lobe: sum the bake's brightest texel groups (a sun, lamps) exactly as lights, specular and diffuse, and read the cubes and SH9 without them (--no-shading-lights: the plain cubes)",
         fieldRef<S>([](S& s) -> auto& { return s.shadingLights; }), {}, "--shading-lights", flag},
        {"rough_fresnel_on_lut", "F_roughness on the LUT", "Split sum as LearnOpenGL: F_roughness(n.v) * A + B instead of F0 * A + B",
         fieldRef<S>([](S& s) -> auto& { return s.roughFresnelOnLut; }), {}, "--rough-fresnel-lut", flag},
        {"specular_direction", "Specular direction",
         "Split sum: the direction the prefiltered cube is read at: reflection (R)|frostbite|filament (dominant directions towards N)",
         fieldRef<S>([](S& s) -> auto& { return s.specularDirection; }), {}, "--specular-direction", value},
        {"normalize_by_accepted", "Normalise by accepted samples",
         "Sampled method: divide by the samples above the horizon (as LearnOpenGL) instead of by N",
         fieldRef<S>([](S& s) -> auto& { return s.normalizeByAccepted; }), {}, "--normalize-accepted", flag},
        {"freeze_sample_set", "Freeze the sample set",
         "Sampled method: keep exactly N samples per pixel instead of adding rotated sample sets over frames",
         fieldRef<S>([](S& s) -> auto& { return s.freezeSampleSet; }), {}, "--freeze-samples", flag},
    };
    return fields;
}

const FieldTable<MaterialSettings>& materialSettingsFields()
{
    using S = MaterialSettings;
    constexpr CliForm value = CliForm::Value;
    static const FieldTable<S> fields{
        {"override_model", "Override the model's factors", "Whether the sliders' base colour, metallic and roughness replace a glTF model's factors (--override-model); by default the model's own materials show",
         fieldRef<S>([](S& s) -> auto& { return s.overrideModel; }), {}, "--override-model", CliForm::Flag},
        // --base-color also takes #rrggbb (app/cli.cpp).
        {"base_color", "Base colour", "Base colour: r,g,b (linear, 0..1) or #rrggbb (sRGB)",
         fieldRef<S>([](S& s) -> auto& { return s.baseColor; }), {}, "--base-color"},
        {"metallic", "Metallic", "Metallic factor", fieldRef<S>([](S& s) -> auto& { return s.metallic; }), {0, 1},
         "--metallic", value},
        {"roughness", "Roughness", "Perceptual roughness (alpha = roughness^2)", fieldRef<S>([](S& s) -> auto& { return s.roughness; }),
         {0, 1}, "--roughness", value},
        {"ambient_occlusion", "AO", "Ambient occlusion factor",
         fieldRef<S>([](S& s) -> auto& { return s.ambientOcclusion; }), {0, 1}, "--ao", value},
        {"specular", "Specular", "Dielectric reflectance, F0 = 0.16 specular^2 (0.5 gives F0 = 0.04)",
         fieldRef<S>([](S& s) -> auto& { return s.specular; }), {.min = 0, .max = 1, .ui = {.format = "%.2f"}}, "--specular", value},
    };
    return fields;
}

namespace {

// An angle is valid at any value (it wraps); its slider spans one turn.
const FieldRange kAngle{.min = -1e6, .max = 1e6, .ui = {.format = "%.1f deg", .min = -180, .max = 180}};
// Exposure and intensity in EV stops.
const FieldRange kStops{.min = -20, .max = 20, .ui = {.format = "%+.2f EV"}};

FieldTable<FrameSettings> makeFrameFields()
{
    using S = FrameSettings;
    constexpr CliForm value = CliForm::Value;
    FieldTable<S> fields{
        // --env (app/cli.cpp) also lists the builtins.
        {"environment.source", "Source", "Environment: an .exr/.hdr file or builtin:NAME",
         fieldRef<S>([](S& s) -> auto& { return s.environment.source; }), {}, "--env"},
        {"environment.yaw_degrees", "Yaw", "Environment rotation about +Y in degrees (+90 brings +X to the front)",
         fieldRef<S>([](S& s) -> auto& { return s.environment.yawDegrees; }), kAngle, "--env-yaw", value},
        {"environment.intensity_ev", "Intensity", "Environment intensity in EV stops",
         fieldRef<S>([](S& s) -> auto& { return s.environment.intensityEv; }), kStops, "--env-intensity", value},
        {"tone_map.operator", "Operator", "Tone-map operator", fieldRef<S>([](S& s) -> auto& { return s.toneMap.op; }), {}, "--tonemap",
         value},
        {"tone_map.exposure_ev", "Exposure", "Exposure before tone mapping in EV stops",
         fieldRef<S>([](S& s) -> auto& { return s.toneMap.exposureEv; }), kStops, "--exposure", value},
        {"camera.yaw_degrees", "Yaw", "Camera yaw in degrees (0 looks down -Z, +90 down +X)",
         fieldRef<S>([](S& s) -> auto& { return s.camera.yawDegrees; }), kAngle, "--yaw", value},
        {"camera.pitch_degrees", "Pitch", "Camera pitch in degrees (positive looks up, from below the target)", fieldRef<S>([](S& s) -> auto& { return s.camera.pitchDegrees; }),
         {.min = -89, .max = 89, .ui = {.format = "%.1f deg"}}, "--pitch", value},
        {"camera.fov_degrees", "Field of view", "Vertical field of view in degrees", fieldRef<S>([](S& s) -> auto& { return s.camera.fovDegrees; }),
         {.min = 1, .max = 170, .ui = {.format = "%.0f deg"}}, "--fov", value},
        // --distance 0 frames the scene (app/cli.cpp).
        {"camera.distance", "Distance", "Camera distance from its target", fieldRef<S>([](S& s) -> auto& { return s.camera.distance; }),
         {.min = 1e-5, .max = 1e6, .special = 0, .specialMeaning = "frame the scene", .ui = {.format = "%.2f", .min = 0.1, .max = 200, .logarithmic = true}},
         "--distance"},
        {"camera.target", "Target", "The point the camera orbits", fieldRef<S>([](S& s) -> auto& { return s.camera.target; })},
    };
    appendNested(fields, materialSettingsFields(), [](S& s) -> MaterialSettings& { return s.material; }, "material.", "");
    appendNested(fields, samplingSettingsFields(), [](S& s) -> SamplingSettings& { return s.sampling; }, "sampling.", "");
    const FieldTable<S> sceneAndView{
        // --scene also takes a .gltf/.glb path (app/cli.cpp).
        {"scene.kind", "Scene", "Scene: sphere|grid|counting|sweep|none|FILE.gltf|FILE.glb",
         fieldRef<S>([](S& s) -> auto& { return s.scene.kind; }), {}, "--scene"},
        {"scene.model", "Model", "The .gltf / .glb shown by the model scene", fieldRef<S>([](S& s) -> auto& { return s.scene.modelPath; })},
        {"scene.counting_spheres", "Spheres",
         "Spheres k of the counting strip (sphere i uses N = i samples) and of the sweep (roughness 0 at the left to 1 at the right)",
         fieldRef<S>([](S& s) -> auto& { return s.scene.countingSpheres; }), {1, 64}, "--counting-spheres", value},
        {"view.mode", "View", "View: final|prefilter-mips|lut|furnace|irradiance|error", fieldRef<S>([](S& s) -> auto& { return s.view.mode; }),
         {}, "--view", value},
        {"view.background", "Background", "Background: environment|irradiance|prefilter-mip|solid",
         fieldRef<S>([](S& s) -> auto& { return s.view.background; }), {}, "--background", value},
        {"view.background_mip", "Mip", "The prefiltered mip that --background prefilter-mip shows",
         fieldRef<S>([](S& s) -> auto& { return s.view.backgroundMip; }), {0, 16}, "--background-mip", value},
        {"view.solid_colour", "Colour", "Background colour of the solid background",
         fieldRef<S>([](S& s) -> auto& { return s.view.solidColour; })},
        {"view.error_space", "Error space", "What --view error compares: linear (HDR, before tone mapping)|display (after it)",
         fieldRef<S>([](S& s) -> auto& { return s.view.errorSpace; }), {}, "--error-space", value},
        {"view.error_scale", "Colour bar top", "The relative error at the top of --view error's colour bar",
         fieldRef<S>([](S& s) -> auto& { return s.view.errorScale; }),
         {.min = 1e-6, .max = 1e6, .ui = {.format = "%.3f", .min = 0.01, .max = 4, .logarithmic = true}}, "--error-scale", value},
        {"view.reference_width", "Reference map",
         "Width of the environment the reference sums over: the loaded map halved until it fits, or a narrower map bilinearly upsampled up to it (height = width / 2)",
         fieldRef<S>([](S& s) -> auto& { return s.view.referenceWidth; }), {2, 4096}, "--reference-width", value},
        {"view.split", "Split view A | B", "Show settings B right of a divider", fieldRef<S>([](S& s) -> auto& { return s.view.split; })},
        // --split POSITION turns the split on and places the divider (app/cli.cpp).
        {"view.split_position", "Divider", "Split view at this position from the left: A (the options above) left of it, B (the --b-* options) right",
         fieldRef<S>([](S& s) -> auto& { return s.view.splitPosition; }), {.min = 0, .max = 1, .ui = {.format = "%.2f"}}, "--split"},
    };
    fields.insert(fields.end(), sceneAndView.begin(), sceneAndView.end());
    appendNested(fields, samplingSettingsFields(), [](S& s) -> SamplingSettings& { return s.view.compare; }, "view.compare.", "b-");
    fields.push_back({"view.msaa_samples", "MSAA", "Multisample anti-aliasing of the lit frame, in samples per pixel (1 is off)",
                      fieldRef<S>([](S& s) -> auto& { return s.view.msaaSamples; }), {.min = 1, .max = 8, .powerOfTwo = true}, "--msaa", value});
    return fields;
}

} // namespace

const FieldTable<FrameSettings>& frameSettingsFields()
{
    static const FieldTable<FrameSettings> fields = makeFrameFields();
    return fields;
}

std::string applyCountingSetup(FrameSettings& s)
{
    s.scene.kind = SceneKind::Counting;
    s.environment.yawDegrees = 180.0f;
    s.sampling.method = ShadingMethod::Sampled;
    s.sampling.forcedMip = 0;
    s.material.metallic = 1.0f;
    s.material.roughness = 0.5f;
    s.camera.yawDegrees = 0.0f;
    s.camera.pitchDegrees = 0.0f;
    s.camera.fovDegrees = 10.0f;
    return "builtin:lights?count=1&elevation=20";
}

std::string toJsonText(const FrameSettings& s, int indent) { return toJson(frameSettingsFields(), s).dump(indent); }

FrameSettings frameSettingsFromJsonText(const std::string& text)
{
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error& e) {
        throw std::runtime_error(std::string("not JSON: ") + e.what());
    }
    if (!j.is_object()) throw std::runtime_error("settings: expected a JSON object");
    FrameSettings s;
    fromJson(frameSettingsFields(), j, s, "settings");
    // A hand-edited preset is checked as the command line is: roughness -5 loaded as typed.
    for (const auto& field : frameSettingsFields())
        if (const std::optional<std::string> problem = rangeProblem(field, s)) throw std::runtime_error("settings." + *problem);
    return s;
}

} // namespace iblab
