#pragma once
// Loading and validating equirectangular HDR environments.
//
// loadEnvironment() turns a spec (a file path, or "builtin:NAME?k=v" — see
// builtin_environments.hpp) into linear-light RGB float texels that every later stage may
// trust: 2:1, at most the size cap, all components finite and >= 0. Whatever had to be
// changed on the way is reported (TexelRepairReport, warnings), never silently hidden.
// Failures throw iblab::Error with a one-line message naming the file; nothing else
// changes, so a caller keeps the environment it had.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "ibl/image.hpp"
#include "io/imported_bake.hpp"

namespace iblab {

// What repairTexels() found and fixed. Counts are of components (R, G, B separately).
//
// Energy: each texel has the solid angle of its equirect cell,
//   Omega(y) = (2 pi / W) (cos(theta_top) - cos(theta_bottom)),  theta = pi * row / H,
// and a component value c contributes  Omega * k_c * c  with Rec. 709 luminance weights
// k = (0.2126, 0.7152, 0.0722). Over all FINITE components:
//   positiveEnergy = sum Omega k_c max(c, 0)
//   negativeEnergy = sum Omega k_c max(-c, 0)
// Clamping negatives to 0 changes the map's total luminance integral by negativeEnergy;
// negativeEnergyShare() = negativeEnergy / positiveEnergy is that change relative to the
// positive light in the map (the pmndrs "sky" map: about 10%). NaN and Inf components are
// excluded from both sums (an Inf has no meaningful energy) and counted on their own.
// The sRGB EOTF (IEC 61966-2-1): an encoded value in [0, 1] to linear. 8-bit maps and
// #rrggbb colours are read with it.
float srgbToLinear(float encoded);

struct TexelRepairReport {
    std::uint64_t nanComponents = 0;
    std::uint64_t positiveInfComponents = 0;
    std::uint64_t negativeInfComponents = 0;
    std::uint64_t negativeComponents = 0;  // finite and < 0
    std::uint64_t repairedTexels = 0;      // texels with at least one component replaced
    double mostNegative = 0.0;             // the smallest finite component seen (<= 0)
    double negativeEnergy = 0.0;           // luminance-weighted sr, see above
    double positiveEnergy = 0.0;

    std::uint64_t repairedComponents() const
    {
        return nanComponents + positiveInfComponents + negativeInfComponents + negativeComponents;
    }
    bool clean() const { return repairedComponents() == 0; }
    double negativeEnergyShare() const { return positiveEnergy > 0.0 ? negativeEnergy / positiveEnergy : 0.0; }
    // Only slightly negative components (no NaN or Inf), whose removal changes the map's light
    // by less than kNegligibleEnergyShare: stitching or resampling noise, not a damaged file.
    static constexpr double kNegligibleEnergyShare = 1e-4;
    bool negligible() const
    {
        return nanComponents + positiveInfComponents + negativeInfComponents == 0 && negativeEnergyShare() < kNegligibleEnergyShare;
    }
    // One line: a calm one for a negligible repair ("repaired 1818 slightly negative texel
    // components to 0 (0.0012% of the light: negligible)"), else, e.g. "repaired 33 texel components (33 negative down to -3394, 10.2% of
    // the positive energy; 0 NaN; 0 Inf) in 30 texels" or "no invalid texels".
    std::string summary() const;
};

// Replaces NaN, +Inf, -Inf and negative components by +0 in place and reports them
// (-0.0 also becomes +0.0, uncounted, so equal-looking maps hash equally).
// +Inf becomes 0 rather than a large finite value: any finite stand-in would still
// dominate every filter, SH projection and importance-sampling CDF it reaches, and the
// file gives no hint of the intended magnitude.
TexelRepairReport repairTexels(ImageRGB32F& image);

// The default limit on the texels a file may declare (EnvironmentLoadOptions::maxSourceTexels).
inline constexpr std::uint64_t kMaxEnvironmentTexels = std::uint64_t(1) << 28;

struct EnvironmentLoadOptions {
    // Size cap: inputs wider than this (or taller than maxWidth / 2) are downsampled to
    // maxWidth x maxWidth/2 with an energy-preserving box filter, and a warning. Must be
    // even and >= 2. Builtins wider than the cap are an error instead.
    int maxWidth = 8192;
    // Texels a file may declare (width x height), checked against its header before
    // anything is allocated. Some decoders hold the whole image at its stored precision
    // (OpenImageIO's PNG reader does for interlaced files: 2 GB for 16-bit RGBA at the
    // default), so a caller with a tighter memory budget (the fuzzer) lowers this.
    std::uint64_t maxSourceTexels = kMaxEnvironmentTexels;
};

struct Environment {
    std::string source;          // the file path as given, or the canonical "builtin:..." spec
    ImageRGB32F image;           // linear RGB, row 0 = zenith, finite and >= 0
    TexelRepairReport repair;    // measured on the input at its original resolution
    std::vector<std::string> warnings; // one line each: LDR input, downsampling, repairs
    std::uint64_t contentHash = 0;     // contentHash(image), keys the on-disk bake cache
    // Another tool's bake (imported_bake.hpp): image is its sky, and BakeJob uploads these
    // cubes instead of baking them. Null for a map.
    std::shared_ptr<const ImportedBake> imported;
};

// The smallest file accepted as an environment: 8x4 (a cube of 2x2 faces).
inline constexpr int kMinEnvironmentWidth = 8;
// Texels in one tile of a tiled file (real files use 32x32 to 512x512; this is 2048x2048).
inline constexpr std::uint64_t kMaxTileTexels = std::uint64_t(1) << 22;

// The image files a user brings as environments, by extension (any case): OpenEXR, Radiance
// .hdr, PFM, TIFF, PNG and JPEG. The GUI's drop and `bake`'s directories take these (and the
// GUI another tool's bake, isImportedBakeSpec); loadEnvironment reads whatever OpenImageIO
// reads, named in full.
bool isEnvironmentImagePath(const std::string& path);
// Those extensions, as a message lists them (".exr, .hdr, .pfm, .tif, .png or .jpg").
extern const char* const kEnvironmentImageKinds;

// Also takes another tool's bake (isImportedBakeSpec: .ktx, .ktx2, a KTX2 pair's directory).
// Loads a file (any format OpenImageIO reads: .exr including DWAB, .hdr, .png, .jpg, ...)
// or a builtin. Files must be 2:1 (+-1 texel of rounding). Grey inputs are replicated to
// RGB, alpha and extra channels are dropped. 8-bit inputs or inputs whose values never
// exceed 1 load with a warning (limited dynamic range); sRGB-encoded ones (as OpenImageIO
// reports through "oiio:ColorSpace", or any 8/16-bit integer file that names no colour
// space) are linearised, gamma-encoded ones ("Gamma2.2") are raised to the gamma.
Environment loadEnvironment(const std::string& spec, const EnvironmentLoadOptions& options = {});

// XXH3-64 of every texel component's IEEE-754 bit pattern (little-endian, in memory order),
// seeded with width << 32 | height. Stable across runs and machines; -0.0 and +0.0 hash
// differently (loaded maps never hold -0.0: repairTexels clears it).
std::uint64_t contentHash(const ImageRGB32F& image);

// Solid angle of one texel in row `row` of a width x height equirect (see above).

// The bundled gallery lives in <assetDir>/environments/*.exr; courtyard.exr is the default.
std::string defaultEnvironmentPath(const std::string& assetDir);
// Sorted paths of <assetDir>/environments/*.exr (hidden files skipped); empty if none.
std::vector<std::string> galleryEnvironments(const std::string& assetDir);

} // namespace iblab
