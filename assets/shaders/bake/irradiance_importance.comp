// Diffuse irradiance by cosine-weighted importance sampling: with l drawn with density
// cos(theta) / pi, E = integral L cos dOmega is estimated by (1/N) sum L cos / pdf
// = (pi / N) sum L(l_i). With uMipFiltering each sample reads the source mip whose texels
// match its share of the sphere (prefilter_lod.glsl), which turns N point samples of a
// high-resolution map into N box-filtered ones: no fireflies from a small bright source.
// The N cosine samples are the table's (source_samples.glsl).
#include "common/conventions.glsl"
#include "common/sampling.glsl"
#include "bake/cube_texel.glsl"
#include "bake/source_samples.glsl"

void main()
{
    ivec2 texel;
    if (!outputTexel(texel))
        return;
    mat3 frame = tangentFrame(outputTexelDirection(texel));
    vec3 sum = vec3(0.0);
    int count = uSampleCount;
    for (int i = 0; i < count; ++i) {
        vec4 s = sourceSamples[i];
        sum += readSource(s.w, frame * s.xyz);
    }
    storeOutput(texel, sum * (IBL_PI / float(count)));
}
