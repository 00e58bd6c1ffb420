#pragma once
// Irradiance SH9 in Filament's convention: what `cmgen --sh-shader` (and --deploy) writes to
// sh.txt and the KTX key "sh", and what Filament's shader evaluates (docs/engine-export.md
// cites the sources):
//  - windowed like cmgen's default --sh-window=auto: band l scaled by sinc(pi l / w)^4, w
//    the largest cut-off (bisection in [3, 13], per channel) whose irradiance has no
//    negative value on the sphere (CubemapSH::windowSH);
//  - pre-scaled for the shader (CubemapSH::preprocessSHForShader): the coefficients c_i of
//    E(d) / pi = c0 + c1 y + c2 z + c3 x + c4 y x + c5 y z + c6 (3 z^2 - 1) + c7 z x
//                + c8 (x^2 - y^2),
//    d in the engine's cube directions.
#include <array>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "ibl/sh.hpp"

namespace iblab {

using FilamentSh = std::array<glm::dvec3, kSh9Count>;

// cmgen's automatic window cut-off for irradiance coefficients E_lm (iblab's basis).
double filamentAutoWindowCutoff(const SH9Color& irradiance);
// Band l's factor of that window (1 for l = 0, 0 for l >= cutoff).
double filamentSincWindow(int band, double cutoff);

// The pre-scaled coefficients of irradiance E_lm (iblab's basis, unwindowed), windowed as
// cmgen does, for an engine whose cube direction d is iblab's direction engineToIblab d.
FilamentSh filamentShaderSh(const SH9Color& irradiance, const glm::dmat3& engineToIblab);

// sum_i c_i P_i(d) of the polynomial above.
glm::dvec3 evaluateFilamentSh(const FilamentSh& sh, glm::dvec3 d);

// Relative difference of band l (0, 1, 2) of two coefficient sets: |a_l - b_l| / |b_l| over
// the band's coefficients and the three channels.
double filamentBandDifference(const FilamentSh& a, const FilamentSh& b, int band);

} // namespace iblab
