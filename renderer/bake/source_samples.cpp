#include "bake/source_samples.hpp"

#include <cmath>
#include <cstdint>

#include "ibl/conventions.hpp"
#include "ibl/prefilter_lod.hpp"
#include "ibl/sampling.hpp"

namespace iblab::bake {
namespace {

glm::vec4 entry(glm::dvec3 l, double pdf, int sampleCount, float lodBias)
{
    return {glm::vec3(l), sourceLodSampleTerm(float(1.0 / (double(sampleCount) * pdf)), lodBias)};
}

} // namespace

std::vector<glm::vec4> cosineSampleTable(int sampleCount, float lodBias)
{
    std::vector<glm::vec4> table;
    table.reserve(std::size_t(sampleCount));
    const auto n = std::uint32_t(sampleCount);
    for (std::uint32_t i = 0; i < n; ++i) {
        const glm::dvec3 l = sampleCosineHemisphere(hammersley(i, n));
        table.push_back(entry(l, pdfCosineHemisphere(l), sampleCount, lodBias));
    }
    return table;
}

std::vector<glm::vec4> ggxReflectedSampleTable(float roughness, int sampleCount, float lodBias, float rotationDegrees)
{
    std::vector<glm::vec4> table;
    table.reserve(std::size_t(sampleCount));
    const double alpha = double(roughness) * double(roughness);
    if (alpha <= 0.0) {
        table.assign(std::size_t(sampleCount), glm::vec4(0.0f, 0.0f, 1.0f, 0.0f));
        return table;
    }
    const auto n = std::uint32_t(sampleCount);
    const double turn = double(rotationDegrees) * kPi / 180.0, c = std::cos(turn), s = std::sin(turn);
    for (std::uint32_t i = 0; i < n; ++i) {
        const glm::dvec3 g = sampleGgxHalfVector(hammersley(i, n), alpha);
        const glm::dvec3 h(c * g.x - s * g.y, s * g.x + c * g.y, g.z);
        // With n = v = +z: l = reflect(-n, h) = 2 (n.h) h - n, and v.h = n.h.
        const glm::dvec3 l = 2.0 * h.z * h - glm::dvec3(0.0, 0.0, 1.0);
        if (l.z <= 0.0)
            continue;
        table.push_back(entry(l, pdfGgxReflected(pdfGgxHalfVector(h, alpha), h.z), sampleCount, lodBias));
    }
    return table;
}

} // namespace iblab::bake
