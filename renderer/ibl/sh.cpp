#include "ibl/sh.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "ibl/conventions.hpp"
#include "ibl/equirect.hpp"
#include "ibl/sampling.hpp"

namespace iblab {

namespace {

const double kY00 = 0.5 * std::sqrt(1.0 / kPi);         // 0.282095
const double kY1 = std::sqrt(3.0 / (4.0 * kPi));         // 0.488603
const double kY2Cross = 0.5 * std::sqrt(15.0 / kPi);     // 1.092548
const double kY20 = 0.25 * std::sqrt(5.0 / kPi);         // 0.315392
const double kY22 = 0.25 * std::sqrt(15.0 / kPi);        // 0.546274

} // namespace

std::array<double, kSh9Count> sh9Basis(glm::dvec3 d)
{
    return {
        kY00,
        kY1 * d.y,
        kY1 * d.z,
        kY1 * d.x,
        kY2Cross * d.x * d.y,
        kY2Cross * d.y * d.z,
        kY20 * (3.0 * d.z * d.z - 1.0),
        kY2Cross * d.x * d.z,
        kY22 * (d.x * d.x - d.y * d.y),
    };
}

SH9Color projectEquirect(const ImageRGB32F& image)
{
    SH9Color out;
    // Accumulate per row first, then add the row into the total: keeps partial sums of
    // similar magnitude (a 4k image has 8M texels; the row split bounds the error growth).
    for (int y = 0; y < image.height; ++y) {
        const double dOmega = equirectTexelSolidAngle(y, image.width, image.height);
        std::array<glm::dvec3, kSh9Count> row{};
        for (int x = 0; x < image.width; ++x) {
            const glm::dvec3 L(image.at(x, y));
            const auto Y = sh9Basis(equirectTexelDirection(x, y, image.width, image.height));
            for (int i = 0; i < kSh9Count; ++i)
                row[i] += L * Y[i];
        }
        for (int i = 0; i < kSh9Count; ++i)
            out.c[i] += row[i] * dOmega;
    }
    return out;
}

glm::dvec3 evaluate(const SH9Color& coeffs, glm::dvec3 dir)
{
    const auto Y = sh9Basis(glm::normalize(dir));
    glm::dvec3 sum(0.0);
    for (int i = 0; i < kSh9Count; ++i)
        sum += coeffs.c[i] * Y[i];
    return sum;
}

double cosineLobeBandFactor(int band)
{
    // A-hat_l = 2 pi integral_0^{pi/2} cos(theta) P_l(cos theta) sin(theta) dtheta:
    // l = 0: 2 pi * 1/2; l = 1: 2 pi * 1/3; l = 2: 2 pi * 1/8.
    switch (band) {
    case 0: return kPi;
    case 1: return 2.0 * kPi / 3.0;
    case 2: return kPi / 4.0;
    default: return 0.0;
    }
}

SH9Color convolveWithCosineLobe(const SH9Color& radianceLm)
{
    SH9Color irradianceLm;
    for (int i = 0; i < kSh9Count; ++i)
        irradianceLm.c[i] = radianceLm.c[i] * cosineLobeBandFactor(sh9Band(i));
    return irradianceLm;
}

double shWindowFactor(ShWindow window, int band, double width)
{
    if (window == ShWindow::None || band == 0)
        return 1.0;
    if (double(band) >= width)
        return 0.0;
    const double x = kPi * double(band) / width;
    if (window == ShWindow::Hanning)
        return 0.5 * (1.0 + std::cos(x));
    return std::sin(x) / x;
}

SH9Color applyWindow(const SH9Color& coeffs, ShWindow window, double width)
{
    SH9Color out;
    for (int i = 0; i < kSh9Count; ++i)
        out.c[i] = coeffs.c[i] * shWindowFactor(window, sh9Band(i), width);
    return out;
}

namespace {

// findMinimum's starting grid, 32 x 16 equirect texel centres (an 11-degree spacing), and its
// compass's 8 headings: the same for every call, so their trigonometry is done once. The
// window search calls findMinimum up to 42 times per bake, and a map that needs the search
// (sunrise.exr) spent 8 ms there, on the bake's critical path.
constexpr int kMinimumGridW = 32;
constexpr int kMinimumGridH = 16;

const std::vector<glm::dvec3>& minimumSearchGrid()
{
    static const std::vector<glm::dvec3> grid = [] {
        std::vector<glm::dvec3> g;
        for (int y = 0; y < kMinimumGridH; ++y)
            for (int x = 0; x < kMinimumGridW; ++x)
                g.push_back(equirectTexelDirection(x, y, kMinimumGridW, kMinimumGridH));
        return g;
    }();
    return grid;
}

const std::array<glm::dvec2, 8>& compassHeadings()
{
    static const std::array<glm::dvec2, 8> headings = [] {
        std::array<glm::dvec2, 8> h;
        for (int k = 0; k < 8; ++k) {
            const double a = 2.0 * kPi * k / 8.0;
            h[std::size_t(k)] = glm::dvec2(std::cos(a), std::sin(a));
        }
        return h;
    }();
    return headings;
}

} // namespace

ShMinimum findMinimum(const SH9Color& coeffs, double stopBelow)
{
    // SH9 is a quadratic c + b.d + d^T A d restricted to the sphere, which has at most one
    // local minimiser besides the global one (Martinez 1994, on the trust-region subproblem).
    // Starting from the best point of an 11-degree grid therefore lands in the global basin
    // unless the two minima are within the grid's sampling error of each other, in which case
    // either answer is within that error of the true minimum.
    // The grid pass serves the three channels at once (evaluate gives all three).
    glm::dvec3 gridBest(std::numeric_limits<double>::infinity());
    std::array<glm::dvec3, 3> gridBestDir;
    gridBestDir.fill(glm::dvec3(0.0, 1.0, 0.0));
    for (const glm::dvec3& d : minimumSearchGrid()) {
        const glm::dvec3 v = evaluate(coeffs, d);
        for (int ch = 0; ch < 3; ++ch)
            if (v[ch] < gridBest[ch]) {
                gridBest[ch] = v[ch];
                gridBestDir[std::size_t(ch)] = d;
            }
    }
    ShMinimum result;
    for (int ch = 0; ch < 3; ++ch) {
        auto f = [&](glm::dvec3 d) { return evaluate(coeffs, d)[ch]; };
        // Rounding error of one evaluation: every basis function is at most 1.1 in
        // magnitude. A "decrease" below it is noise, and accepting it let the search wander
        // along a flat minimum at the smallest step for tens of seconds (a one-texel light's
        // windowed irradiance, whose minimum is a double root, as the GPU projects it).
        double magnitude = 0.0;
        for (const glm::dvec3& c : coeffs.c)
            magnitude += std::abs(c[ch]);
        const double noise = 16.0 * std::numeric_limits<double>::epsilon() * 1.1 * magnitude;
        double best = gridBest[ch];
        glm::dvec3 bestDir = gridBestDir[std::size_t(ch)];
        // Compass search in the tangent plane, re-projected onto the sphere.
        double step = kPi / kMinimumGridH;
        while (step > 1e-9 && !(best < stopBelow)) {
            const Frame frame = tangentFrame(bestDir);
            bool improved = false;
            for (const glm::dvec2& heading : compassHeadings()) {
                const glm::dvec3 d = glm::normalize(bestDir + step * (heading.x * frame.t + heading.y * frame.b));
                const double v = f(d);
                if (v < best - noise) {
                    best = v;
                    bestDir = d;
                    improved = true;
                    break;
                }
            }
            if (!improved)
                step *= 0.5;
        }
        result.value[ch] = best;
        result.direction[ch] = bestDir;
    }
    return result;
}

double findNonNegativeWindowWidth(const SH9Color& coeffs, ShWindow window, double minWidth, double maxWidth)
{
    auto nonNegative = [&](double w) {
        // A search stops at its first negative value: that settles it, and a map with a
        // bright sun took half a second of searching down to the minimum (2 degrees at 1e6).
        const glm::dvec3 m = findMinimum(applyWindow(coeffs, window, w), 0.0).value;
        return m.x >= 0.0 && m.y >= 0.0 && m.z >= 0.0;
    };
    if (window == ShWindow::None || nonNegative(maxWidth))
        return maxWidth;
    if (!nonNegative(minWidth))
        return minWidth;
    double lo = minWidth; // non-negative
    double hi = maxWidth; // negative somewhere
    for (int i = 0; i < 40; ++i) {
        const double mid = 0.5 * (lo + hi);
        (nonNegative(mid) ? lo : hi) = mid;
    }
    return lo;
}

} // namespace iblab
