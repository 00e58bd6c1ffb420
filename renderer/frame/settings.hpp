#pragma once
// The plain parameter structs that the UI edits, the CLI fills and the renderer reads.
// Everything a screenshot needs to be reproduced is in here and serialises to JSON, which
// is also the lab's preset format.
#include <string>
#include <string_view>

#include <glm/vec3.hpp>

#include "ibl/brdf.hpp"
#include "ibl/tonemap.hpp"
#include "io/settings_fields.hpp"

namespace iblab {

struct EnvironmentSettings {
    std::string source;       // a file path or builtin:NAME
    float yawDegrees = 0.0f;  // rotation about +Y; +90 brings what was at +X in front of the default camera
    float intensityEv = 0.0f; // radiance scale in stops
    bool operator==(const EnvironmentSettings&) const = default;
};

struct ToneMapSettings {
    ToneMapOperator op = ToneMapOperator::AcesHill;
    float exposureEv = 0.0f;
    bool operator==(const ToneMapSettings&) const = default;
};

// An orbit camera around a target; at yaw = pitch = 0 it looks down -Z.
struct CameraSettings {
    float yawDegrees = 0.0f;   // positive turns right: +90 looks down +X
    float pitchDegrees = 0.0f; // positive looks up
    float fovDegrees = 45.0f;  // vertical field of view
    float distance = 3.5f;     // from the target, in scene units (a sphere has radius 1)
    glm::vec3 target{0.0f};
    bool operator==(const CameraSettings&) const = default;
};

// The material the sliders edit. With overrideModel off, a glTF keeps its own factors.
struct MaterialSettings {
    bool overrideModel = false; // a model shows its own materials first, in the GUI and on the command line
    glm::vec3 baseColor{0.95f, 0.64f, 0.54f}; // linear; copper-ish, so metals show colour
    float metallic = 1.0f;
    float roughness = 0.3f; // perceptual; alpha = roughness^2
    float ambientOcclusion = 1.0f;
    // Dielectric reflectance as Filament defines it: F0 = 0.16 * specular^2, so 0.5 gives
    // the common 4%.
    float specular = 0.5f;
    bool operator==(const MaterialSettings&) const = default;
};

// FittedLobe: the split sum's LUT with the prefiltered cube read where and as wide as the
// true lobe is, per (n.v, roughness) from a table fitted against the full integral (the
// "Fresnel-split fitted lobe" of docs/accuracy-study.md; common/specular_lobe.glsl).
// Reference: the full integral over the environment's texels (the reference renderer), the
// ground truth the real-time methods approximate; progressive in the GUI, complete headless.
enum class ShadingMethod { SplitSum, Sampled, FittedLobe, Reference };
template <>
struct EnumNames<ShadingMethod> {
    static constexpr std::array<EnumName<ShadingMethod>, 4> entries{{{ShadingMethod::SplitSum, "splitsum"},
                                                                      {ShadingMethod::Sampled, "sampled"},
                                                                      {ShadingMethod::FittedLobe, "fitted-lobe"},
                                                                      {ShadingMethod::Reference, "reference"}}};
};
// Where the split sum reads the prefiltered cube: at the reflection R (Karis 2013), or at a
// dominant direction between R and N that follows the true lobe's off-specular peak:
// Frostbite's (Lagarde & de Rousiers 2014, listing 22) or Filament's (mix(R, N, alpha^2)).
// The formulas: common/specular_lobe.glsl; their measured error: docs/accuracy-study.md.
enum class SpecularDirection { Reflection, Frostbite, Filament };
template <>
struct EnumNames<SpecularDirection> {
    static constexpr std::array<EnumName<SpecularDirection>, 3> entries{
        {{SpecularDirection::Reflection, "reflection"}, {SpecularDirection::Frostbite, "frostbite"}, {SpecularDirection::Filament, "filament"}}};
};
// The multiple-scattering compensation's form, a factor on the single-scattering specular
// (E_ss = A + B from the LUT's third channel; both give exactly 1 for a white metal):
// Filament's 1 + F0 (1 / E_ss - 1) (Filament.md.html, "Energy loss in specular reflectance";
// shaders/src/surface_shading_lit.fs, getEnergyCompensationPixelParams), or Fdez-Aguera's
// 1 / (1 - F_avg (1 - E_ss)), F_avg = F0 + (1 - F0) / 21, which is FssEss + FmsEms over FssEss
// as the glTF Sample Viewer's getIBLGGXFresnel and Bevy's compute_multiscatter write it
// (docs/engine-export.md cites the lines).
enum class MultiscatterModel { Filament, FdezAguera };
template <>
struct EnumNames<MultiscatterModel> {
    static constexpr std::array<EnumName<MultiscatterModel>, 2> entries{
        {{MultiscatterModel::Filament, "filament"}, {MultiscatterModel::FdezAguera, "fdez-aguera"}}};
};
// Sh9: the bake's SH9 irradiance as it windowed it (BakeSettings::sh.window); Sh9Plain: the
// same projection without the window, so that its ringing can be seen.
enum class DiffuseSource { Sh9, Sh9Plain, IrradianceCube };
template <>
struct EnumNames<DiffuseSource> {
    static constexpr std::array<EnumName<DiffuseSource>, 3> entries{
        {{DiffuseSource::Sh9, "sh9"}, {DiffuseSource::Sh9Plain, "sh9-plain"}, {DiffuseSource::IrradianceCube, "irradiance-cube"}}};
};

// Whether the method reads the bake's prefiltered cube (the split sum's part 1).
inline bool readsPrefilteredCube(ShadingMethod method) { return method == ShadingMethod::SplitSum || method == ShadingMethod::FittedLobe; }

// The sampled method's largest N: the Hammersley table the renderer uploads holds this many.
inline constexpr int kMaxSampleCount = 1024;

struct SamplingSettings {
    // The fitted lobe: at most half the split sum's error against the full integral on every
    // bundled and unseen map of scripts/measure-lobe.sh, at the split sum's frame time
    // (docs/accuracy-study.md).
    ShadingMethod method = ShadingMethod::FittedLobe;
    int samples = 16;      // N for the sampled method, 1..1024
    int forcedMip = -1;    // -1: the lod follows roughness (split-sum) or the sample pdf (sampled)
    bool pdfMipFiltering = true;
    float mipBias = 1.0f;  // added to 0.5 log2(Omega_s / Omega_p); 0 = LearnOpenGL, 1 = Filament
    GeometryTerm geometry = GeometryTerm::HeightCorrelatedSmith;
    // The baked irradiance cube (the default bake's moment cube: 0.12% mean / 0.28% max off
    // the exact irradiance on courtyard.exr where shading reads it, SH9 5% / 25%); SH9 when
    // the bake has no cube.
    DiffuseSource diffuse = DiffuseSource::IrradianceCube;
    bool cosineSampledDiffuse = false; // sampled method: diffuse from N cosine samples instead of SH9
    // Multiple-scattering energy compensation from the LUT's third channel, on as Filament, the
    // glTF Sample Viewer, three.js, Godot and Bevy ship it (docs/engine-export.md, "Convention
    // presets against today's engines"): a rough white metal reflects 1 in the furnace instead
    // of its single-scattering albedo. The reference renderer applies the same factor with its
    // own exact E_ss, so errors against it measure the compensated BRDF.
    bool multiscatter = true;
    MultiscatterModel multiscatterModel = MultiscatterModel::Filament;
    // The fitted lobe: sum the bake's shading lights (its brightest texel groups, a sun, a
    // lamp) exactly and read the cube without them (ibl/shading_lights.hpp). A bake without
    // lights (--prefilter-shading-lights 0, an imported one) shades as without.
    bool shadingLights = true;
    // Split sum as LearnOpenGL writes it: prefiltered * (F_roughness(n.v) A + B), Fresnel applied
    // on top of the LUT that already integrates it. false: prefiltered * (F0 A + B), exact for
    // the split sum (Karis 2013). The convention presets turn it on for LearnOpenGL.
    bool roughFresnelOnLut = false;
    // Split sum: the direction it reads the prefiltered cube at. The convention presets set it
    // as each engine does (Filament's for Filament).
    SpecularDirection specularDirection = SpecularDirection::Reflection;
    // Sampled method: divide by the samples above the horizon, as LearnOpenGL's prefilter
    // does, instead of by N (unbiased); for comparing the two.
    bool normalizeByAccepted = false;
    // Sampled method: keep the one sample set of N per pixel instead of adding rotated sets
    // under accumulation, so that N is exactly what each pixel averages (see
    // keepsExactSampleCount, which also turns it on for the counting strip).
    bool freezeSampleSet = false;
    bool operator==(const SamplingSettings&) const = default;
};

// Counting: sphere i uses N = i. Sweep: every sphere uses N = SamplingSettings::samples and
// roughness runs from 0 (left) to 1 (right), so reflections merge at 0 and spread apart.
// None shows the environment alone.
enum class SceneKind { Sphere, Grid, Counting, Sweep, Model, None };
template <>
struct EnumNames<SceneKind> {
    static constexpr std::array<EnumName<SceneKind>, 6> entries{{{SceneKind::Sphere, "sphere"},
                                                                {SceneKind::None, "none"},
                                                                {SceneKind::Grid, "grid"},
                                                                {SceneKind::Counting, "counting"},
                                                                {SceneKind::Sweep, "sweep"},
                                                                {SceneKind::Model, "model"}}};
};

struct SceneSettings {
    SceneKind kind = SceneKind::Sphere;
    std::string modelPath;  // .gltf / .glb when kind == Model
    int countingSpheres = 8; // spheres in the counting strip and the roughness sweep
    bool operator==(const SceneSettings&) const = default;
};

// Error: the frame's per-pixel relative error against the reference renderer (the full
// integral over the environment's texels), in false colour.
enum class ViewMode { Final, PrefilterMips, Lut, Furnace, Irradiance, Error };
template <>
struct EnumNames<ViewMode> {
    static constexpr std::array<EnumName<ViewMode>, 6> entries{{{ViewMode::Final, "final"},
                                                               {ViewMode::PrefilterMips, "prefilter-mips"},
                                                               {ViewMode::Lut, "lut"},
                                                               {ViewMode::Furnace, "furnace"},
                                                               {ViewMode::Irradiance, "irradiance"},
                                                               {ViewMode::Error, "error"}}};
};
enum class BackgroundMode { Environment, Irradiance, PrefilterMip, SolidColour };
template <>
struct EnumNames<BackgroundMode> {
    static constexpr std::array<EnumName<BackgroundMode>, 4> entries{{{BackgroundMode::Environment, "environment"},
                                                                     {BackgroundMode::Irradiance, "irradiance"},
                                                                     {BackgroundMode::PrefilterMip, "prefilter-mip"},
                                                                     {BackgroundMode::SolidColour, "solid"}}};
};
// Where ViewMode::Error compares: the linear HDR radiance before exposure and tone mapping,
// or the display values after them (what the eye is shown).
enum class ErrorSpace { Linear, Display };
template <>
struct EnumNames<ErrorSpace> {
    static constexpr std::array<EnumName<ErrorSpace>, 2> entries{{{ErrorSpace::Linear, "linear"}, {ErrorSpace::Display, "display"}}};
};

struct ViewSettings {
    ViewMode mode = ViewMode::Final;
    BackgroundMode background = BackgroundMode::Environment;
    int backgroundMip = 2;
    glm::vec3 solidColour{0.18f};
    ErrorSpace errorSpace = ErrorSpace::Linear;
    float errorScale = 0.25f; // the relative error at the top of the colour bar
    // Width of the environment the reference sums over (height = width / 2), reached by
    // solid-angle-preserving 2x downsampling of the loaded map. 256 x 128 texels are 1.4
    // degrees wide: lobes of roughness >= 0.3 span several texels (see referenceMidpointNote).
    int referenceWidth = 256;
    // A/B split: the frame shows `sampling` left of the divider and `compare` right of it.
    bool split = false;
    float splitPosition = 0.5f; // divider, as a fraction of the width from the left
    SamplingSettings compare;
    // Samples per pixel of the lit frame (1 = no MSAA); the renderer clamps it to what the
    // driver offers. Debug views of baked data are drawn single-sampled.
    int msaaSamples = 4;
    bool operator==(const ViewSettings&) const = default;
};

struct FrameSettings {
    EnvironmentSettings environment;
    ToneMapSettings toneMap;
    CameraSettings camera;
    MaterialSettings material;
    SamplingSettings sampling;
    SceneSettings scene;
    ViewSettings view;
    bool operator==(const FrameSettings&) const = default;
};

// Whether accumulation must leave the sampled method's N samples per pixel alone: the
// freeze switch, or the counting strip, whose point is that sphere i shows exactly i
// samples (a mean of rotated sets would show i times as many reflections).
bool keepsExactSampleCount(const FrameSettings& settings);
// The scene's part of that rule: its kind demands exact counts whatever the switch says.
bool sceneDemandsExactSampleCount(const SceneSettings& scene);

// Every setting's description (io/settings_fields.hpp): JSON key, label, help, range and
// command-line option, in the order JSON writes them. Sampling's fields appear twice, under
// "sampling." and under "view.compare." (option prefix "b-").
const FieldTable<FrameSettings>& frameSettingsFields();
const FieldTable<SamplingSettings>& samplingSettingsFields();
const FieldTable<MaterialSettings>& materialSettingsFields();

// The counting strip set up so that each sphere's reflections can be counted: one small
// light (builtin:lights, behind the camera), the sampled method reading mip 0 (each sample a
// sharp reflection), a half-rough metal (the samples spread apart), a narrow field of view
// from the front. Returns the environment to load. As the README's counting example.
std::string applyCountingSetup(FrameSettings& settings);

// JSON text of the settings (screenshot metadata and sidecars, lab presets).
std::string toJsonText(const FrameSettings& settings, int indent = 2);
// Missing keys keep their defaults. Throws std::runtime_error naming the offending key.
FrameSettings frameSettingsFromJsonText(const std::string& text);

} // namespace iblab
