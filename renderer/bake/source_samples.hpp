#pragma once
// The sample tables of the bake passes that importance-sample the environment cube
// (irradiance_importance.comp, prefilter_ggx.comp), built once per pass and mip by the CPU
// core's samplers (ibl/sampling.hpp) instead of by every invocation: the Hammersley point,
// the warp to a direction, its pdf and the sample's half of the PDF-based source lod are the
// same for every output texel, and on llvmpipe computing them per texel cost about as much
// as the texture reads themselves.
//
// Each entry is (x, y, z, w): the direction in the tangent frame (+z = the texel's normal,
// so z is also n.l) and w = sourceLodSampleTerm(1 / (N pdf), bias) (prefilter_lod.glsl),
// from which a pass gets the lod of the texel it reads with sourceLodFromSampleTerm. N is
// the number of samples drawn, including those a table drops.
#include <vector>

#include <glm/vec4.hpp>

namespace iblab::bake {

// Cosine-weighted hemisphere, N Hammersley points (every one has n.l > 0).
std::vector<glm::vec4> cosineSampleTable(int sampleCount, float lodBias);

// GGX lobe around n = v for perceptual roughness r (alpha = r^2), N Hammersley half
// vectors reflected about n; those whose l falls below the horizon are dropped (their
// weight n.l is 0). r = 0 puts every sample on n with w = 0 (a delta has no footprint).
// rotationDegrees turns the whole set about n (the tests' check that a bake does not
// depend on where the set's points happen to fall).
std::vector<glm::vec4> ggxReflectedSampleTable(float roughness, int sampleCount, float lodBias, float rotationDegrees = 0.0f);

} // namespace iblab::bake
