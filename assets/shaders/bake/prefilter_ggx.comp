// One mip of the GGX-prefiltered specular cube (split-sum part 1, Karis 2013; LearnOpenGL's
// prefilter with the same N = V = R assumption): the cos-weighted average of the
// environment over the GGX lobe around n,
//   sum L(l_i) (n.l_i) / sum (n.l_i),  h_i ~ D(h)(n.h),  l_i = reflect(-n, h_i),
// which converges to renderer/ibl/reference.hpp's referencePrefilteredRadiance.
// With uMipFiltering each sample reads the source mip that matches its share of the lobe
// (the density of l is D(h)(n.h) / (4 v.h) = D / 4 with v = n), see prefilter_lod.glsl.
// The half vectors, their reflections and pdfs are the table's (source_samples.glsl), built
// for this mip's roughness and sample count; the weights n.l are the same for every texel,
// so their sum is a uniform.
// Roughness 0 is a delta lobe: with uMirrorCopy the mirror level is the environment itself,
// read at uCopyLod (the source mip with this level's texel size, so it is a box-filtered
// copy, not a point sample that aliases when the source is larger). Without, the loop runs
// as LearnOpenGL's does: alpha = 0 puts every half vector on n, and every sample reads n
// (at mip 0: the roughness-0 pdf is a delta, there is no footprint to filter).
#include "common/conventions.glsl"
#include "common/sampling.glsl"
#include "bake/cube_texel.glsl"
#include "bake/source_samples.glsl"

uniform float uRoughness;      // perceptual; 0 selects the mirror level
uniform float uWeightSum;      // sum of n.l over the table
uniform float uCopyLod;
uniform int uMirrorCopy;

void main()
{
    ivec2 texel;
    if (!outputTexel(texel))
        return;
    vec3 n = outputTexelDirection(texel);
    if (uRoughness <= 0.0 && uMirrorCopy != 0) {
        storeOutput(texel, textureLod(uEnvironment, n, uCopyLod).rgb);
        return;
    }
    mat3 frame = tangentFrame(n);
    vec3 sum = vec3(0.0);
    int count = uSampleCount;
    for (int i = 0; i < count; ++i) {
        vec4 s = sourceSamples[i];
        sum += readSource(s.w, frame * s.xyz) * s.z;
    }
    storeOutput(texel, sum / uWeightSum);
}
