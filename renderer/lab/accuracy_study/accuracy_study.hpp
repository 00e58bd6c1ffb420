#pragma once
// accuracy_study: how far real-time specular IBL methods are from the full integral, and the
// fit of the lobe table (issue #14; docs/accuracy-study.md). CPU only, no GL. What the
// tool's files share: the options (main.cpp parses them), the measurement's inputs
// (inputs.cpp: environments, the GPU's LUT and prefiltered chain as the CPU emulates them,
// cached full integrals, the scenes' pixels and how a pixel's lobes combine), the two
// commands (evaluate.cpp, fit.cpp) and what they write (report.cpp: the markdown tables, the
// lobe table's C++ include).
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "ibl/brdf.hpp"
#include "ibl/image.hpp"
#include "ibl/specular_approximations.hpp"

namespace iblab::accuracy {

constexpr GeometryTerm kTerm = GeometryTerm::HeightCorrelatedSmith; // SamplingSettings default
inline const glm::dvec3 kCopper(0.95, 0.64, 0.54);                  // MaterialSettings default base colour
constexpr double kDielectricF0 = 0.04;                              // 0.16 * 0.5^2
// The repository: its bundled environments, the unseen ones beside it, the committed table.
inline const std::filesystem::path kSourceDir = IBLAB_SOURCE_DIR;

struct StudyOptions {
    std::string command; // eval or fit
    int width = 256;     // of the environments, downsampled: the reference's resolution
    // eval
    int sphere = 64;
    int grid = 128;
    std::string sets = "bundled,unseen,procedural";
    std::vector<std::string> envs;
    std::string csv;
    std::vector<std::string> tables;
    std::vector<double> roughnesses{0.2, 0.3, 0.5, 0.7, 0.9}; // of the spheres
    // Diagnostics: read the exact prefilter at the requested roughness (O(texels) per read)
    // instead of the emulated mip chain, to separate the chain's discrete levels from the lobe.
    bool exactPrefilter = false;
    bool bins = false; // the copper spheres' errors by n.v band too
    // eval and fit, with --bakes: --lights reads each bake's shading lights (bake.json) and
    // its mips less them, as the renderer shades the fitted lobe (ibl/shading_lights.hpp;
    // docs/accuracy-study.md, "Compact sources"). eval adds "<method>+lights" for the split
    // sum and each fitted lobe: the method on the residual's mips plus the lights' exact
    // specular; fit fits the table that way.
    bool lights = false;
    // The GPU measure's configuration (scripts/measure-lobe.sh, the bench's specular-lobe
    // family): copper spheres 128 x 128 framed as the bench frames them, one measure per
    // roughness of `roughnesses` (not pooled, no dielectric), and the grid. Diffuse stays the
    // exact irradiance: the family shades with the moment cube, within 0.3% of it.
    bool benchScenes = false;
    // eval and fit: read the prefiltered cube the GPU reads, from DIR/<map name>/ as written
    // by `iblab bake --env MAP --out DIR/<map name>` (scripts/accuracy-bakes.sh), instead of
    // the exact-prefilter emulation.
    std::string bakes;
    // fit
    int taps = 1;
    int frames = 96;
    int size = 16;
    double minRoughness = 0.15;
    std::string out;
    std::string init; // fit: the table to start from (one-tap, or for --taps 3 and 4 a Fresnel split)
    unsigned seed = 14;
    // Also the dielectric's specular alone, so that a read that only the dielectric's
    // diffuse hides (a dark dielectric would show it) is not rewarded.
    bool mixedObjective = false;
    // Weigh every map alike: per cell, each map's squared error over the split sum's there
    // (the bar is a ratio per map), instead of the sum over all samples.
    bool perMapRatio = false;
    // The energy compensation the lab shades with by default (SamplingSettings::multiscatter,
    // Filament's 1 + F0 (1 / E_ss - 1) with the LUT's E_ss) on both the estimate's specular and
    // the full integral's, as the bench measures it; the GPU reference divides by its own
    // E_ss, which the 128^2 LUT matches to its precision. --no-multiscatter measures single
    // scattering (the committed table was fitted that way).
    bool multiscatter = true;
    // After the cells are fitted alone, `smoothPasses` passes re-fit each against its
    // objective plus `smooth` times its squared distance from the lines through its
    // neighbours (the table's second differences; fit.cpp, Smoother), in the objective's
    // units. 0: cells fitted alone, as before.
    double smooth = 0.0;
    int smoothPasses = 4;
    // No read sharper than the lobe it stands for (read_floor.hpp): each cell's reads kept at
    // or above readRoughnessFloor's roughness.
    bool readFloor = false;
    // Leave-one-out (scripts/fit-lobe-loo.sh): fit on the bundled maps but this one (its
    // study name, e.g. city), to measure the table on a map it has not seen.
    std::string leaveOut;
};

int evalCommand(const StudyOptions& options);
int fitCommand(const StudyOptions& options);

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t);

// fn(i) for i in [0, count), over all hardware threads.
template <typename Fn>
void parallelFor(int count, const Fn& fn)
{
    const int threads = int(std::clamp(std::thread::hardware_concurrency(), 1u, 64u));
    std::atomic<int> next{0};
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
        pool.emplace_back([&] {
            for (int i = next++; i < count; i = next++) fn(i);
        });
    for (auto& th : pool) th.join();
}

// ---- inputs.cpp --------------------------------------------------------------------------

// The split-sum LUT as the GPU reads it: the bake's 128^2 x 2048 table, bilinear.
struct Lut {
    int size = 128;
    std::vector<glm::vec3> table;
    glm::dvec3 sample(double NdotV, double roughness) const;
};
const Lut& lut();

