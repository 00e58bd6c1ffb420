#pragma once
// Filament cmgen's automatic SH window for a map whose irradiance is never negative, derived
// here independently of renderer/ibl/engine_sh: each channel's bisection accepts every
// midpoint, so it ends at the last l within 0.1 of the cut-off so far (CubemapSH::windowSH),
// three channels in turn. The export tests compare iblab's windowed SH against it.
namespace iblab::testing {

inline double cmgenNeverNegativeCutoff()
{
    double cutoff = 13.0;
    for (int channel = 0; channel < 3; ++channel) {
        double l = 3.0;
        for (int i = 0; i < 16 && l + 0.1 < cutoff; ++i) l = 0.5 * (l + cutoff);
        cutoff = l;
    }
    return cutoff;
}

} // namespace iblab::testing
