// The sample table of an importance-sampled pass, built by the host with the C++ core
// (renderer/bake/source_samples.hpp), one entry per sample: xyz the direction in the tangent
// frame (+z = the output texel's normal, so z is n.l), w the sample's term of the source lod
// (source_read.glsl).
// SAMPLE_TABLE_CAPACITY > 0: the table is a uniform block of that many entries (the host pads
// it). Every invocation reads the same entry at the same time, which llvmpipe serves from a
// uniform block with one load for all its lanes, and from a storage buffer lane by lane, with
// a bounds check each: the default bake's prefilter took 83 ms with its tables in storage
// buffers and 36 ms in uniform blocks (scripts/measure-bake.sh phases). 0: a storage buffer,
// for a table larger than the uniform block the driver allows (BakePasses chooses).
#include "bake/source_read.glsl"

#if SAMPLE_TABLE_CAPACITY > 0
layout(std140, binding = 0) uniform SourceSamples {
    vec4 sourceSamples[SAMPLE_TABLE_CAPACITY];
};
#else
layout(std430, binding = 0) readonly buffer SourceSamples {
    vec4 sourceSamples[];
};
#endif
// The table's length, read by both variants the same way. A uniform, not a constant: a
// constant bound would have the compiler unroll the loop.
uniform int uSampleCount;
