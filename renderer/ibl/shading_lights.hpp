#pragma once
// The map's brightest texels, shaded exactly (docs/accuracy-study.md, "Compact sources").
// A small bright source (a sun, a lamp) reaches a prefiltered cube as the prefilter's kernel,
// one isotropic lobe, and no read of the fitted lobe's table turns that into the BRDF's own
// highlight: fitted on a map whose sun dominates, the table still keeps 0.71 of the split
// sum's error there. So the brightest groups of texels are split off as lights, each summed
// with the exact BRDF at its direction, and the fitted lobe reads the chain of the rest (the
// residual). Residual plus lights is the map: nothing is counted twice or lost.
#include <vector>

#include <glm/vec3.hpp>

#include "ibl/image.hpp"
#include "ibl/sh.hpp"

namespace iblab {

// The most lights a frame shades (ibl_lighting.glsl's SHADING_LIGHTS_MAX): on llvmpipe each
// costs about 2 ms of a 1280 x 720 sphere, so only lights that matter are kept (below).
inline constexpr int kMaxShadingLights = 16;
// How many a bake finds by default (PrefilterSettings::shadingLights). On the unseen maps of
// docs/accuracy-study.md the fitted lobe's worst and median error with 4 are within 0.01 of
// those with 16 (one case, pmndrs-studio, moves by 0.05: the lights after the first few
// carry little), and on llvmpipe each light costs about 0.035x of the split sum's frame,
// however little it carries.
inline constexpr int kDefaultShadingLights = 4;
// Lights are groups of a cube grid with this many groups per face edge (about 1.4 degrees
// each, the texel of a 256-wide equirect): a 0.5 degree sun falls in one group or two.
inline constexpr int kShadingLightGrid = 64;
// Each light keeps its excess on a grid this fine within its group, for the residual's
// narrow mips, where the group's spread changes the prefilter kernel.
inline constexpr int kShadingLightPointsPerEdge = 4;
// A group whose excess carries less than this share of the map's flux (luminance x solid
// angle) stays in the residual: it would cost as much as a sun and change next to nothing.
inline constexpr double kMinShadingLightShare = 1e-3;

struct ShadingLight {
    glm::vec3 direction{0.0f, 1.0f, 0.0f}; // unit, environment space: the excess's flux centroid
    glm::vec3 flux{0.0f};                  // radiance x solid angle
};

// A light and where it came from: its group on the cube grid, the fraction of the group's
// radiance the residual keeps, and its excess as points on a finer grid.
struct ShadingLightGroup {
    ShadingLight light;
    int face = 0, x = 0, row = 0; // the group, on a grid x grid face
    float keep = 1.0f;
    std::vector<ShadingLight> points;
};

struct ShadingLights {
    int grid = kShadingLightGrid;
    std::vector<ShadingLightGroup> groups; // brightest first
    // A light is a group of texels, not a point: shading widens alpha to at least this (a
    // GGX highlight whose half-maximum width is the group's).
    float minAlpha() const;
    std::vector<ShadingLight> lights() const;
};

// The lights of an equirect map (float, as loaded): the `maxLights` brightest groups (by mean
// luminance) keep the mean luminance of the next group, colour kept, and give the rest of
// their radiance to their light. `grid` divides the face size of the mirror the residual is
// made from (a power of two no larger than it).
ShadingLights findShadingLights(const ImageRGB32F& source, int maxLights = kMaxShadingLights, int grid = kShadingLightGrid);

// One cube level, RGB, texels [(face * size + row) * size + x] (CubeImage's order).
struct CubeLevelRgb {
    int size = 0;
    std::vector<glm::vec3> texels;
};

// The residual of a prefiltered chain whose mip 0 is the environment (roughness 0) and whose
// mip m is the N = V = R GGX prefilter at mipRoughness[m]: mip 0 as keepInMirror leaves it,
// every other mip as subtractShadingLights does.
std::vector<CubeLevelRgb> shadingLightResidual(std::vector<CubeLevelRgb> chain, const std::vector<double>& mipRoughness, const ShadingLights& lights);

// The constants of a light's exact prefilter at `roughness` (> 0), which subtractShadingLights
// and the renderer's GPU pass (shading_lights_residual.comp) share: the kernel is
// scale ggxPrefilterWeight(c) (ibl/brdf.hpp), c = n.l; a texel sums a light's points when
// c > cosNear, its centroid otherwise.
struct ShadingLightKernel {
    double alpha2 = 0.0;
    double scale = 0.0;
    double cosNear = 0.0;
};
ShadingLightKernel shadingLightKernel(double roughness, int grid);

// A prefiltered mip at `roughness` (> 0) less each light's exact prefilter (the bake's
// kernel, D(h) max(0, n.l) / Z(alpha)) at every texel centre, summed over the light's points
// near it and from its centroid far away, clamped at 0.
void subtractShadingLights(CubeLevelRgb& mip, double roughness, const ShadingLights& lights);

// The texels of a size^2 mirror face (size a multiple of the grid) that a light's group
// covers: a block `texels` wide from (x, row), on its face.
struct MirrorBlock {
    int face = 0, x = 0, row = 0, texels = 0;
};
MirrorBlock mirrorBlock(const ShadingLightGroup& group, int grid, int size);

// The mirror (mip 0) with each light's group scaled by its `keep`.
void keepInMirror(CubeLevelRgb& mip0, const ShadingLights& lights);

// The lights' irradiance at a unit normal n (environment space): flux max(0, n.l) summed
// over the lights (ShadingLights::lights(), the groups' centroids), as the renderer sums it
// per pixel (ibl_lighting.glsl's shadingLightsSpecular, beside their specular).
glm::dvec3 shadingLightsIrradiance(const std::vector<ShadingLight>& lights, glm::dvec3 n);

// An irradiance cube (E at each texel centre) less the lights' irradiance there, clamped at 0:
// what the renderer interpolates between texel centres before it adds the lights' own per
// pixel. Interpolated with them, a 32 face spreads a sun's terminator over a texel (2.8
// degrees) and lights the dark side beside it: up to 2.8 times the sky's irradiance there.
void subtractShadingLightsIrradiance(CubeLevelRgb& cube, const std::vector<ShadingLight>& lights);

// The lights' irradiance as SH9 coefficients (their radiance, a delta at each centroid,
// projected and convolved with the cosine lobe), to take from a map's SH9 irradiance.
SH9Color shadingLightsShIrradiance(const std::vector<ShadingLight>& lights);

} // namespace iblab
