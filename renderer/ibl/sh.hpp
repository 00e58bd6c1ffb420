#pragma once
// Order-3 (nine coefficient, bands l = 0..2) real spherical harmonics for diffuse lighting
// (Ramamoorthi & Hanrahan 2001; Sloan 2008, "Stupid Spherical Harmonics (SH) Tricks").
//
// Basis, evaluated on iblab world axes (x, y, z) of a unit direction, +Y up — exactly
// Sloan's table with no Condon-Shortley phase (every constant positive):
//   index 0 (0, 0): 0.282095                 = 1/2 sqrt(1/pi)
//   index 1 (1,-1): 0.488603 y               = sqrt(3/(4 pi)) y
//   index 2 (1, 0): 0.488603 z
//   index 3 (1, 1): 0.488603 x
//   index 4 (2,-2): 1.092548 x y             = 1/2 sqrt(15/pi) x y
//   index 5 (2,-1): 1.092548 y z
//   index 6 (2, 0): 0.315392 (3 z^2 - 1)     = 1/4 sqrt(5/pi) (3 z^2 - 1)
//   index 7 (2, 1): 1.092548 x z
//   index 8 (2, 2): 0.546274 (x^2 - y^2)     = 1/4 sqrt(15/pi) (x^2 - y^2)
// Note the zonal axis of this basis is world z, not the +Y up axis: that is only a choice
// of labels (the nine functions span the same space under any rotation), but a shader that
// evaluates these coefficients must use the same table on the same axes.
// The constants below are the exact expressions; Sloan's six-digit values differ by < 1e-6.
//
// Two kinds of coefficient set travel in SH9Color and must not be confused:
//   radiance   L_lm = integral L(w) Y_lm(w) dOmega               (projectEquirect)
//   irradiance E_lm = A-hat_l L_lm, E(n) = sum E_lm Y_lm(n)      (convolveWithCosineLobe)
// with A-hat_0 = pi, A-hat_1 = 2 pi / 3, A-hat_2 = pi / 4 (Ramamoorthi & Hanrahan eq. 8),
// the zonal coefficients of max(0, cos) scaled by sqrt(4 pi / (2l + 1)) (Funk-Hecke).
// Lambertian outgoing radiance is then albedo / pi * E(n).
#include <array>
#include <limits>

#include <glm/vec3.hpp>

#include "ibl/enum_names.hpp"
#include "ibl/image.hpp"

namespace iblab {

inline constexpr const char* kSh9Convention =
    "real SH9, Sloan 2008 constants, no Condon-Shortley phase, world axes x,y,z (+Y up), "
    "order (0,0),(1,-1),(1,0),(1,1),(2,-2),(2,-1),(2,0),(2,1),(2,2)";

inline constexpr int kSh9Count = 9;

// Band l of coefficient index i (0, 1, 1, 1, 2, 2, 2, 2, 2).
constexpr int sh9Band(int index)
{
    return index == 0 ? 0 : (index < 4 ? 1 : 2);
}

struct SH9Color {
    std::array<glm::dvec3, kSh9Count> c{};
};

// The nine basis functions at a unit direction.
std::array<double, kSh9Count> sh9Basis(glm::dvec3 dir);

// Radiance coefficients L_lm of an equirect image: sum over every texel of
// L(texel) Y_lm(texel centre) dOmega(texel), with the texel's exact solid angle (equirect.hpp)
// and double accumulation. The result is exact for the projection of the image's texel-centre
// samples; the only error is the midpoint rule within each texel.
SH9Color projectEquirect(const ImageRGB32F& image);

// sum_i coeffs.c[i] Y_i(dir): radiance for L_lm, irradiance for E_lm.
glm::dvec3 evaluate(const SH9Color& coeffs, glm::dvec3 dir);

// The clamped-cosine lobe's band factors A-hat_l (pi, 2 pi / 3, pi / 4).
double cosineLobeBandFactor(int band);

// Irradiance coefficients E_lm = A-hat_l L_lm from radiance coefficients L_lm.
SH9Color convolveWithCosineLobe(const SH9Color& radianceLm);

// Windowing against ringing. A bright, small source projected onto only three bands rings:
// the truncated series overshoots and goes negative on the far side. Scaling band l by a
// window factor sigma_l (a convolution with a zonal kernel) trades sharpness for
// non-negativity (Sloan 2008, section "Windowing"). Both windows are parameterised by a
// width w in band units: band l is scaled by
//   Hanning: (1 + cos(pi l / w)) / 2 for l < w, 0 otherwise
//   Lanczos: sinc(pi l / w) = sin(pi l / w) / (pi l / w) for l < w, 0 otherwise (sigma factors)
// Band 0 is never changed (sigma_0 = 1), so the mean is preserved. Larger w = weaker
// filtering; w -> infinity is no window. A typical strong setting for SH9 is w = 3 (Hanning
// scales bands 1 and 2 by 0.75 and 0.25).
enum class ShWindow { None, Hanning, Lanczos };
template <>
struct EnumNames<ShWindow> {
    static constexpr std::array<EnumName<ShWindow>, 3> entries{{{ShWindow::None, "none"}, {ShWindow::Hanning, "hanning"}, {ShWindow::Lanczos, "lanczos"}}};
};

double shWindowFactor(ShWindow window, int band, double width);
SH9Color applyWindow(const SH9Color& coeffs, ShWindow window, double width);

// The minimum over the sphere of each colour channel of sum c_i Y_i (for ringing checks:
// irradiance must be >= 0). Found by a dense direction grid then a shrinking pattern search
// on the sphere from the best grid point; accurate to ~1e-9 relative for these smooth
// degree-2 polynomials.
struct ShMinimum {
    glm::dvec3 value{0.0};
    std::array<glm::dvec3, 3> direction{}; // where each channel's minimum lies
};
// With stopBelow, a channel's search stops at the first value found below it, which it
// reports (the window search only asks whether a minimum is negative).
ShMinimum findMinimum(const SH9Color& coeffs, double stopBelow = -std::numeric_limits<double>::infinity());

// The largest window width (bisection within [minWidth, maxWidth]) for which every channel of
// the windowed coefficients' minimum is >= 0, i.e. the gentlest window that removes negative
// lobes. Returns maxWidth if the coefficients are already non-negative there and minWidth if
// even that is not enough (a negative mean cannot be fixed by windowing).
double findNonNegativeWindowWidth(const SH9Color& coeffs, ShWindow window, double minWidth = 1.0,
                                  double maxWidth = 64.0);

} // namespace iblab
