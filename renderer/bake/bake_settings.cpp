#include "bake/bake_settings.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "ibl/prefilter_lod.hpp"
#include "ibl/reference.hpp"
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
    s.irradiance = IrradianceMethod::Riemann;
    s.riemann = {.faceSize = 32, .sampleDelta = 0.025f, .mipFiltering = false, .mipBias = 0.0f};
    // LearnOpenGL's prefilter samples every mip, the mirror level included (below). Each
    // sample reads the source mip its pdf picks (2.2.1.prefilter.fs lines 90-98: saTexel the
    // face average of the 512 cube, mip 0.5 log2(saSample / saTexel), mip 0 at roughness 0),
    // trilinearly from the mip chain ibl_specular.cpp lines 171 and 209 set up: bias 0
    // against the face-average texel. Its two 0.0001 guards are left out: they move no
    // sample's lod by more than 0.06 mip (source_samples_test).
    s.exactTexelSolidAngle = false;
    s.prefilter = {.faceSize = 128,
                   .levels = 5,
                   .layout = RoughnessLayout::Linear,
                   .samples = 1024,
                   .sampleGrowth = 1.0f,
                   .mipSampleScale = {},
                   .mipFiltering = true,
                   .mipBias = 0.0f,
                   .mirrorCopy = false,
                   .brightTexels = 0,
                   .brightThreshold = 4.0f,
                   .shadingLights = 0};
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
    s.irradiance = IrradianceMethod::None;
    s.prefilter = {.faceSize = 256,
                   .levels = 5,
                   .layout = RoughnessLayout::Quadratic,
                   .samples = 1024,
                   .sampleGrowth = 1.0f,
                   .mipSampleScale = {},
                   .mipFiltering = true,
                   .mipBias = 1.0f,
                   .mirrorCopy = true,
                   .brightTexels = 0,
                   .brightThreshold = 4.0f,
                   .shadingLights = 0};
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
    s.irradiance = IrradianceMethod::Importance;
    s.importance = {.faceSize = 32, .samples = 2048, .mipFiltering = true, .mipBias = 1.8257f};
    s.prefilter = {.faceSize = 256,
                   .levels = 5,
                   .layout = RoughnessLayout::Linear,
                   .samples = 1024,
                   .sampleGrowth = 1.0f,
                   .mipSampleScale = {},
                   .mipFiltering = true,
                   .mipBias = 1.8257f,
                   .mirrorCopy = false,
                   .brightTexels = 0,
                   .brightThreshold = 4.0f,
                   .shadingLights = 0};
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
    const NumberList& scales = settings.mipSampleScale;
    const double scale = std::size_t(level - 1) < scales.size() ? scales[std::size_t(level - 1)] : 1.0;
    const double n = scale * double(settings.samples) * std::pow(double(settings.sampleGrowth), double(std::max(level - 1, 0)));
    return int(std::clamp(std::lround(n), 1l, 65536l));
}

int irradianceFaceSize(const BakeSettings& s)
{
    switch (s.irradiance) {
    case IrradianceMethod::None: return 0;
    case IrradianceMethod::Riemann: return s.riemann.faceSize;
    case IrradianceMethod::Importance: return s.importance.faceSize;
    case IrradianceMethod::Moments: return s.moments.faceSize;
    }
    return 0;
}

namespace {
constexpr int kMaxUpsampledBakeWidth = 1024;
} // namespace

