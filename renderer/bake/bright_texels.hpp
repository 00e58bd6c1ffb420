#pragma once
// The prefilter's split of the environment into a bounded base and its brightest texels
// (docs/bake.md, "The prefilter's estimator"). A small, very bright source (a sun) is what a
// sample table shared by every texel cannot integrate: each output texel sees it through
// the same few samples, and the result carries the table's pattern. So every texel whose
// luminance exceeds a threshold T keeps only T (its chroma unchanged), and its excess is
// summed exactly, as a point of light at the texel's centre with the excess times the
// texel's solid angle as its flux, by every output texel with the GGX weight itself. The
// base, whose largest value is T, is importance-sampled as before.
//
// T is thresholdOverMean times the map's mean luminance, raised where needed so that at
// most maxTexels texels are above it (the per-texel cost of the exact sum). The exact part
// carries the bright sources wherever they are on the sphere; what is left to sampling has
// the dynamic range of an overcast sky.
#include <vector>

#include <glm/vec4.hpp>

#include "bake/baked_texture.hpp"
#include "bake/bake_settings.hpp"
#include "gl/handles.hpp"

namespace iblab::bake {

class BakePasses;

struct BrightTexelSplit {
    CubeImage base;                // the environment's level 0 with every bright texel scaled down to T
    float threshold = 0.0f;        // T, luminance (Rec. 709 weights)
    float meanLuminance = 0.0f;    // over the sphere, by solid angle
    int brightTexels = 0;          // texels above T
    // One point of light per bright texel, two vec4 each: (direction, 0), (flux rgb, 0);
    // flux = excess radiance x the texel's solid angle. Texel order (deterministic).
    std::vector<glm::vec4> lights;
};

BrightTexelSplit splitBrightTexels(const CubeImage& level0, int maxTexels, float thresholdOverMean);

// The split on the GPU, for BakePasses::prefilter.
struct PrefilterBrightTexels {
    BakedTexture base;   // the split's base as a cube with the environment's size, format and mips
    gl::Buffer texels;   // the split's lights, padded to a uniform block of 2 settings.brightTexels entries
    int count = 0;       // lights
    int capacity = 0;    // entries of the block (prefilter_ggx.comp's BRIGHT_CAPACITY)
    float threshold = 0.0f;
    float meanLuminance = 0.0f;
};

// Reads the environment's level 0 back, splits it, and uploads the base (with its mips,
// built as the environment's are) and the lights. Throws iblab::Error where the driver's
// uniform blocks cannot hold settings.brightTexels lights.
PrefilterBrightTexels splitBrightTexels(BakePasses& passes, const BakedTexture& environment, const PrefilterSettings& settings);

// Z(alpha) = integral of D(h) max(0, n.l) dOmega_l over the sphere, with v = n and h the
// half vector of n and l (GGX, alpha = roughness^2): what the exact sum divides its weights
// D(h) max(0, n.l) dOmega by, as the reference divides by the same integral summed over its
// texels. (The sampled part divides by its own sum of n.l, which estimates the same lobe.)
double ggxPrefilterNormalization(double roughness);

} // namespace iblab::bake
