#pragma once
// What a bake computes and how: the plain settings struct that the UI edits, the CLI fills
// from a preset plus overrides, and the cache hashes. No GL here (the UI includes it).
//
// Conventions every consumer of a bake relies on (docs/bake.md has the long form):
//  - cube faces in GL order +X, -X, +Y, -Y, +Z, -Z, texel (x, row) at face-local
//    ((x + 0.5) / size, (row + 0.5) / size) of conventions.glsl;
//  - prefiltered mip m holds perceptual roughness prefilterRoughnessFromMip(m, levels, layout)
//    (prefilter_lod.glsl: linear m / (levels - 1), or Filament's quadratic layout);
//  - irradiance cubes and SH irradiance hold E (a white environment of radiance 1 gives pi);
//    Lambertian outgoing radiance is albedo / pi * E;
//  - BRDF LUT texel (x, y): n.v = (x + 0.5) / size, roughness = (y + 0.5) / size, row 0 =
//    roughness near 0; R = A, G = B, B = A + B (brdf_lut.hpp).
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ibl/shading_lights.hpp"
#include "ibl/brdf.hpp"
#include "ibl/sh.hpp"
#include "io/settings_fields.hpp"

namespace iblab::bake {

// Texture storage of the cubes: half floats are what a renderer wants (half the memory and
// bandwidth, 11-bit mantissa: 5e-4 relative rounding); float is for checks that need more.
// Both are image-load/store capable (RGB16F is not).
enum class Precision { Half, Float };

enum class ShDevice { Cpu, Gpu };

// How roughness is spread over the prefiltered mips (prefilter_lod.glsl has the formulas and
// the reasons); the values are the GLSL's PREFILTER_LAYOUT_* constants.
enum class RoughnessLayout { Linear = 0, Quadratic = 1 };

struct EnvironmentCubeSettings {
    // 0: from the source, the largest power of two f with 6 f^2 <= width * height, so the
    // cube never holds more texels than the equirect it comes from (capped at maxFaceSize).
    int faceSize = 0;
    int maxFaceSize = 2048;
    bool operator==(const EnvironmentCubeSettings&) const = default;
};

struct ShSettings {
    ShDevice device = ShDevice::Gpu; // measured faster on llvmpipe (12 vs 25 ms at 1024x512); docs/bake.md
    ShWindow window = ShWindow::Hanning;
    // Window width in bands (sh.hpp); 0 picks the gentlest width that makes the windowed
    // irradiance non-negative everywhere (findNonNegativeWindowWidth).
    double windowWidth = 0.0;
    bool operator==(const ShSettings&) const = default;
};

// How the irradiance cube is baked: one method per bake, each with its settings struct
// below. Adding one: docs/architecture.md, "Where does X go".
// None bakes no cube: diffuse comes from SH9 alone (Filament's way).
enum class IrradianceMethod { None, Riemann, Importance, Moments };

// LearnOpenGL's irradiance convolution: a (theta, phi) grid of step sampleDelta radians.
// mipFiltering (not in the tutorial) reads each cell's radiance from the source mip whose
// texels are as large as the cell, so a coarse grid averages instead of point-sampling.
struct RiemannIrradianceSettings {
    int faceSize = 32;
    float sampleDelta = 0.025f;
    bool mipFiltering = false;
    float mipBias = 0.0f;
    bool operator==(const RiemannIrradianceSettings&) const = default;
};

// Cosine-weighted importance sampling with PDF-based source-mip selection. (Not in the
// default any more: read where shading reads it, between texel centres, a 6^2 face is 7%
// off on courtyard.exr, and a face large enough to interpolate well costs 10-50x the moment
// cube below for the same sampling noise; docs/bake.md.)
struct ImportanceIrradianceSettings {
    int faceSize = 6;
    int samples = 8192;
    bool mipFiltering = true;
    float mipBias = 0.0f;
    bool operator==(const ImportanceIrradianceSettings&) const = default;
};

// Irradiance as a sum over groups of environment texels, each group's flux and first moment
// per channel (irradiance_moments.comp): exact for every group above the horizon, smoothed
// across it, no sampling noise. The groups are the texels of a sourceFaceSize^2 cube; the
// output has the tutorial's 32^2 faces, which bilinear shading interpolates to within the
// tutorial's own error (docs/bake.md).
struct MomentIrradianceSettings {
    int faceSize = 32;
    int sourceFaceSize = 8;
    bool operator==(const MomentIrradianceSettings&) const = default;
};

struct PrefilterSettings {
    // The defaults were chosen by the error of what split-sum shading reads at roughness 0 to
    // 1 in steps of 0.1 (bake_accuracy.hpp, "as shaded"; docs/bake.md has the table). With 5
    // linear levels (LearnOpenGL) a roughness between two mips blends lobes 0.25 apart, and
    // that blend, not the sampling, is the largest error (12% at roughness 0.1 on
    // courtyard.exr). Filament's quadratic layout over 6 levels of a 256 face puts mips at
    // roughness 0, 0.11, 0.23, 0.37, 0.55, 1 and halves the largest error on both bundled test
    // maps; roughness 1 lands on the 8^2 face, where many samples per texel cost little.
    int faceSize = 256;
    int levels = 6;  // levels <= log2(faceSize) + 1
    RoughnessLayout layout = RoughnessLayout::Quadratic; // mip m holds prefilterRoughnessFromMip(m, levels, layout)
    int samples = 8; // GGX samples per texel at mip 1 (mip 0, roughness 0, is a copy)
    // Mip m >= 1 takes samples * sampleGrowth^(m - 1) (prefilterSamples()). Each mip has a
    // quarter of the texels of the one above and a wider lobe, so growth 3 lowers the work of
    // each further mip while giving the wide lobes, which need them most, more samples
    // (8, 24, 72, 216, 648 for mips 1-5).
    float sampleGrowth = 3.0f;
    // Per-mip factors on that rule, mips 1, 2, ..., each in [1/64, 64] (a mip the list does
    // not reach: 1).
    // The default quadruples mip 3 (roughness 0.37; 8, 24, 288, 216, 648): of the mips that
    // roughness 0.2-0.5 reads, it had the most error per sample on maps with small, very
    // bright lights (doubling it halved its error against the exact prefilter on
    // courtyard.exr and sunset.exr), and it is the one mip the split leaves to its samples
    // alone, unrefined, where bright lines a few texels wide are too many to list (16
    // meridians 6 texels wide on a 2048-wide map read 0.049 at 144 samples, 0.031 at 288; the
    // mip costs about 6 ms more on llvmpipe; docs/bake.md).
    NumberList mipSampleScale = {1.0, 1.0, 4.0};
    bool mipFiltering = true;
    // Added to 0.5 log2(Omega_s / Omega_p): 0 = LearnOpenGL's anchor, 1 = Filament's.
    float mipBias = 0.0f;
    // Mip 0 (roughness 0, a mirror) as a copy of the source mip with the same texel size
    // (one box-filtered read per texel). false: sampled like every other mip, `samples`
    // times at source lod 0, which is what LearnOpenGL does (every sample is n itself).
    bool mirrorCopy = true;
    // The bright-texel split (bright_texels.hpp; docs/bake.md, "The prefilter's estimator"):
    // the environment's brightest texels (from the float map) summed exactly by every output
    // texel, near ones light by light and far ones merged, the rest sampled. Each texel of
    // mip 1 sums at most this many far cells in its block (mip 2's 8 times as many where it has
    // a block, each further mip's 4 times the one before's, brightTexelCap); 16 is what the
    // 1.25x time budget allowed on llvmpipe (docs/bake.md). 0: every texel is sampled (the
    // anchors).
    int brightTexels = 16;
    // Texels above this multiple of the map's mean luminance are bright (fewer when the caps
    // above are reached): the sampled rest then has at most this dynamic range.
    float brightThreshold = 4.0f;
    // With the split, a mip whose base can be summed exactly over a source mip with texels at
    // most half of alpha radians across (and at least an 8 face), of at most this many texels,
    // is summed so (every texel of that mip, GGX-weighted, normalised by the weights' sum)
    // instead of sampled: 1536 (a 16^2 face) takes mips 4 and 5 of the default (roughness 0.55
    // and 1), whose sampled bases aliased large bright areas (docs/bake.md). 0 with
    // exactSumTiledTexels 0: every mip's base is sampled (0 alone hands mips 3-5 to the tiles).
    int exactSumTexels = 1536;
    // With the split, a mip whose exact-sum source has more texels than exactSumTexels but at
    // most this many is summed over per-tile cuts of it instead of sampled (exact_tiles.hpp:
    // the source's texels near each tile of 16 x 16 output texels, groups merged at their flux
    // centre further out). 6144 (a 32^2 face) takes mip 3 of the default (roughness 0.37),
    // whose 288 samples a texel leave it to where their reads fall on thin bright lines: its
    // error on the bundled maps falls from 0.002-0.007 to 0.001-0.002, at about the samples'
    // cost on llvmpipe, and no held-out map's worst mip rises (docs/bake.md, "Mip 3 summed per
    // tile"). 0 samples it.
    int exactSumTiledTexels = 6144;
    // With the split, a texel of mips 1 and 2 whose samples' luminances spread by more than
    // refineSpread x the RMS luminance of its base (the map clamped at its mip's threshold,
    // averaged in blocks as wide as the samples' median footprint, block_luminance.hpp; over
    // the sphere) is sampled again with refineFactor times as many: near the edge of a
    // large bright area that the caps leave in the base, a few samples that each read a mip
    // the edge cuts alias it (docs/bake.md, "The prefilter's estimator"). 1: never.
    // A texel is refined too where its samples' own standard error (the weighted spread of
    // their luminances over the square root of their count) exceeds refineError x that RMS:
    // texel noise, whose every texel differs from the next, reads spreads below the RMS
    // from 8 box-filtered samples and still errs by a twentieth of it. 0.035 is the per-mip
    // bound of 0.05 over sqrt(2): the texels left unrefined then hold at most half of the
    // bound's squared error. Set from the bound, not fitted to a map (docs/bake.md).
    int refineFactor = 8;
    float refineSpread = 1.0f;
    float refineError = 0.035f;
    // With the split, the lights of mips 1 and 2 listed per tile of 8 x 8 output texels
    // (tile_lights.hpp), merged where far from it, at most this many per tile: mip 1's below
    // the threshold of the block every texel sums, within 18 degrees, mip 2's all of them
    // (docs/bake.md, "Lights per tile"). 128 left thin lines (tubes, arcs) to mip 1's samples
    // that 256 sums. Four times as many where the base the cap leaves is spiky (bright_texels.hpp's
    // spikyBase). 0: none, mip 2 sums a block as the rougher mips do.
    int tileLights = 256;
    // Degrees the sample set is turned about each texel's normal (0: as generated).
    float sampleRotation = 0.0f;
    // The fitted lobe's shading lights (ibl/shading_lights.hpp): at most this many of the
    // map's brightest groups of texels, found on the float map, which shading sums exactly
    // while the fitted lobe reads the chain without them. 0: none (the plain chain).
    int shadingLights = kDefaultShadingLights;
    bool operator==(const PrefilterSettings&) const = default;
};

// The sample count of prefiltered mip `level`, capped at 65536 (1 for a copied mirror level).
int prefilterSamples(const PrefilterSettings& settings, int level);

// The split-sum LUT. Depends on no environment: baked once per (size, samples, geometry)
// and cached on its own.
struct LutSettings {
    int size = 128;
    int samples = 2048; // baked once and cached: more samples cost nothing per environment
    bool schlickGgx = true;            // GeometryTerm::SchlickGGX
    bool heightCorrelatedSmith = true; // GeometryTerm::HeightCorrelatedSmith
    bool wants(GeometryTerm term) const { return term == GeometryTerm::SchlickGGX ? schlickGgx : heightCorrelatedSmith; }
    bool operator==(const LutSettings&) const = default;
};

struct BakeSettings {
    std::string preset = "default"; // informational: where the values started
    Precision precision = Precision::Half;
    // PDF-based source-mip selection compares a sample's solid angle with the source texel's:
    // true uses the texel the sample reads (prefilter_lod.glsl, sourceLodFromPdfAt), false the
    // face average 4 pi / (6 f^2) as LearnOpenGL and Filament do.
    bool exactTexelSolidAngle = true;
    EnvironmentCubeSettings cube;
    ShSettings sh;
    IrradianceMethod irradiance = IrradianceMethod::Moments;
    RiemannIrradianceSettings riemann;
    ImportanceIrradianceSettings importance;
    MomentIrradianceSettings moments;
    PrefilterSettings prefilter;
    LutSettings lut;
    // Work per bake step, in texture samples (about 20 ms on llvmpipe per million): a step
    // is a band of rows of one face of one mip, or as many whole faces as fit.
    // kUnslicedBake makes each pass one step per mip, for callers with no frame to keep.
    std::int64_t samplesPerStep = 1 << 20;
    bool operator==(const BakeSettings&) const = default;
};

inline constexpr std::int64_t kUnslicedBake = std::int64_t(1) << 62;

inline constexpr std::array<GeometryTerm, 2> kGeometryTerms{GeometryTerm::SchlickGGX, GeometryTerm::HeightCorrelatedSmith};

// LearnOpenGL's settings: cube 512, irradiance 32x32 by Riemann sum (delta 0.025, mip 0),
// prefilter 128 with 5 mips x 1024 samples, each read at the source mip its pdf picks
// (bias 0, face-average texel), LUT 512^2 x 1024 samples
// (Schlick-GGX only, as the tutorial). SH9 is computed as well (it costs milliseconds).
BakeSettings tutorialPreset();
// The fast and accurate choice (docs/bake.md has the measurements): cube sized from the
// source, SH9 for diffuse plus a 32^2 moment irradiance cube over 8^2 texel groups per face,
// prefilter 256 x 6 mips in Filament's quadratic layout
// with PDF source-mip filtering (bias 0), 8 samples at mip 1 tripling per mip, LUTs 128^2 x
// 2048 for both geometry terms (cached: they depend on no environment).
BakeSettings defaultPreset();
// How Filament and the Khronos glTF Sample Viewer bake (bake_settings.cpp says where each
// value comes from); with tutorialPreset() they are the bake side of the convention presets.
BakeSettings filamentPreset();
BakeSettings gltfViewerPreset();
std::vector<std::string> presetNames();
// Throws iblab::Error naming the preset and the valid ones.
BakeSettings presetByName(std::string_view name);

// Throws iblab::Error ("bake settings: prefilter.levels: 9 levels need a face of at least
// 256, got 128") for values no bake can use.
void validate(const BakeSettings& settings);

// The face size the environment cube gets for a width x height equirect.
int environmentFaceSize(const EnvironmentCubeSettings& settings, int width, int height);
// The face size a bake with these settings gives it: as for the map upsampled by
// bakeSourceUpsampleFactor, so that a coarse map's cube is as fine as mip 1's lobe needs (the
// cube's texels are the map's bilinear reads either way).
int bakeEnvironmentFaceSize(const BakeSettings& settings, int width, int height);
// The face size of the irradiance cube settings.irradiance bakes (0 for None).
int irradianceFaceSize(const BakeSettings& settings);

// Every setting's description (io/settings_fields.hpp), in the order JSON writes them.
const FieldTable<BakeSettings>& bakeSettingsFields();

// Every field, as a JSON object (stable key order). The cache key hashes it.
std::string toJsonText(const BakeSettings& settings, int indent = -1);
// The LUT's own settings for one geometry term, as JSON (its cache key and file metadata).
std::string lutJsonText(int size, int samples, GeometryTerm term, bool multiscatterChannel);

// The roughness prefiltered mip `level` holds, and its inverse, for these settings.
float prefilterMipRoughness(const PrefilterSettings& settings, int level);

// How many times finer than a map of this width the bake reads it
// (upsampleEquirectBilinear, the map as the sky and the GPU's sampler read it, each texel's
// flux kept): enough
// for a sum over its texels to resolve mip 1's lobe, as the reference's sums do
// (referenceUpsampleFactor). The job bakes from that upsample (its cube, SH, lights and
// bases alike); from the map's own texels a coarse map's cube is coarser than that lobe and
// each bright texel a point light wider than it: builtin:sun 160 wide read 0.116 at mip 1
// (0.215 against the upsampled reference). The lights alone from the upsample, with a finer
// cube but the rest from the map's texels, read 0.34 (not looked into: the bases near the
// lights are resampled from the map as uploaded). 1 where the map is fine enough or the
// prefilter has no rough mip; never more than it takes to reach 1024 wide.
int bakeSourceUpsampleFactor(const PrefilterSettings& settings, int width);

} // namespace iblab::bake

