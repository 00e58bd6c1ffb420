#pragma once
// How far a bake is from the exact integrals of renderer/ibl/reference.hpp (each summed over
// every texel of the equirect), two ways:
//  - per texture level at the texel centres of a regular grid of texels on each face (the
//    comparison reads texels, with no interpolation error of its own): is each mip right?
//  - "as shaded": what shading reads (textureLod, seamless, trilinear) at directions off the
//    texel grid: the prefiltered cube at the layout's lod for roughness values between the
//    mips, against the reference at that roughness, and each irradiance cube bilinearly.
//    These are the numbers that compare bakes of different sizes and layouts on equal terms.
// Used by `iblab bake --json` and docs/bake.md.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "bake/bake_result.hpp"
#include "gl/shader_library.hpp"
#include "ibl/image.hpp"

namespace iblab::bake {

struct AccuracyOptions {
    // A 16 x 16 grid of texels per face: 1536 directions per cube level, every texel of a
    // face of 16 or less (`iblab bake --error-texel-grid N`). A 4 x 4 grid (96 directions)
    // is too few for a stable figure at mip 1, one texel in 1024: where none of them falls
    // on a bright area, the dim texels beside it decide the whole figure (studio.exr 0.362
    // at grid 4, 0.017 at 16, 0.018 at 32; docs/bake.md, "How many directions the per-mip
    // figure needs"). Grid 16 costs about 0.5 s more per map than grid 4 on llvmpipe.
    int texelsPerFaceEdge = 16;
    // The references cost O(texels) per direction; an environment wider than this is halved
    // (energy-preserving, reference.hpp's downsampleEquirect2x) until it is not, for the
    // rough mips (roughness >= 0.5) and the irradiance only. Their lobes span tens of
    // degrees, hundreds of texels of the halved map, so halving changes those integrals by
    // far less than the errors being measured. Sharper mips always use the full map.
    int maxReferenceWidthForWideLobes = 512;
    // As shaded: this many directions spread evenly over the sphere (a Fibonacci lattice,
    // which lines up with no cube's texel grid) at shadedRoughnessSteps + 1 roughness values
    // 0, 1/steps, ..., 1: finer than any chain's mip spacing, so that no layout is favoured by
    // having its mips where the measurement looks.
    int shadedDirections = 96;
    int shadedRoughnessSteps = 10;
    // The floor of the as-shaded error: an exact prefilter of the bake's sizes and format
    // (the reference at every texel the shaded lookups read), read the same way. What is
    // left is the interpolation between texels and mips, which no estimator removes.
    bool shadedFloor = false;
    int lutGrid = 8;                       // 8 x 8 LUT texels
    std::uint32_t lutReferenceSamples = 16384;
    // Where the reference values are kept between runs (empty: computed every time). They
    // depend only on the map's pixels and on what is measured (the bake's sizes and layout),
    // not on how it was baked, so every later bake of a map reads them, as bakes read the
    // cached LUTs. <bake cache root>/reference in the bake command.
    std::filesystem::path referenceCacheDirectory;
};

struct ErrorStats {
    double mean = 0.0;
    double max = 0.0;
    int directions = 0;
};

struct PrefilterLevelError {
    int level = 0;
    float roughness = 0.0f;
    // sqrt(sum |baked - reference|^2 / sum |reference|^2) over the directions and channels.
    double relativeRmse = 0.0;
    int directions = 0;
    int referenceWidth = 0; // of the equirect the reference summed over
};

struct ShadedRoughnessError {
    float roughness = 0.0f;
    float lod = 0.0f;          // where the layout reads it
    double relativeRmse = 0.0; // as PrefilterLevelError
    int directions = 0;
    int referenceWidth = 0;
};

struct BakeErrors {
    std::vector<PrefilterLevelError> prefilter;
    std::vector<ShadedRoughnessError> prefilterShaded;
    // Root mean square of prefilterShaded's relative RMSEs: one number per bake.
    double prefilterShadedRms = 0.0;
    // With AccuracyOptions::shadedFloor: the same for the exact prefilter of the same sizes.
    std::vector<ShadedRoughnessError> prefilterShadedFloor;
    double prefilterShadedFloorRms = 0.0;
    // Per direction |baked - reference| / |reference| (RGB vector norms).
    ErrorStats shIrradiance;
    ErrorStats shIrradianceWindowed;
    IrradianceMethod irradianceMethod = IrradianceMethod::None; // the bake's, which irradianceCube measures
    std::optional<ErrorStats> irradianceCube;                    // empty for None
    int irradianceReferenceWidth = 0;
    // As shaded: at AccuracyOptions::shadedDirections, each cube read bilinearly.
    ErrorStats shIrradianceShaded;
    std::optional<ErrorStats> irradianceCubeShaded;
    // Where the bake found shading lights: the diffuse as the fitted lobe shades it, each source
    // less the lights (residual_irradiance.hpp) read as above, plus each light's flux max(0, n.l).
    std::optional<ErrorStats> shIrradianceWithLightsShaded;         // SH9 as projected
    std::optional<ErrorStats> shIrradianceWindowedWithLightsShaded; // SH9 as the bake windowed it
    std::optional<ErrorStats> irradianceCubeWithLightsShaded;
    // Max |baked - reference| over the grid and the A, B, A + B channels.
    std::array<std::optional<double>, 2> lutMaxAbs;
    bool referencesFromCache = false;
    double referenceMilliseconds = 0.0; // computing or reading them, within milliseconds
    double milliseconds = 0.0;
    std::vector<std::string> notes; // one line each: a reference cache entry found corrupt, or not written
};

// Reads the result's textures back and samples them (needs its context current).
BakeErrors measureBakeErrors(const BakeResult& result, const ImageRGB32F& environment, gl::ShaderLibrary& shaders,
                             const AccuracyOptions& options = {});

// n directions spread evenly over the unit sphere (spherical Fibonacci lattice).
std::vector<glm::dvec3> fibonacciSphere(int n);

// The texel-centre directions of a grid x grid texel subset of each face of a size^2 cube
// level (all texels when size <= grid), with their (face, x, row).
struct CubeTexelRef {
    int face = 0;
    int x = 0;
    int row = 0;
};
std::vector<CubeTexelRef> cubeTexelGrid(int size, int grid);

// {"prefilter_relative_rmse": [{"mip", "roughness", "relative_rmse", ...}], "irradiance": {...},
// "lut_max_abs": {...}, "method": "..."}
std::string errorsJsonText(const BakeErrors& errors, const AccuracyOptions& options);

} // namespace iblab::bake
