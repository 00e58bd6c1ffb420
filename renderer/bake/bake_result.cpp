#include "bake/bake_result.hpp"

namespace iblab::bake {

std::size_t BakeResult::gpuBytes() const
{
    std::size_t total = environmentCube.bytes() + irradianceCube.bytes() + prefiltered.bytes();
    for (const BakedTexture& lut : brdfLut)
        total += lut.bytes();
    return total;
}

double BakeResult::phaseMilliseconds(BakePhase phase) const
{
    for (const PhaseTiming& t : timings)
        if (t.phase == phase)
            return t.milliseconds;
    return 0.0;
}

} // namespace iblab::bake