namespace iblab {
template <>
struct EnumNames<bake::Precision> {
    static constexpr std::array<EnumName<bake::Precision>, 2> entries{{{bake::Precision::Half, "half"}, {bake::Precision::Float, "float"}}};
};
template <>
struct EnumNames<bake::ShDevice> {
    static constexpr std::array<EnumName<bake::ShDevice>, 2> entries{{{bake::ShDevice::Cpu, "cpu"}, {bake::ShDevice::Gpu, "gpu"}}};
};
// The names are also the irradiance cube's file (irradiance_<name>.exr) and its key in the
// accuracy report (cube_<name>).
template <>
struct EnumNames<bake::IrradianceMethod> {
    static constexpr std::array<EnumName<bake::IrradianceMethod>, 4> entries{{{bake::IrradianceMethod::None, "none"},
                                                                             {bake::IrradianceMethod::Riemann, "riemann"},
                                                                             {bake::IrradianceMethod::Importance, "importance"},
                                                                             {bake::IrradianceMethod::Moments, "moments"}}};
};
template <>
struct EnumNames<bake::RoughnessLayout> {
    static constexpr std::array<EnumName<bake::RoughnessLayout>, 2> entries{
        {{bake::RoughnessLayout::Linear, "linear"}, {bake::RoughnessLayout::Quadratic, "quadratic"}}};
};
} // namespace iblab
