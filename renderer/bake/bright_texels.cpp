#include "bake/bright_texels.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <string>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "bake/bake_passes.hpp"
#include "ibl/conventions.hpp"
#include "io/error.hpp"

namespace iblab::bake {
namespace {

float luminance(glm::vec3 c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

// Solid angle of texel (x, row) of a size^2 face: its area (2 / size)^2 on the face plane at
// distance 1, foreshortened by 1 / r^3 at its centre (r = the centre's distance). Within
// O(1 / size^2) of the exact value (summed over the sphere: 4e-6 of 4 pi at 256, 4e-3 at 8),
// which is all the threshold needs.
double approximateTexelSolidAngle(int x, int row, int size)
{
    const double u = 2.0 * (x + 0.5) / size - 1.0, v = 2.0 * (row + 0.5) / size - 1.0;
    const double r2 = 1.0 + u * u + v * v;
    return 4.0 / (double(size) * size * r2 * std::sqrt(r2));
}

// The exact one, for the flux of a bright texel: the corner differences of the solid angle
// of the face rectangle [0, a] x [0, b], atan(a b / sqrt(a^2 + b^2 + 1)).
double texelSolidAngle(int x, int row, int size)
{
    auto corner = [](double a, double b) { return std::atan2(a * b, std::sqrt(a * a + b * b + 1.0)); };
    const double u0 = 2.0 * x / size - 1.0, u1 = 2.0 * (x + 1) / size - 1.0;
    const double v0 = 2.0 * row / size - 1.0, v1 = 2.0 * (row + 1) / size - 1.0;
    return corner(u1, v1) - corner(u0, v1) - corner(u1, v0) + corner(u0, v0);
}

} // namespace

double ggxPrefilterNormalization(double roughness)
{
    // With v = n, dOmega_l = 4 (n.h) dOmega_h, so Z = 4 E[max(0, n.l)] for h drawn with
    // density D(h) (n.h), whose inverse CDF is cos^2(theta_h) = (1 - u) / (1 + (alpha^2 - 1) u);
    // n.l = 2 cos^2(theta_h) - 1. The integrand is smooth in u: the midpoint rule with 2^16
    // points is exact to well under 1e-6.
    const double a2 = roughness * roughness * roughness * roughness;
    constexpr int kSteps = 1 << 16;
    double sum = 0.0;
    for (int i = 0; i < kSteps; ++i) {
        const double u = (i + 0.5) / kSteps;
        const double cos2 = (1.0 - u) / (1.0 + (a2 - 1.0) * u);
        sum += std::max(0.0, 2.0 * cos2 - 1.0);
    }
    return 4.0 * sum / kSteps;
}

BrightTexelSplit splitBrightTexels(const CubeImage& level0, int maxTexels, float thresholdOverMean)
{
    BrightTexelSplit split;
    split.base = level0;
    const int f = level0.size;
    std::vector<double> solidAngle(std::size_t(f) * std::size_t(f));
    for (int row = 0; row < f; ++row)
        for (int x = 0; x < f; ++x)
            solidAngle[std::size_t(row) * std::size_t(f) + std::size_t(x)] = approximateTexelSolidAngle(x, row, f);

    double flux = 0.0;
    for (int face = 0; face < 6; ++face)
        for (int row = 0; row < f; ++row)
            for (int x = 0; x < f; ++x)
                flux += double(std::max(0.0f, luminance(level0.rgb(face, x, row)))) * solidAngle[std::size_t(row) * std::size_t(f) + std::size_t(x)];
    split.meanLuminance = float(flux / (4.0 * kPi));
    if (maxTexels <= 0)
        return split;

    // T: the multiple of the mean, or the luminance of the (maxTexels + 1)-th brightest
    // texel when more than maxTexels lie above that (only texels strictly above T are split).
    float threshold = thresholdOverMean * split.meanLuminance;
    std::vector<float> above;
    for (const glm::vec4& t : level0.texels)
        if (const float y = luminance(glm::vec3(t)); y > threshold)
            above.push_back(y);
    if (above.size() > std::size_t(maxTexels)) {
        std::nth_element(above.begin(), above.begin() + maxTexels, above.end(), std::greater<float>());
        threshold = above[std::size_t(maxTexels)];
    }
    split.threshold = threshold;

    for (int face = 0; face < 6; ++face)
        for (int row = 0; row < f; ++row)
            for (int x = 0; x < f; ++x) {
                glm::vec4& texel = split.base.at(face, x, row);
                const glm::vec3 rgb(texel);
                const float y = luminance(rgb);
                if (!(y > threshold))
                    continue;
                const glm::vec3 kept = rgb * (threshold / y);
                texel = glm::vec4(kept, texel.a);
                const double omega = texelSolidAngle(x, row, f);
                const glm::dvec3 excessFlux = glm::dvec3(rgb - kept) * omega;
                const glm::vec3 direction = level0.texelDirection(face, x, row);
                split.lights.emplace_back(direction, 0.0f);
                split.lights.emplace_back(glm::vec3(excessFlux), 0.0f);
                ++split.brightTexels;
            }
    return split;
}

PrefilterBrightTexels splitBrightTexels(BakePasses& passes, const BakedTexture& environment, const PrefilterSettings& settings)
{
    PrefilterBrightTexels out;
    out.capacity = 2 * settings.brightTexels;
    GLint maxBlockBytes = 0;
    glGetIntegerv(GL_MAX_UNIFORM_BLOCK_SIZE, &maxBlockBytes);
    if (GLint(out.capacity * sizeof(glm::vec4)) > maxBlockBytes)
        throw Error("prefilter", std::to_string(settings.brightTexels) + " bright texels need a " +
                                     std::to_string(out.capacity * sizeof(glm::vec4)) + "-byte uniform block; this GL driver allows " +
                                     std::to_string(maxBlockBytes) + " (lower prefilter.bright_texels)");
    const BrightTexelSplit split = splitBrightTexels(readCubeLevel(environment, 0), settings.brightTexels, settings.brightThreshold);
    out.count = split.brightTexels;
    out.threshold = split.threshold;
    out.meanLuminance = split.meanLuminance;
    out.base = createCubeTexture(environment.internalFormat, environment.size, environment.levels);
    uploadCubeLevel(out.base, 0, split.base);
    passes.generateMips(out.base);
    // GL leaves reads undefined where the bound range is shorter than the block: padded.
    std::vector<glm::vec4> padded(std::size_t(out.capacity), glm::vec4(0.0f));
    std::copy(split.lights.begin(), split.lights.end(), padded.begin());
    out.texels = gl::createBufferWith<glm::vec4>(padded);
    return out;
}

} // namespace iblab::bake
