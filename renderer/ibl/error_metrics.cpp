#include "ibl/error_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace iblab {

ErrorMetrics computeErrorMetrics(std::span<const float> valueRgba, std::span<const float> referenceRgba, std::span<const std::uint8_t> include)
{
    if (valueRgba.size() != include.size() * 4 || referenceRgba.size() != include.size() * 4)
        throw std::invalid_argument("computeErrorMetrics: " + std::to_string(valueRgba.size()) + " and " + std::to_string(referenceRgba.size()) +
                                    " floats for " + std::to_string(include.size()) + " RGBA pixels");
    std::vector<double> errors;
    ErrorMetrics m;
    double sum = 0.0, sumSquares = 0.0;
    for (std::size_t i = 0; i < include.size(); ++i) {
        if (!include[i]) continue;
        const glm::vec3 value(valueRgba[i * 4], valueRgba[i * 4 + 1], valueRgba[i * 4 + 2]);
        const glm::vec3 reference(referenceRgba[i * 4], referenceRgba[i * 4 + 1], referenceRgba[i * 4 + 2]);
        const double e = relativeError(value, reference);
        errors.push_back(e);
        sum += e;
        sumSquares += e * e;
        m.maxRelative = std::max(m.maxRelative, e);
        m.fireflies += isFirefly(value, reference) ? 1 : 0;
    }
    m.pixels = errors.size();
    if (errors.empty()) return m;
    const double n = double(errors.size());
    m.meanRelative = sum / n;
    m.relativeRmse = std::sqrt(sumSquares / n);
    const std::size_t rank = std::size_t(std::ceil(0.99 * n)) - 1;
    std::nth_element(errors.begin(), errors.begin() + std::ptrdiff_t(rank), errors.end());
    m.p99Relative = errors[rank];
    return m;
}

} // namespace iblab
