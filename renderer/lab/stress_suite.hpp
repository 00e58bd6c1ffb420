#pragma once
// The stability suite behind `iblab stress`: environments made to break IBL methods (a sun
// swept over five decades of dynamic range, a one-texel light, sub-texel slits, the white
// furnace, saturated coloured lights, black, NaN/Inf/negative texels), each baked once (on
// the lab's harness, lab/harness.hpp, which bakes the LUT once for all) and rendered with
// every method at roughness 0, 0.05, 0.5 and 1, and measured against the exact integrals of
// the shading model (ibl/reference.hpp's, combined by ibl/brdf.hpp's combineLobes) for what
// must hold: finite non-negative outputs, no fireflies above the exact integrals, no SH ringing,
// no seams across cube faces, energy conserved in the furnace, no banding from the LUT's
// half floats. Every finding is classified pass / warn / fail against a threshold the
// report states.
//
// The analysis is a library function so that tests assert its invariants directly; the
// command only writes what it returns. Needs a current GL 4.5 context (the Renderer's).
// Public header: no GL.
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "bake/bake_settings.hpp"
#include "frame/settings.hpp"

namespace iblab {
class Renderer;
}

namespace iblab::stress {

enum class Verdict { Pass, Warn, Fail };
std::string_view verdictName(Verdict verdict);

struct StressEnvironment {
    std::string name;   // short key used in tables and JSON: "sun-1e4", "texel", ...
    std::string spec;   // builtin spec, width set by StressOptions::environmentWidth
    std::string breaks; // what it is made to break
    bool furnace = false; // uniform radiance 1: the reflected energy is the render itself
    bool inBench = false; // one of those the default bench adds (bench_sweep.hpp builtinBenchEnvironments)
};

// The material a method is shown on: white metal (F0 = 1, specular only) for estimators of
// the specular integral, white plastic (albedo 1, F0 = 0.04) where the diffuse source is
// what differs.
enum class StressMaterial { WhiteMetal, WhitePlastic };

struct StressMethod {
    std::string name;
    SamplingSettings sampling;   // method, N, PDF filtering, diffuse source (plain or windowed SH9, the cube)
    StressMaterial material = StressMaterial::WhiteMetal;
};

struct StressOptions {
    bool quick = false;
    int environmentWidth = 256; // every stress environment is a builtin at this width
    int frameSize = 96;         // square frames, the sphere filling most of them
    int gridCell = 48;          // thumbnail edge in the image grid
    bake::BakeSettings bake;
    std::vector<float> roughnesses{0.0f, 0.05f, 0.5f, 1.0f};
    std::function<void(const std::string&)> progress; // one line per environment, may be empty
};

// The default run (about a minute on llvmpipe) or the quick one (seconds, tests): smaller
// environments, frames and bakes, the same environments and methods.
StressOptions defaultStressOptions(bool quick);

// Every environment, in report order. The sun sweep's intensities make the nominal
// peak / mean radiance (disc over the solid-angle mean) 1e2 .. 1e6.
std::vector<StressEnvironment> stressEnvironments(int width);
std::vector<StressMethod> stressMethods();
// The sun intensity (radiance added inside a disc of diameter sizeDegrees on a sky of
// radiance sky) whose peak / mean radiance is peakToMean. Throws iblab::Error when a disc that
// large cannot reach it (peak / mean < 4 pi / disc solid angle).
double sunIntensityForPeakToMean(double peakToMean, double sizeDegrees, double sky);

// One view of a sphere's pixels, by n.v of the exact sphere under each pixel.
enum class ViewBin { All, Normal, Grazing };
inline constexpr float kNormalMinNdotV = 0.9f;  // normal incidence: n.v >= 0.9
inline constexpr float kGrazingMaxNdotV = 0.25f; // grazing: n.v <= 0.25 (the rim, n.v ~ 0.1)
std::string_view viewBinName(ViewBin bin);

struct ViewReading {
    ViewBin bin = ViewBin::All;
    int pixels = 0;
    double renderMax = 0.0;     // luminance
    double renderMean = 0.0;
    double referenceMax = 0.0;  // exact integrals of the same material at the bin's pixels
    double referenceMean = 0.0;
    double fireflyRatio = 1.0;  // (renderMax + eps) / (referenceMax of the All bin + eps)
    double energyRatio = 1.0;   // (renderMean + eps) / (referenceMean + eps)
};

struct RenderMeasurement {
    std::string environment;
    std::string method;
    float roughness = 0.0f;
    bool multiscatter = false;
    // Over every pixel of the HDR frame (components).
    std::uint64_t nanComponents = 0;
    std::uint64_t infComponents = 0;
    std::uint64_t negativeComponents = 0;
    std::vector<ViewReading> views; // All, Normal, Grazing
    const ViewReading& view(ViewBin bin) const;
};

struct ShRinging {
    std::string environment;
    double meanIrradiance = 0.0;  // band 0, luminance
    // Minimum over the sphere of the SH9 irradiance / its mean, worst channel (< 0: ringing).
    double plainMinimum = 0.0;
    double windowedMinimum = 0.0;
    double windowWidth = 0.0;
};

enum class SeamTexture { Prefiltered, Irradiance };
inline constexpr std::array<std::string_view, 2> kSeamTextureNames{"prefiltered", "irradiance"}; // in the enum's order
inline std::string_view seamTextureName(SeamTexture texture) { return kSeamTextureNames[std::size_t(texture)]; }

struct SeamReading {
    std::string environment;
    SeamTexture texture = SeamTexture::Prefiltered;
    int level = 0;
    float roughness = 0.0f; // prefiltered mips only
    double edgeJump = 0.0;     // mean |L(a) - L(across the edge)| over every edge texel (luminance)
    double interiorStep = 0.0; // mean |L(a) - L(one texel inwards)| over the same texels
    double meanLevel = 0.0;    // mean luminance of the level
    double ratio = 1.0;        // edgeJump / interiorStep
};

struct BakeHealth {
    std::string environment;
    std::uint64_t nonFiniteTexels = 0; // components, over every cube level, the LUT and SH
    std::uint64_t negativeTexels = 0;
    double energyKept = 1.0; // power of the environment cube's mip 0 / power of the equirect
};

struct EnvironmentSummary {
    std::string name;
    std::string spec;
    std::string breaks;
    bool furnace = false; // StressEnvironment::furnace
    double meanLuminance = 0.0; // solid-angle mean of the loaded map
    double peakLuminance = 0.0; // brightest texel
    std::string repair = {};    // the loader's repair summary
    std::uint64_t repairedComponents = 0;
    double bakeMilliseconds = 0.0;
};

struct LutBanding {
    std::string geometry;
    int size = 0;
    double maxAbsVsCpu = 0.0;        // baked RGBA16F A, B vs the float CPU LUT (same samples)
    double maxAbsQuantisation = 0.0; // the CPU LUT rounded to half vs itself: the format alone
    int maxDisplayStep = 0;          // 8-bit codes between the baked and CPU LUT after tone mapping
    int texelsWithDisplayStep = 0;
};

// What a finding checks, and the reports' spelling of it (in the enum's order).
enum class StressCheck { Fireflies, NonFinite, Negative, ShRinging, Seams, Furnace, Lut, Bake };
inline constexpr std::array<std::string_view, 8> kStressCheckNames{"fireflies", "non-finite", "negative", "sh-ringing", "seams", "furnace", "lut", "bake"};
inline std::string_view stressCheckName(StressCheck check) { return kStressCheckNames[std::size_t(check)]; }

struct Finding {
    StressCheck check = StressCheck::Bake;
    std::string environment; // "" for environment-independent checks
    std::string method;
    std::string condition;   // "roughness 0.5, grazing", ...
    double value = 0.0;
    std::string threshold;   // how the value was classified, in words
    Verdict verdict = Verdict::Pass;
};

// Thumbnails of the tone-mapped renders, rows = environments, columns = method x roughness,
// with a left margin and a header left free for the labels (drawn by the caller, which has
// a font).
struct StressGrid {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba; // top row first
    struct Label {
        int x = 0; // top-left, pixels
        int y = 0;
        std::string text;
    };
    std::vector<Label> labels;
};

struct StressReport {
    StressOptions options;
    std::string renderer; // GL renderer string
    std::vector<EnvironmentSummary> environments;
    std::vector<std::string> methods;
    std::vector<RenderMeasurement> renders;
    std::vector<ShRinging> sh;
    std::vector<SeamReading> seams;
    std::vector<BakeHealth> bakes;
    LutBanding lut;
    std::vector<Finding> findings;
    StressGrid grid;
    double seconds = 0.0;

    int count(Verdict verdict) const;
};

// Runs the whole suite with `renderer` (its environment and bake are replaced).
StressReport runStressSuite(Renderer& renderer, const StressOptions& options);

// The report as JSON (every measurement and finding) and as Markdown (the findings table
// first, worst first, then the per-check tables).
std::string stressJsonText(const StressReport& report);
std::string stressMarkdown(const StressReport& report);

} // namespace iblab::stress
