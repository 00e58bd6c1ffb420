// What shading reads from a prefiltered cube for a (direction, roughness) pair: textureLod at
// the lod of the bake's roughness layout (prefilter_lod.glsl), trilinear and seamless, the
// lookup ibl_lighting.glsl's shadeSplitSum makes. bake_accuracy compares these values with the
// exact reference at arbitrary directions and roughness values ("as shaded"), which counts
// what a texel-centre comparison cannot: interpolation between texels and between mips.
#include "common/prefilter_lod.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Queries { vec4 queries[]; }; // xyz direction, w roughness
layout(std430, binding = 1) writeonly buffer Radiance { vec4 radiance[]; };

uniform int uCount;
uniform samplerCube uPrefiltered;
uniform float uLevels;
uniform int uLayout;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= uint(uCount))
        return;
    vec4 q = queries[i];
    radiance[i] = vec4(textureLod(uPrefiltered, q.xyz, prefilterMipFromRoughness(q.w, uLevels, uLayout)).rgb, 0.0);
}
