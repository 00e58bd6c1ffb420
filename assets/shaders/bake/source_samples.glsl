// The sample table of an importance-sampled pass, built by the host with the C++ core
// (renderer/bake/source_samples.hpp), one entry per sample: xyz the direction in the tangent
// frame (+z = the output texel's normal, so z is n.l), w the sample's term of the source lod
// (source_read.glsl).
#include "bake/source_read.glsl"

layout(std430, binding = 0) readonly buffer SourceSamples {
    vec4 sourceSamples[];
};
