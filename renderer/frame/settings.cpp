#include "frame/settings.hpp"

#include <array>
#include <stdexcept>
#include <utility>

#include <nlohmann/json.hpp>

namespace iblab {
namespace {

// One table per enum: the single place a name is spelled.
template <typename Enum, std::size_t N>
using NameTable = std::array<std::pair<Enum, std::string_view>, N>;

constexpr NameTable<ShadingMethod, 2> kShadingMethods{{{ShadingMethod::SplitSum, "splitsum"}, {ShadingMethod::Sampled, "sampled"}}};
constexpr NameTable<SceneKind, 6> kSceneKinds{{{SceneKind::Sphere, "sphere"},
                                               {SceneKind::None, "none"},
                                               {SceneKind::Grid, "grid"},
                                               {SceneKind::Counting, "counting"},
                                               {SceneKind::Sweep, "sweep"},
                                               {SceneKind::Model, "model"}}};
constexpr NameTable<ViewMode, 6> kViewModes{{{ViewMode::Final, "final"},
                                             {ViewMode::PrefilterMips, "prefilter-mips"},
                                             {ViewMode::Lut, "lut"},
                                             {ViewMode::Furnace, "furnace"},
                                             {ViewMode::Irradiance, "irradiance"},
                                             {ViewMode::Error, "error"}}};
constexpr NameTable<BackgroundMode, 4> kBackgroundModes{{{BackgroundMode::Environment, "environment"},
                                                         {BackgroundMode::Irradiance, "irradiance"},
                                                         {BackgroundMode::PrefilterMip, "prefilter-mip"},
                                                         {BackgroundMode::SolidColour, "solid"}}};
constexpr NameTable<DiffuseSource, 3> kDiffuseSources{
    {{DiffuseSource::Sh9, "sh9"}, {DiffuseSource::Sh9Plain, "sh9-plain"}, {DiffuseSource::IrradianceCube, "irradiance-cube"}}};
constexpr NameTable<GeometryTerm, 2> kGeometryTerms{
    {{GeometryTerm::SchlickGGX, "schlick"}, {GeometryTerm::HeightCorrelatedSmith, "correlated"}}};
constexpr NameTable<ErrorSpace, 2> kErrorSpaces{{{ErrorSpace::Linear, "linear"}, {ErrorSpace::Display, "display"}}};

template <typename Enum, std::size_t N>
std::string_view nameOf(const NameTable<Enum, N>& table, Enum value)
{
    for (const auto& [e, name] : table)
        if (e == value) return name;
    return "?";
}

template <typename Enum, std::size_t N>
bool parseName(const NameTable<Enum, N>& table, std::string_view name, Enum& value)
{
    for (const auto& [e, n] : table)
        if (n == name) {
            value = e;
            return true;
        }
    return false;
}

using Json = nlohmann::ordered_json;

Json vec3Json(glm::vec3 v) { return Json::array({v.x, v.y, v.z}); }

// Reads object[key] into target when present; names the full key path on a type error.
class Reader {
public:
    Reader(const nlohmann::json& object, std::string path) : object_(object), path_(std::move(path)) {}

    template <typename T>
    void read(const char* key, T& target) const
    {
        if (!object_.contains(key)) return;
        try {
            if constexpr (std::is_same_v<T, glm::vec3>) {
                const auto& a = object_.at(key);
                if (!a.is_array() || a.size() != 3) throw std::runtime_error("expected [r, g, b]");
                target = glm::vec3(a[0].get<float>(), a[1].get<float>(), a[2].get<float>());
            } else {
                target = object_.at(key).get<T>();
            }
        } catch (const std::exception& e) {
            throw std::runtime_error(path_ + "." + key + ": " + e.what());
        }
    }

    template <typename Enum, std::size_t N>
    void readName(const char* key, const NameTable<Enum, N>& table, Enum& target) const
    {
        std::string name;
        read(key, name);
        if (!name.empty() && !parseName(table, name, target)) throw std::runtime_error(path_ + "." + key + ": unknown value \"" + name + "\"");
    }

