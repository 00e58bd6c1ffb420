#include "ibl/engine_sh.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace iblab {
namespace {

std::array<double, kSh9Count> filamentPolynomials(glm::dvec3 d)
{
    return {1.0, d.y, d.z, d.x, d.y * d.x, d.y * d.z, 3.0 * d.z * d.z - 1.0, d.z * d.x, d.x * d.x - d.y * d.y};
}

SH9Color windowed(const SH9Color& sh, double cutoff)
{
    SH9Color out = sh;
    for (int i = 0; i < kSh9Count; ++i) out.c[std::size_t(i)] *= filamentSincWindow(sh9Band(i), cutoff);
    return out;
}

// Directions spread evenly over the sphere (a Fibonacci lattice).
std::vector<glm::dvec3> fitDirections()
{
    constexpr int n = 256;
    std::vector<glm::dvec3> d;
    const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < n; ++i) {
        const double y = 1.0 - 2.0 * (i + 0.5) / n;
        const double r = std::sqrt(std::max(0.0, 1.0 - y * y));
        d.push_back({r * std::cos(golden * i), y, r * std::sin(golden * i)});
    }
    return d;
}

} // namespace

double filamentSincWindow(int band, double cutoff)
{
    if (band == 0) return 1.0;
    if (band >= cutoff) return 0.0;
    const double x = std::numbers::pi * band / cutoff;
    return std::pow(std::sin(x) / x, 4.0);
}

double filamentAutoWindowCutoff(const SH9Color& irradiance)
{
    // CubemapSH::windowSH with cutoff 0 and 3 bands: start at 3 * 4 + 1, then per channel a
    // bisection between 3 and the cut-off so far, at most 16 halvings, to a width of 0.1.
    double cutoff = 13.0;
    for (int channel = 0; channel < 3; ++channel) {
        SH9Color one;
        for (int i = 0; i < kSh9Count; ++i) one.c[std::size_t(i)] = glm::dvec3(irradiance.c[std::size_t(i)][channel]);
        double l = 3.0;
        double r = cutoff;
        for (int i = 0; i < 16 && l + 0.1 < r; ++i) {
            const double m = 0.5 * (l + r);
            if (findMinimum(windowed(one, m)).value.x < 0.0)
                r = m;
            else
                l = m;
        }
        cutoff = std::min(cutoff, l);
    }
    return cutoff;
}

FilamentSh filamentShaderSh(const SH9Color& irradiance, const glm::dmat3& engineToIblab)
{
    const SH9Color w = windowed(irradiance, filamentAutoWindowCutoff(irradiance));
    // E(engineToIblab d) / pi is a degree-2 polynomial in d, so the least-squares fit of the
    // nine polynomials on directions spread over the sphere gives its coefficients exactly
    // (up to rounding); whatever the signs and axes of the two bases.
    double ata[kSh9Count][kSh9Count] = {};
    glm::dvec3 atb[kSh9Count] = {};
    for (const glm::dvec3& d : fitDirections()) {
        const auto p = filamentPolynomials(d);
        const glm::dvec3 value = evaluate(w, engineToIblab * d) / std::numbers::pi;
        for (int i = 0; i < kSh9Count; ++i) {
            for (int j = 0; j < kSh9Count; ++j) ata[i][j] += p[std::size_t(i)] * p[std::size_t(j)];
            atb[i] += p[std::size_t(i)] * value;
        }
    }
    // Gaussian elimination with partial pivoting (the matrix is well conditioned: the
    // polynomials are orthogonal on the sphere).
    for (int col = 0; col < kSh9Count; ++col) {
        int pivot = col;
        for (int row = col + 1; row < kSh9Count; ++row)
            if (std::abs(ata[row][col]) > std::abs(ata[pivot][col])) pivot = row;
        std::swap(ata[col], ata[pivot]);
        std::swap(atb[col], atb[pivot]);
        for (int row = col + 1; row < kSh9Count; ++row) {
            const double f = ata[row][col] / ata[col][col];
            for (int k = col; k < kSh9Count; ++k) ata[row][k] -= f * ata[col][k];
            atb[row] -= f * atb[col];
        }
    }
    FilamentSh c{};
    for (int row = kSh9Count - 1; row >= 0; --row) {
        glm::dvec3 v = atb[row];
        for (int k = row + 1; k < kSh9Count; ++k) v -= ata[row][k] * c[std::size_t(k)];
        c[std::size_t(row)] = v / ata[row][row];
    }
    return c;
}

glm::dvec3 evaluateFilamentSh(const FilamentSh& sh, glm::dvec3 d)
{
    const auto p = filamentPolynomials(d);
    glm::dvec3 v(0.0);
    for (int i = 0; i < kSh9Count; ++i) v += sh[std::size_t(i)] * p[std::size_t(i)];
    return v;
}

double filamentBandDifference(const FilamentSh& a, const FilamentSh& b, int band)
{
    double diff = 0.0;
    double ref = 0.0;
    for (int i = 0; i < kSh9Count; ++i) {
        if (sh9Band(i) != band) continue;
        const glm::dvec3 d = a[std::size_t(i)] - b[std::size_t(i)];
        diff += glm::dot(d, d);
        ref += glm::dot(b[std::size_t(i)], b[std::size_t(i)]);
    }
    return ref > 0.0 ? std::sqrt(diff / ref) : std::sqrt(diff);
}

} // namespace iblab
