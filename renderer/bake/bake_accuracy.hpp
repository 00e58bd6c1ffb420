#pragma once
// How far a bake is from the exact integrals of renderer/ibl/reference.hpp (each summed over
// every texel of the equirect), at a fixed set of directions: the texel centres of a
// regular grid of texels on each face of the baked cube (so the comparison reads texels,
// with no interpolation error of its own). Used by `iblab bake --json` and docs/bake.md.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "bake/bake_result.hpp"
#include "ibl/image.hpp"

namespace iblab::bake {

struct AccuracyOptions {
    int texelsPerFaceEdge = 4; // a 4 x 4 grid of texels per face: 96 directions per cube level
    // The references cost O(texels) per direction; an environment wider than this is halved
    // (energy-preserving, reference.hpp's downsampleEquirect2x) until it is not, for the
    // rough mips (roughness >= 0.5) and the irradiance only. Their lobes span tens of
    // degrees, hundreds of texels of the halved map, so halving changes those integrals by
    // far less than the errors being measured. Sharper mips always use the full map.
    int maxReferenceWidthForWideLobes = 512;
    int lutGrid = 8;                       // 8 x 8 LUT texels
    std::uint32_t lutReferenceSamples = 16384;
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

struct BakeErrors {
    std::vector<PrefilterLevelError> prefilter;
    // Per direction |baked - reference| / |reference| (RGB vector norms).
    ErrorStats shIrradiance;
    ErrorStats shIrradianceWindowed;
    std::optional<ErrorStats> irradianceRiemann;
    std::optional<ErrorStats> irradianceImportance;
    int irradianceReferenceWidth = 0;
    // Max |baked - reference| over the grid and the A, B, A + B channels.
    std::array<std::optional<double>, 2> lutMaxAbs;
    double milliseconds = 0.0;
};

// Reads the result's textures back (needs its context current).
BakeErrors measureBakeErrors(const BakeResult& result, const ImageRGB32F& environment, const AccuracyOptions& options = {});

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