    Reader child(const char* key) const
    {
        static const nlohmann::json empty = nlohmann::json::object();
        return {object_.contains(key) ? object_.at(key) : empty, path_ + "." + key};
    }

private:
    const nlohmann::json& object_;
    std::string path_;
};

} // namespace

std::string_view shadingMethodName(ShadingMethod m) { return nameOf(kShadingMethods, m); }
bool parseShadingMethod(std::string_view n, ShadingMethod& m) { return parseName(kShadingMethods, n, m); }
std::string_view sceneKindName(SceneKind k) { return nameOf(kSceneKinds, k); }
bool parseSceneKind(std::string_view n, SceneKind& k) { return parseName(kSceneKinds, n, k); }
std::string_view viewModeName(ViewMode m) { return nameOf(kViewModes, m); }
bool parseViewMode(std::string_view n, ViewMode& m) { return parseName(kViewModes, n, m); }
std::string_view backgroundModeName(BackgroundMode m) { return nameOf(kBackgroundModes, m); }
bool parseBackgroundMode(std::string_view n, BackgroundMode& m) { return parseName(kBackgroundModes, n, m); }
std::string_view diffuseSourceName(DiffuseSource s) { return nameOf(kDiffuseSources, s); }
bool parseDiffuseSource(std::string_view n, DiffuseSource& s) { return parseName(kDiffuseSources, n, s); }
std::string_view geometryTermShortName(GeometryTerm t) { return nameOf(kGeometryTerms, t); }
bool parseGeometryTerm(std::string_view n, GeometryTerm& t) { return parseName(kGeometryTerms, n, t); }
std::string_view errorSpaceName(ErrorSpace s) { return nameOf(kErrorSpaces, s); }
bool parseErrorSpace(std::string_view n, ErrorSpace& s) { return parseName(kErrorSpaces, n, s); }

bool sceneDemandsExactSampleCount(const SceneSettings& scene) { return scene.kind == SceneKind::Counting; }

bool keepsExactSampleCount(const FrameSettings& settings)
{
    return settings.sampling.freezeSampleSet || sceneDemandsExactSampleCount(settings.scene);
}

namespace {

// The sampling block is written twice: the frame's own and the split view's comparison.
Json samplingJson(const SamplingSettings& s)
{
    return {{"method", std::string(shadingMethodName(s.method))},
            {"samples", s.samples},
            {"forced_mip", s.forcedMip},
            {"pdf_mip_filtering", s.pdfMipFiltering},
            {"mip_bias", s.mipBias},
            {"geometry", std::string(geometryTermShortName(s.geometry))},
            {"diffuse", std::string(diffuseSourceName(s.diffuse))},
            {"cosine_sampled_diffuse", s.cosineSampledDiffuse},
            {"multiscatter", s.multiscatter},
            {"rough_fresnel_on_lut", s.roughFresnelOnLut},
            {"normalize_by_accepted", s.normalizeByAccepted},
            {"freeze_sample_set", s.freezeSampleSet}};
}

void readSampling(const Reader& sampling, SamplingSettings& s)
{
    sampling.readName("method", kShadingMethods, s.method);
    sampling.read("samples", s.samples);
    sampling.read("forced_mip", s.forcedMip);
    sampling.read("pdf_mip_filtering", s.pdfMipFiltering);
    sampling.read("mip_bias", s.mipBias);
    sampling.readName("geometry", kGeometryTerms, s.geometry);
    sampling.readName("diffuse", kDiffuseSources, s.diffuse);
    sampling.read("cosine_sampled_diffuse", s.cosineSampledDiffuse);
    sampling.read("multiscatter", s.multiscatter);
    sampling.read("rough_fresnel_on_lut", s.roughFresnelOnLut);
    sampling.read("normalize_by_accepted", s.normalizeByAccepted);
    sampling.read("freeze_sample_set", s.freezeSampleSet);
}

} // namespace

std::string toJsonText(const FrameSettings& s, int indent)
{
    Json j;
    j["environment"] = {{"source", s.environment.source}, {"yaw_degrees", s.environment.yawDegrees}, {"intensity_ev", s.environment.intensityEv}};
    j["tone_map"] = {{"operator", std::string(toneMapOperatorName(s.toneMap.op))}, {"exposure_ev", s.toneMap.exposureEv}};
    j["camera"] = {{"yaw_degrees", s.camera.yawDegrees},
                   {"pitch_degrees", s.camera.pitchDegrees},
                   {"fov_degrees", s.camera.fovDegrees},
                   {"distance", s.camera.distance},
                   {"target", vec3Json(s.camera.target)}};
    j["material"] = {{"override_model", s.material.overrideModel},
                     {"base_color", vec3Json(s.material.baseColor)},
                     {"metallic", s.material.metallic},
                     {"roughness", s.material.roughness},
                     {"ambient_occlusion", s.material.ambientOcclusion},
                     {"specular", s.material.specular}};
    j["sampling"] = samplingJson(s.sampling);
    j["scene"] = {{"kind", std::string(sceneKindName(s.scene.kind))}, {"model", s.scene.modelPath}, {"counting_spheres", s.scene.countingSpheres}};
    j["view"] = {{"mode", std::string(viewModeName(s.view.mode))},
                 {"background", std::string(backgroundModeName(s.view.background))},
                 {"background_mip", s.view.backgroundMip},
                 {"solid_colour", vec3Json(s.view.solidColour)},
                 {"error_space", std::string(errorSpaceName(s.view.errorSpace))},
                 {"error_scale", s.view.errorScale},
                 {"reference_width", s.view.referenceWidth},
                 {"split", s.view.split},
                 {"split_position", s.view.splitPosition},
                 {"compare", samplingJson(s.view.compare)},
                 {"msaa_samples", s.view.msaaSamples}};
    return j.dump(indent);
}

FrameSettings frameSettingsFromJsonText(const std::string& text)
{
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error& e) {
        throw std::runtime_error(std::string("not JSON: ") + e.what());
    }
    if (!j.is_object()) throw std::runtime_error("settings: expected a JSON object");
    const Reader root(j, "settings");
    FrameSettings s;
    const Reader environment = root.child("environment");
    environment.read("source", s.environment.source);
    environment.read("yaw_degrees", s.environment.yawDegrees);
    environment.read("intensity_ev", s.environment.intensityEv);

