#pragma once
// Independent numerical integration for checking samplers and BRDF terms: nothing here
// shares code with the sampling under test.
#include <numbers>

namespace iblab::testing {

// Integral over the upper hemisphere of an azimuthally symmetric f(theta) dOmega:
// 2 pi times the midpoint rule in theta with the sin(theta) Jacobian. The GGX lobe at
// alpha = 0.05 is ~3 degrees wide; 200k steps over [0, pi/2] are 8e-6 rad each, so the
// rule's O(h^2 f'') error is far below any tolerance the tests use.
template <typename Fn>
double integrateSymmetricHemisphere(Fn&& f, int steps = 200000)
{
    const double h = 0.5 * std::numbers::pi / steps;
    double sum = 0.0;
    for (int k = 0; k < steps; ++k) {
        const double theta = (k + 0.5) * h;
        sum += f(theta) * std::sin(theta);
    }
    return 2.0 * std::numbers::pi * sum * h;
}

} // namespace iblab::testing
