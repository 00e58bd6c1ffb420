#include "bake/bake_settings.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include <nlohmann/json.hpp>

#include "ibl/prefilter_lod.hpp"
#include "io/error.hpp"

namespace iblab::bake {
namespace {

void require(bool ok, std::string_view field, const std::string& problem)
{
    if (!ok)
        throw Error("bake settings", std::string(field) + ": " + problem);
}

std::string got(double v)
{
    nlohmann::json j = v;
    return "got " + j.dump();
}

} // namespace

BakeSettings tutorialPreset()
{
    BakeSettings s;
    s.preset = "tutorial";
    s.cube.faceSize = 512;
    s.riemann = {.enabled = true, .faceSize = 32, .sampleDelta = 0.025f, .mipFiltering = false, .mipBias = 0.0f};
    s.moments.enabled = false;
    // LearnOpenGL's prefilter samples every mip, the mirror level included (below).
    s.prefilter = {.faceSize = 128,
                   .levels = 5,
                   .layout = RoughnessLayout::Linear,
                   .samples = 1024,
                   .sampleGrowth = 1.0f,
                   .mipFiltering = false,
                   .mipBias = 0.0f,
                   .mirrorCopy = false};
    s.lut = {.size = 512, .samples = 1024, .schlickGgx = true, .heightCorrelatedSmith = false};
    return s;
}

// Filament's IBL as cmgen and its IBLPrefilterContext set it up (Filament.md.html, "Image
// based lights"): a 256 cube, roughness laid out quadratically over the mips down to the 16
// face (iblRoughnessOneLevel = 4, so 5 levels), filtered importance sampling with K = 4
// (bias +1) against the face-average texel, a DFG LUT with the height-correlated Smith term
// and multiple-scattering energy compensation, SH9 for diffuse. The sample count is ours
// (Filament's varies by tool and version): 1024, LearnOpenGL's, so that the layout and the
// bias are what differs.
BakeSettings filamentPreset()
{
    BakeSettings s;
    s.preset = "filament";
    s.exactTexelSolidAngle = false;
    s.cube.faceSize = 256;
    s.moments.enabled = false;
    s.prefilter = {.faceSize = 256,
                   .levels = 5,
                   .layout = RoughnessLayout::Quadratic,
                   .samples = 1024,
                   .sampleGrowth = 1.0f,
                   .mipFiltering = true,
                   .mipBias = 1.0f,
                   .mirrorCopy = true};
    s.lut = {.size = 128, .samples = 1024, .schlickGgx = false, .heightCorrelatedSmith = true};
    return s;
}

// The Khronos glTF Sample Viewer's ibl_sampler.js: a 256 cube, 1024 GGX samples per texel,
// mips down to the 16 face (lowestMipLevel 4: 5 levels) with roughness linear in the mip,
// a Lambertian cube by 2048 cosine samples (its face size, 32, is ours), and the source lod
// 0.5 log2(6 w^2 / (N pdf)) + lodBias (0): Krivanek's formula without the 4 pi of the texel's
// solid angle, which is the face-average formula with a bias of 0.5 log2(4 pi) = +1.83 mips.
// Its LUT (lut_ggx.png) uses the height-correlated Smith term; no energy compensation.
BakeSettings gltfViewerPreset()
{
    BakeSettings s;
    s.preset = "gltf-viewer";
    s.exactTexelSolidAngle = false;
    s.cube.faceSize = 256;
    s.importance = {.enabled = true, .faceSize = 32, .samples = 2048, .mipFiltering = true, .mipBias = 1.8257f};
    s.moments.enabled = false;
    s.prefilter = {.faceSize = 256,
                   .levels = 5,
                   .layout = RoughnessLayout::Linear,
                   .samples = 1024,
                   .sampleGrowth = 1.0f,
                   .mipFiltering = true,
                   .mipBias = 1.8257f,
                   .mirrorCopy = false};
    s.lut = {.size = 128, .samples = 1024, .schlickGgx = false, .heightCorrelatedSmith = true};
    return s;
}

BakeSettings defaultPreset()
{
    BakeSettings s; // the member initialisers are the default preset
    s.preset = "default";
    return s;
}

std::vector<std::string> presetNames() { return {"default", "tutorial", "filament", "gltf-viewer"}; }

BakeSettings presetByName(std::string_view name)
{
    if (name == "default")
        return defaultPreset();
    if (name == "tutorial")
        return tutorialPreset();
    if (name == "filament")
        return filamentPreset();
    if (name == "gltf-viewer")
        return gltfViewerPreset();
    throw Error("preset \"" + std::string(name) + "\"", "unknown preset; expected default, tutorial, filament or gltf-viewer");
}

int prefilterSamples(const PrefilterSettings& settings, int level)
{
    if (level == 0)
        return settings.mirrorCopy ? 1 : settings.samples;
    const double n = double(settings.samples) * std::pow(double(settings.sampleGrowth), double(std::max(level - 1, 0)));
    return int(std::clamp(std::lround(n), 1l, 65536l));
}

int environmentFaceSize(const EnvironmentCubeSettings& settings, int width, int height)
{
    if (settings.faceSize > 0)
        return settings.faceSize;
    // Largest power of two f with 6 f^2 <= W H.
    const double limit = std::sqrt(double(width) * double(height) / 6.0);
    int f = 1;
    while (2.0 * f <= limit && 2 * f <= settings.maxFaceSize)
        f *= 2;
    return f;
}

void validate(const BakeSettings& s)
{
    auto isPow2 = [](int v) { return v > 0 && std::has_single_bit(unsigned(v)); };
    require(s.cube.faceSize == 0 || (s.cube.faceSize >= 4 && s.cube.faceSize <= 8192), "cube.faceSize",
            "must be 0 (from the source) or 4..8192, " + got(s.cube.faceSize));
    require(s.cube.maxFaceSize >= 4 && s.cube.maxFaceSize <= 8192, "cube.maxFaceSize", "must be 4..8192, " + got(s.cube.maxFaceSize));
    require(s.sh.windowWidth >= 0.0, "sh.windowWidth", "must be >= 0 (0 = automatic), " + got(s.sh.windowWidth));
    require(s.riemann.faceSize >= 1 && s.riemann.faceSize <= 1024, "riemann.faceSize", "must be 1..1024, " + got(s.riemann.faceSize));
    require(s.riemann.sampleDelta >= 0.001f && s.riemann.sampleDelta <= 1.0f, "riemann.sampleDelta",
            "must be 0.001..1 radians, " + got(s.riemann.sampleDelta));
    require(s.importance.faceSize >= 1 && s.importance.faceSize <= 1024, "importance.faceSize",
            "must be 1..1024, " + got(s.importance.faceSize));
    require(s.importance.samples >= 1 && s.importance.samples <= 65536, "importance.samples",
            "must be 1..65536, " + got(s.importance.samples));
    require(std::isfinite(s.importance.mipBias), "importance.mipBias", "must be finite");
    require(s.moments.faceSize >= 1 && s.moments.faceSize <= 1024, "moments.faceSize", "must be 1..1024, " + got(s.moments.faceSize));
    require(s.moments.sourceFaceSize >= 1 && s.moments.sourceFaceSize <= 64, "moments.sourceFaceSize",
            "must be 1..64, " + got(s.moments.sourceFaceSize));
    require(isPow2(s.prefilter.faceSize) && s.prefilter.faceSize <= 4096, "prefilter.faceSize",
            "must be a power of two up to 4096, " + got(s.prefilter.faceSize));
    const int maxLevels = std::bit_width(unsigned(std::max(s.prefilter.faceSize, 1)));
    require(s.prefilter.levels >= 1 && s.prefilter.levels <= maxLevels, "prefilter.levels",
            "must be 1.." + std::to_string(maxLevels) + " for a face of " + std::to_string(s.prefilter.faceSize) + ", " +
                got(s.prefilter.levels));
    require(s.prefilter.samples >= 1 && s.prefilter.samples <= 65536, "prefilter.samples",
            "must be 1..65536, " + got(s.prefilter.samples));
    require(std::isfinite(s.prefilter.mipBias), "prefilter.mipBias", "must be finite");
    require(s.prefilter.sampleGrowth >= 1.0f && s.prefilter.sampleGrowth <= 8.0f, "prefilter.sampleGrowth",
            "must be 1..8, " + got(s.prefilter.sampleGrowth));
    require(std::isfinite(s.riemann.mipBias), "riemann.mipBias", "must be finite");
    require(s.lut.size >= 1 && s.lut.size <= 4096, "lut.size", "must be 1..4096, " + got(s.lut.size));
    require(s.lut.samples >= 1 && s.lut.samples <= 1 << 20, "lut.samples", "must be 1..1048576, " + got(s.lut.samples));
    require(s.samplesPerStep >= 1024, "samplesPerStep", "must be >= 1024, " + got(double(s.samplesPerStep)));
}

std::string toJsonText(const BakeSettings& s, int indent)
{
    nlohmann::ordered_json j;
    j["preset"] = s.preset;
    j["precision"] = precisionName(s.precision);
    j["exact_texel_solid_angle"] = s.exactTexelSolidAngle;
    j["cube"] = {{"face_size", s.cube.faceSize}, {"max_face_size", s.cube.maxFaceSize}};
    j["sh"] = {{"device", shDeviceName(s.sh.device)}, {"window", shWindowName(s.sh.window)}, {"window_width", s.sh.windowWidth}};
    j["irradiance_riemann"] = {
        {"enabled", s.riemann.enabled}, {"face_size", s.riemann.faceSize}, {"sample_delta", s.riemann.sampleDelta},
        {"mip_filtering", s.riemann.mipFiltering}, {"mip_bias", s.riemann.mipBias}};
    j["irradiance_importance"] = {{"enabled", s.importance.enabled},
                                  {"face_size", s.importance.faceSize},
                                  {"samples", s.importance.samples},
                                  {"mip_filtering", s.importance.mipFiltering},
                                  {"mip_bias", s.importance.mipBias}};
    j["irradiance_moments"] = {
        {"enabled", s.moments.enabled}, {"face_size", s.moments.faceSize}, {"source_face_size", s.moments.sourceFaceSize}};
    j["prefilter"] = {{"face_size", s.prefilter.faceSize},
                      {"levels", s.prefilter.levels},
                      {"samples", s.prefilter.samples},
                      {"sample_growth", s.prefilter.sampleGrowth},
                      {"mip_filtering", s.prefilter.mipFiltering},
                      {"mip_bias", s.prefilter.mipBias},
                      {"mirror_copy", s.prefilter.mirrorCopy},
                      {"layout", roughnessLayoutName(s.prefilter.layout)},
                      {"roughness_per_mip", s.prefilter.layout == RoughnessLayout::Quadratic
                                                ? "1 - sqrt(1 - mip / (levels - 1))"
                                                : "mip / (levels - 1)"}};
    j["lut"] = {{"size", s.lut.size},
                {"samples", s.lut.samples},
                {"schlick_ggx", s.lut.schlickGgx},
                {"height_correlated_smith", s.lut.heightCorrelatedSmith}};
    j["samples_per_step"] = s.samplesPerStep;
    return j.dump(indent);
}

std::string lutJsonText(int size, int samples, GeometryTerm term, bool multiscatterChannel)
{
    nlohmann::ordered_json j;
    j["kind"] = "brdf_lut";
    j["size"] = size;
    j["samples"] = samples;
    j["geometry"] = geometryTermName(term);
    j["x"] = "NdotV = (i + 0.5) / size";
    j["y"] = "perceptual roughness = (j + 0.5) / size; first scanline = roughness near 0";
    j["channels"] = multiscatterChannel ? "R = A (scale), G = B (bias), B = A + B" : "R = A (scale), G = B (bias), B = 0";
    return j.dump();
}

std::string_view precisionName(Precision p) { return p == Precision::Half ? "half" : "float"; }
std::string_view shDeviceName(ShDevice d) { return d == ShDevice::Cpu ? "cpu" : "gpu"; }
std::string_view shWindowName(ShWindow w)
{
    switch (w) {
    case ShWindow::None: return "none";
    case ShWindow::Hanning: return "hanning";
    case ShWindow::Lanczos: return "lanczos";
    }
    return "none";
}

std::string_view roughnessLayoutName(RoughnessLayout layout) { return layout == RoughnessLayout::Quadratic ? "quadratic" : "linear"; }

std::optional<RoughnessLayout> parseRoughnessLayout(std::string_view name)
{
    if (name == "linear") return RoughnessLayout::Linear;
    if (name == "quadratic") return RoughnessLayout::Quadratic;
    return std::nullopt;
}

static_assert(int(RoughnessLayout::Linear) == PREFILTER_LAYOUT_LINEAR && int(RoughnessLayout::Quadratic) == PREFILTER_LAYOUT_QUADRATIC);

float prefilterMipRoughness(const PrefilterSettings& settings, int level)
{
    return prefilterRoughnessFromMip(float(level), float(settings.levels), int(settings.layout));
}

std::optional<Precision> parsePrecision(std::string_view name)
{
    if (name == "half") return Precision::Half;
    if (name == "float") return Precision::Float;
    return std::nullopt;
}

std::optional<ShDevice> parseShDevice(std::string_view name)
{
    if (name == "cpu") return ShDevice::Cpu;
    if (name == "gpu") return ShDevice::Gpu;
    return std::nullopt;
}

std::optional<ShWindow> parseShWindow(std::string_view name)
{
    if (name == "none") return ShWindow::None;
    if (name == "hanning") return ShWindow::Hanning;
    if (name == "lanczos") return ShWindow::Lanczos;
    return std::nullopt;
}

std::optional<GeometryTerm> parseGeometryTerm(std::string_view name)
{
    if (name == "schlick" || name == "schlick-ggx") return GeometryTerm::SchlickGGX;
    if (name == "correlated" || name == "height-correlated-smith") return GeometryTerm::HeightCorrelatedSmith;
    return std::nullopt;
}

} // namespace iblab::bake
