#pragma once
// Bilinear reads of a table over [0, 1]^2, as a shader's texture() reads it with LINEAR
// filtering and CLAMP_TO_EDGE: texel centres at (i + 0.5) / size, coordinates clamped to
// [0, 1], the outermost texels repeated beyond their centres. One definition for every CPU
// read of a GPU table: the split-sum LUT (brdf_lut.hpp's layout) and the fitted lobe table
// (specular_approximations.hpp).
#include <algorithm>
#include <cmath>

namespace iblab {

// fetch(col, row) returns the texel (any type with + and * double); x selects among `cols`
// columns, y among `rows` rows.
template <typename Fetch>
auto sampleTableBilinear(double x, double y, int cols, int rows, const Fetch& fetch)
{
    struct Taps {
        int i0, i1;
        double t; // weight of i1
    };
    const auto axis = [](double u, int size) {
        const double f = std::clamp(u, 0.0, 1.0) * size - 0.5;
        const double fl = std::floor(f);
        return Taps{std::clamp(int(fl), 0, size - 1), std::clamp(int(fl) + 1, 0, size - 1), f - fl};
    };
    const Taps tx = axis(x, cols), ty = axis(y, rows);
    return (fetch(tx.i0, ty.i0) * (1.0 - tx.t) + fetch(tx.i1, ty.i0) * tx.t) * (1.0 - ty.t) +
           (fetch(tx.i0, ty.i1) * (1.0 - tx.t) + fetch(tx.i1, ty.i1) * tx.t) * ty.t;
}

} // namespace iblab