    const Reader toneMap = root.child("tone_map");
    std::string op;
    toneMap.read("operator", op);
    if (!op.empty()) {
        const auto parsed = parseToneMapOperator(op);
        if (!parsed) throw std::runtime_error("settings.tone_map.operator: unknown value \"" + op + "\"");
        s.toneMap.op = *parsed;
    }
    toneMap.read("exposure_ev", s.toneMap.exposureEv);

    const Reader camera = root.child("camera");
    camera.read("yaw_degrees", s.camera.yawDegrees);
    camera.read("pitch_degrees", s.camera.pitchDegrees);
    camera.read("fov_degrees", s.camera.fovDegrees);
    camera.read("distance", s.camera.distance);
    camera.read("target", s.camera.target);

    const Reader material = root.child("material");
    material.read("override_model", s.material.overrideModel);
    material.read("base_color", s.material.baseColor);
    material.read("metallic", s.material.metallic);
    material.read("roughness", s.material.roughness);
    material.read("ambient_occlusion", s.material.ambientOcclusion);
    material.read("specular", s.material.specular);

    readSampling(root.child("sampling"), s.sampling);

    const Reader scene = root.child("scene");
    scene.readName("kind", kSceneKinds, s.scene.kind);
    scene.read("model", s.scene.modelPath);
    scene.read("counting_spheres", s.scene.countingSpheres);

    const Reader view = root.child("view");
    view.readName("mode", kViewModes, s.view.mode);
    view.readName("background", kBackgroundModes, s.view.background);
    view.read("background_mip", s.view.backgroundMip);
    view.read("solid_colour", s.view.solidColour);
    view.readName("error_space", kErrorSpaces, s.view.errorSpace);
    view.read("error_scale", s.view.errorScale);
    view.read("reference_width", s.view.referenceWidth);
    view.read("split", s.view.split);
    view.read("split_position", s.view.splitPosition);
    readSampling(view.child("compare"), s.view.compare);
    view.read("msaa_samples", s.view.msaaSamples);
    return s;
}

} // namespace iblab