int bakeSourceUpsampleFactor(const PrefilterSettings& settings, int width)
{
    if (settings.levels < 2 || width <= 0)
        return 1;
    const float roughness = prefilterMipRoughness(settings, 1);
    if (!(roughness > 0.0f))
        return 1;
    // Never past the first power of two at or above 1024 wide: the default's mip 1 (roughness
    // 0.106) needs 845, and a preset with a sharper mip 1 would otherwise bake a 1024-wide map
    // at 4096 (roughness 0.05), its cube 1024 wide, several times the bake's time and memory.
    int factor = referenceUpsampleFactor(width, roughness, 16);
    while (factor > 1 && width * (factor / 2) >= kMaxUpsampledBakeWidth) factor /= 2;
    return factor;
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

int bakeEnvironmentFaceSize(const BakeSettings& settings, int width, int height)
{
    const int factor = bakeSourceUpsampleFactor(settings.prefilter, width);
    return environmentFaceSize(settings.cube, width * factor, height * factor);
}

namespace {

// The bright split's fields (docs/bake.md, "The prefilter's estimator"), in the order the
// table lists them after prefilter.mirror_copy.
FieldTable<BakeSettings> brightSplitFields()
{
    using S = BakeSettings;
    constexpr CliForm value = CliForm::Value;
    return {
        {"prefilter.bright_texels", "Bright texels summed exactly",
         "Far cells of bright texels each mip-1 texel sums exactly (8x at the rougher mips; near cells light by light); the rest is sampled (0: samples all)",
         fieldRef<S>([](S& s) -> auto& { return s.prefilter.brightTexels; }), {0, 1024}, "--prefilter-bright-texels", value},
        {"prefilter.bright_threshold", "Bright texel threshold",
         "Texels above this multiple of the mean luminance are summed exactly (at most --prefilter-bright-texels of them)",
         fieldRef<S>([](S& s) -> auto& { return s.prefilter.brightThreshold; }), {0, 1e9}, "--prefilter-bright-threshold", value},
        {"prefilter.exact_sum_texels", "Exact-sum source texels",
         "With the bright split: a mip whose base fits an exact sum over a source mip of at most this many texels (texels <= alpha / 2 across, a face of 8 or more) is summed, not sampled (0: never)",
         fieldRef<S>([](S& s) -> auto& { return s.prefilter.exactSumTexels; }), {0, 1 << 16}, "--prefilter-exact-sum-texels", value},
        {"prefilter.exact_sum_tiled_texels", "Tiled exact-sum source texels",
         "With the bright split: a mip whose exact-sum source has more texels than --prefilter-exact-sum-texels but at most this many is summed over per-tile cuts of it (its texels near each tile, merged groups further out), not sampled (0: never)",
         fieldRef<S>([](S& s) -> auto& { return s.prefilter.exactSumTiledTexels; }), {0, 1 << 16}, "--prefilter-exact-sum-tiled-texels", value},
        {"prefilter.refine_factor", "Refined sample factor",
         "With the bright split: a texel of mips 1 and 2 whose samples' luminances spread by more than --prefilter-refine-spread x its base's RMS luminance is sampled again with this many times the samples (1: never)",
         fieldRef<S>([](S& s) -> auto& { return s.prefilter.refineFactor; }), {1, 64}, "--prefilter-refine-factor", value},
        {"prefilter.refine_spread", "Refine spread",
         "The spread of the sample luminances of a texel of mips 1 and 2, in units of its base's RMS luminance (the map clamped at its mip's bright threshold, averaged in blocks as wide as the samples' median footprint), above which it is sampled again (--prefilter-refine-factor)",
         fieldRef<S>([](S& s) -> auto& { return s.prefilter.refineSpread; }), {0, 1e9}, "--prefilter-refine-spread", value},
        {"prefilter.refine_error", "Refine error",
         "The standard error of the mean of a texel's samples (mips 1 and 2), in units of its base's RMS luminance, above which it is sampled again (--prefilter-refine-factor)",
         fieldRef<S>([](S& s) -> auto& { return s.prefilter.refineError; }), {0, 1e9}, "--prefilter-refine-error", value},
        {"prefilter.tile_lights", "Lights per tile",
         "With the bright split: the lights of mips 1 and 2 listed per tile of 8 x 8 texels, at most this many per tile (mip 1: below its block's threshold, within 18 degrees; 0: none)",
         fieldRef<S>([](S& s) -> auto& { return s.prefilter.tileLights; }), {0, 1024}, "--prefilter-tile-lights", value},
    };
}

// The table with the split's fields placed after prefilter.mirror_copy.
FieldTable<BakeSettings> withBrightSplitFields(FieldTable<BakeSettings> fields)
{
    const auto mirrorCopy = std::find_if(fields.begin(), fields.end(), [](const auto& f) { return f.key == "prefilter.mirror_copy"; });
    const FieldTable<BakeSettings> split = brightSplitFields();
    fields.insert(mirrorCopy == fields.end() ? fields.end() : mirrorCopy + 1, split.begin(), split.end());
    return fields;
}

} // namespace

const FieldTable<BakeSettings>& bakeSettingsFields()
{
    using S = BakeSettings;
    constexpr CliForm value = CliForm::Value;
    static const FieldTable<S> fields = withBrightSplitFields({
        {"preset", "Preset", "Where the values started (informational)", fieldRef<S>([](S& s) -> auto& { return s.preset; })},
        {"precision", "Precision", "Storage of the baked cubes: half (RGBA16F) or float (RGBA32F)", fieldRef<S>([](S& s) -> auto& { return s.precision; }), {},
         "--precision", value},
        {"exact_texel_solid_angle", "Exact texel solid angle",
         "PDF source-mip selection against the solid angle of the texel read (on) or of the face's average texel (off)",
         fieldRef<S>([](S& s) -> auto& { return s.exactTexelSolidAngle; }), {}, "--exact-texel-solid-angle", value},
        {"cube.face_size", "Cube face size", "Environment cube face size in texels",
         fieldRef<S>([](S& s) -> auto& { return s.cube.faceSize; }), {4, 8192, 0, "from the source"}, "--cube-size", value},
        {"cube.max_face_size", "Largest cube face", "Cap on the face size chosen from the source",
         fieldRef<S>([](S& s) -> auto& { return s.cube.maxFaceSize; }), {4, 8192}},
        {"sh.device", "SH9 device", "Where the SH9 projection runs: cpu or gpu", fieldRef<S>([](S& s) -> auto& { return s.sh.device; }), {},
         "--sh-device", value},
        {"sh.window", "SH9 window", "Window on the SH9 bands against ringing: none, hanning or lanczos", fieldRef<S>([](S& s) -> auto& { return s.sh.window; }),
         {}, "--sh-window", value},
        {"sh.window_width", "SH9 window width", "SH window width in bands, 0 for the gentlest one that keeps irradiance non-negative",
         fieldRef<S>([](S& s) -> auto& { return s.sh.windowWidth; }), {0, 1e6}, "--sh-window-width", value},
        {"irradiance", "Irradiance method", "How the irradiance cube is baked: none (SH9 only), riemann (LearnOpenGL), importance (cosine samples) or moments",
         fieldRef<S>([](S& s) -> auto& { return s.irradiance; }), {}, "--irradiance", value},
        {"irradiance_riemann.face_size", "Riemann face size", "Face size of the Riemann irradiance cube (--irradiance riemann)",
         fieldRef<S>([](S& s) -> auto& { return s.riemann.faceSize; }), {1, 1024}, "--riemann-size", value},
        {"irradiance_riemann.sample_delta", "Riemann sample delta", "Step of the Riemann irradiance sum in radians",
         fieldRef<S>([](S& s) -> auto& { return s.riemann.sampleDelta; }), {0.001, 1}, "--riemann-delta", value},
        {"irradiance_riemann.mip_filtering", "Riemann mip filtering", "Read each Riemann cell from the source mip matching its size",
         fieldRef<S>([](S& s) -> auto& { return s.riemann.mipFiltering; }), {}, "--riemann-mip-filter", value},
        {"irradiance_riemann.mip_bias", "Riemann mip bias", "Levels added to the source lod of the Riemann cells",
         fieldRef<S>([](S& s) -> auto& { return s.riemann.mipBias; }), {}, "--riemann-mip-bias", value},
        {"irradiance_importance.face_size", "Importance face size", "Face size of the importance-sampled irradiance cube (--irradiance importance)",
         fieldRef<S>([](S& s) -> auto& { return s.importance.faceSize; }), {1, 1024}, "--importance-size", value},
        {"irradiance_importance.samples", "Importance samples", "Cosine samples per texel of the importance-sampled irradiance cube",
         fieldRef<S>([](S& s) -> auto& { return s.importance.samples; }), {1, 65536}, "--importance-samples", value},
        {"irradiance_importance.mip_filtering", "Importance mip filtering", "PDF-based source-mip selection for the importance-sampled irradiance",
         fieldRef<S>([](S& s) -> auto& { return s.importance.mipFiltering; }), {}, "--importance-mip-filter", value},
        {"irradiance_importance.mip_bias", "Importance mip bias", "Levels added to the source lod of the importance-sampled irradiance",
         fieldRef<S>([](S& s) -> auto& { return s.importance.mipBias; }), {}, "--importance-mip-bias", value},
        {"irradiance_moments.face_size", "Moment face size", "Face size of the moment irradiance cube (--irradiance moments)",
         fieldRef<S>([](S& s) -> auto& { return s.moments.faceSize; }), {1, 1024}, "--moments-size", value},
        {"irradiance_moments.source_face_size", "Moment groups per edge", "Texel groups per face edge that the moment irradiance sums over",
         fieldRef<S>([](S& s) -> auto& { return s.moments.sourceFaceSize; }), {1, 64}, "--moments-source-size", value},
        {"prefilter.face_size", "Prefilter face size", "Face size of the prefiltered cube's mip 0",
         fieldRef<S>([](S& s) -> auto& { return s.prefilter.faceSize; }), {.min = 1, .max = 4096, .powerOfTwo = true}, "--prefilter-size", value},
        {"prefilter.levels", "Prefilter levels", "Prefiltered mips, from roughness 0 at mip 0 to 1 at the last",
         fieldRef<S>([](S& s) -> auto& { return s.prefilter.levels; }), {1, 13}, "--prefilter-levels", value},
        {"prefilter.samples", "Prefilter samples", "GGX samples per prefiltered texel at mip 1",
         fieldRef<S>([](S& s) -> auto& { return s.prefilter.samples; }), {1, 65536}, "--prefilter-samples", value},
        {"prefilter.sample_growth", "Prefilter sample growth", "Growth of the prefilter's samples per mip: mip m takes samples * growth^(m-1)",
         fieldRef<S>([](S& s) -> auto& { return s.prefilter.sampleGrowth; }), {1, 8}, "--prefilter-sample-growth", value},
        {"prefilter.mip_sample_scale", "Prefilter sample scale per mip",
         "Factors on samples * growth^(m-1) for mips 1, 2, ..., comma-separated (1,1,4, the default, quadruples mip 3; \"\" for none)",
         fieldRef<S>([](S& s) -> auto& { return s.prefilter.mipSampleScale; }), {1.0 / 64.0, 64.0}, "--prefilter-mip-sample-scale", value},
        {"prefilter.mip_filtering", "Prefilter mip filtering", "PDF-based source-mip selection for the prefilter",
         fieldRef<S>([](S& s) -> auto& { return s.prefilter.mipFiltering; }), {}, "--prefilter-mip-filter", value},
        {"prefilter.mip_bias", "Prefilter mip bias", "Levels added to the prefilter's source lod (0 as LearnOpenGL, 1 as Filament)",
         fieldRef<S>([](S& s) -> auto& { return s.prefilter.mipBias; }), {}, "--prefilter-mip-bias", value},
        {"prefilter.mirror_copy", "Mirror mip as a copy",
         "Mip 0 as a copy of the matching source mip (on), or sampled like the other mips as LearnOpenGL does (off)",
         fieldRef<S>([](S& s) -> auto& { return s.prefilter.mirrorCopy; }), {}, "--prefilter-mirror-copy", value},
        {"prefilter.shading_lights", "Shading lights",
         "The map's brightest texel groups the fitted lobe shades exactly, as lights, reading the prefiltered cube without them (0: none)",
         fieldRef<S>([](S& s) -> auto& { return s.prefilter.shadingLights; }), {0, kMaxShadingLights}, "--prefilter-shading-lights", value},
        {"prefilter.sample_rotation", "Prefilter sample rotation", "Degrees the GGX sample set is turned about each texel's normal (for checks)",
         fieldRef<S>([](S& s) -> auto& { return s.prefilter.sampleRotation; }), {-360, 360}, "--prefilter-sample-rotation", value},
        {"prefilter.layout", "Roughness layout",
         "Roughness per mip: linear (m / (levels - 1), LearnOpenGL) or quadratic (Filament: 1 - sqrt(1 - m / (levels - 1)))",
         fieldRef<S>([](S& s) -> auto& { return s.prefilter.layout; }), {}, "--prefilter-layout", value},
        {"lut.size", "LUT size", "BRDF LUT width and height in texels", fieldRef<S>([](S& s) -> auto& { return s.lut.size; }), {1, 4096}, "--lut-size", value},
        {"lut.samples", "LUT samples", "BRDF LUT samples per texel", fieldRef<S>([](S& s) -> auto& { return s.lut.samples; }), {1, 1 << 20},
         "--lut-samples", value},
        // One option, --lut-geometry schlick|correlated|both|none, sets these two (app/bake_commands.cpp).
        {"lut.schlick_ggx", "LUT for Schlick-GGX", "Bake the Schlick-GGX LUT", fieldRef<S>([](S& s) -> auto& { return s.lut.schlickGgx; })},
        {"lut.height_correlated_smith", "LUT for height-correlated Smith", "Bake the height-correlated Smith LUT",
         fieldRef<S>([](S& s) -> auto& { return s.lut.heightCorrelatedSmith; })},
        {"samples_per_step", "Samples per step",
         "Work per bake step in texture samples, as the GUI slices a bake (the largest value is one step per pass and mip)",
         fieldRef<S>([](S& s) -> auto& { return s.samplesPerStep; }), {1024, double(kUnslicedBake)}, "--step-samples", value},
    });
    return fields;
}

void validate(const BakeSettings& s)
{
    validateRanges(bakeSettingsFields(), s, "bake settings");
    // The rule that relates two fields.
    const int maxLevels = std::bit_width(unsigned(std::max(s.prefilter.faceSize, 1)));
    require(s.prefilter.levels <= maxLevels, "prefilter.levels",
            "must be 1.." + std::to_string(maxLevels) + " for a face of " + std::to_string(s.prefilter.faceSize) + ", " +
                got(s.prefilter.levels));
}

std::string toJsonText(const BakeSettings& s, int indent)
{
    nlohmann::ordered_json j = toJson(bakeSettingsFields(), s);
    // For a reader of bake.json, not read back.
    j["prefilter"]["roughness_per_mip"] =
        s.prefilter.layout == RoughnessLayout::Quadratic ? "1 - sqrt(1 - mip / (levels - 1))" : "mip / (levels - 1)";
    return j.dump(indent);
}

std::string lutJsonText(int size, int samples, GeometryTerm term, bool multiscatterChannel)
{
    nlohmann::ordered_json j;
    j["kind"] = "brdf_lut";
    j["size"] = size;
    j["samples"] = samples;
    j["geometry"] = enumName(term);
    j["x"] = "NdotV = (i + 0.5) / size";
    j["y"] = "perceptual roughness = (j + 0.5) / size; first scanline = roughness near 0";
    j["channels"] = multiscatterChannel ? "R = A (scale), G = B (bias), B = A + B" : "R = A (scale), G = B (bias), B = 0";
    return j.dump();
}

static_assert(int(RoughnessLayout::Linear) == PREFILTER_LAYOUT_LINEAR && int(RoughnessLayout::Quadratic) == PREFILTER_LAYOUT_QUADRATIC);

float prefilterMipRoughness(const PrefilterSettings& settings, int level)
{
    return prefilterRoughnessFromMip(float(level), float(settings.levels), int(settings.layout));
}

} // namespace iblab::bake
