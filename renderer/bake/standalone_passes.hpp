#pragma once
// Two of the bake's passes run alone, for the commands that time or write just that one
// (`iblab sh --device gpu`, `iblab lut`): the passes themselves (bake_passes.hpp) are
// internal to the bake layer. Each needs a current GL context.
#include "bake/baked_texture.hpp"
#include "gl/shader_library.hpp"
#include "ibl/brdf.hpp"
#include "ibl/image.hpp"
#include "ibl/sh.hpp"

namespace iblab::bake {

struct TimedSh9 {
    SH9Color radiance;
    double ms = 0.0; // the projection: upload and read-back included, compiling its program not
};
// Radiance L_lm of the equirect projected on the GPU (BakePasses::projectSh9).
TimedSh9 projectSh9OnGpu(gl::ShaderLibrary& shaders, const ImageRGB32F& equirect);

struct TimedLut {
    BakedTexture lut; // RGBA16F, size x size
    double ms = 0.0;  // the LUT's dispatch until finished, compiling its program not
};
// The split sum's BRDF LUT with `samples` samples per texel (BakePasses::brdfLut).
TimedLut bakeBrdfLut(gl::ShaderLibrary& shaders, int size, int samples, GeometryTerm term);

} // namespace iblab::bake
