#pragma once
// Error of a rendered frame against the reference: the per-pixel measure and false colour
// of assets/shaders/common/error_metrics.glsl (the same source, compiled with glm), and the
// summary numbers over a set of pixels.
#include <cstddef>
#include <cstdint>
#include <span>

#include "ibl/glsl_shared.hpp"

namespace iblab::shared {
#include "common/error_metrics.glsl"
}

namespace iblab {

using shared::falseColour;
using shared::isFirefly;
using shared::isMeasuredPixel;
using shared::relativeError;

struct ErrorMetrics {
    std::size_t pixels = 0;      // pixels measured
    double relativeRmse = 0.0;   // sqrt(mean(e^2)) of the per-pixel relative error e
    double meanRelative = 0.0;
    double maxRelative = 0.0;
    double p99Relative = 0.0;    // nearest rank: the smallest e with at least 99% of pixels <= e
    std::size_t fireflies = 0;   // pixels more than 3x as bright as the reference
};

// Over the pixels with include[i] != 0 of two RGBA float images of include.size() pixels
// each (alpha ignored). Throws std::invalid_argument when the sizes disagree.
ErrorMetrics computeErrorMetrics(std::span<const float> valueRgba, std::span<const float> referenceRgba, std::span<const std::uint8_t> include);

} // namespace iblab