// ---- gpu_chain.cpp -------------------------------------------------------------------
// A bake's prefiltered cube as textureLod reads it (seamless bilinear per mip, linear
// between mips at the layout's lod).
class CubeChain {
public:
    static CubeChain fromBake(const std::filesystem::path& directory, int layout);
    glm::dvec3 lookup(glm::dvec3 direction, double roughness) const;
    int levels() const { return int(mips_.size()); }
    // The chain less the lights (shadingLightResidual).
    CubeChain withoutShadingLights(const ShadingLights& lights) const;

private:
    struct Mip {
        int size = 0;
        std::vector<glm::vec3> texels; // [(face * size + row) * size + x], bake_files.hpp
        const glm::vec3& at(int face, int x, int row) const { return texels[(std::size_t(face) * std::size_t(size) + std::size_t(row)) * std::size_t(size) + std::size_t(x)]; }
        glm::dvec3 bilinear(glm::dvec3 direction) const;
    };
    std::vector<Mip> mips_;
    int layout_ = PREFILTER_LAYOUT_QUADRATIC;
};

struct EnvCase {
    std::string name;
    std::string set; // bundled, unseen, procedural
    ImageRGB32F image;
    std::shared_ptr<PrefilteredChain> chain; // the exact-prefilter emulation
    std::shared_ptr<CubeChain> bake;         // the GPU's own mips (--bakes), read instead
    std::shared_ptr<ReferenceSums> sums;
    std::uint64_t hash = 0;
    // --lights: the bake without its shading lights, and the lights' sums.
    std::shared_ptr<CubeChain> residualBake;
    std::shared_ptr<ReferenceSums> lights;
    // The lights' alpha floor as the shader applies it (ShadingLights::minAlpha), as a
    // perceptual roughness: a light is a group of texels, not a point.
    double lightsMinRoughness = 0.0;
    double lightsRoughness(double roughness) const { return std::max(roughness, lightsMinRoughness); }
    glm::dvec3 prefiltered(glm::dvec3 direction, double roughness) const
    {
        return bake ? bake->lookup(direction, roughness) : chain->lookup(direction, roughness);
    }
};

// --lights: reads the shading lights of env's bake (bakes/<name>/bake.json) into
// env.residualBake and env.lights.
void splitShadingLightsOf(EnvCase& env, const std::string& bakes);

// (spec, set) of every environment in `sets` (a list naming bundled, unseen, procedural),
// then the `extra` specs.
std::vector<std::pair<std::string, std::string>> environmentList(const std::string& sets, const std::vector<std::string>& extra);

// The environment downsampled to `width`, with its full-integral sums and (withChain) its
// prefiltered chain: the bake's from bakes/<name> when `bakes` is given, else the emulated
// one.
EnvCase loadCase(const std::string& spec, const std::string& set, int width, bool withChain, const std::string& bakes = {});

struct Query {
    glm::dvec3 n, v;
    double roughness;
};

// The full integral for every query (parallel), through the on-disk cache.
std::vector<FullIntegral> fullIntegrals(const EnvCase& env, const std::vector<Query>& queries, bool withIrradiance);

struct Pixel {
    glm::dvec3 n, v;
    double roughness = 0.0;
    double metallic = 0.0;
};

// A unit sphere at the origin, size x size pixels, from the default orbit camera (distance
// 3.5, `iblab render`'s view) or framed as the bench frames it (frameBox: 1.08 x the distance
// at which the unit box's half height fills half the fov, plus its half depth). With
// msaaCoverage, only the pixels the bench measures: those its 4x MSAA covers wholly.
inline constexpr double kDefaultCameraDistance = 3.5;
inline const double kBenchSphereDistance = 1.08 / std::tan(0.5 * 45.0 * 3.14159265358979323846 / 180.0) + 1.0;
std::vector<Pixel> spherePixels(int size, double distance, bool msaaCoverage);
// The 7 x 7 metallic x roughness grid framed as the bench frames it, size x size pixels.
std::vector<Pixel> gridPixels(int size, bool msaaCoverage);

struct Shaded {
    glm::dvec3 total, specular;
};

// Shades a pixel with the core's combineLobes (ibl/brdf.hpp, the GLSL's twin), given the
// specular radiance; the base colour is copper's.
Shaded combine(const Pixel& p, glm::dvec3 specular, glm::dvec3 irradiance, glm::dvec3 F0);

// The bench's per-pixel measure (common/error_metrics.glsl).
double pixelError(glm::dvec3 value, glm::dvec3 reference);

// ---- report.cpp --------------------------------------------------------------------------

// One environment's results: per method, the relative RMSE of each measure (eval's list:
// spheres total, spheres specular, grid total, grid specular; or --bench-scenes' list).
struct EnvironmentRow {
    std::string env, set;
    std::vector<std::vector<double>> values; // [method][measure]
};

// The copper spheres' total relative error by n.v band (--bins): per band, the sum of
// squares and the count; per environment name, per method.
constexpr int kBins = 5;
using Bins = std::array<std::array<double, 2>, kBins>;
using BinsByEnvironment = std::map<std::string, std::vector<Bins>>;

// The markdown tables on stdout: one per measure, rows = environments, columns = methods
// (value and ratio to the first, the split sum), then the n.v bands when `bins` is given.
void printEvaluation(const std::vector<std::string>& methodNames, const std::vector<std::string>& measures, const std::vector<EnvironmentRow>& rows,
                     BinsByEnvironment* bins);

// A table in the .inc format fit writes (renderer/ibl/specular_lobe_fit.inc).
LobeFitTable readLobeTable(const std::string& path);
// The .inc text of a fitted table, with a header saying how it was made.
std::string lobeTableInclude(const LobeFitTable& table, const StudyOptions& options);

} // namespace iblab::accuracy
