// The bright-texel split's bases (renderer/bake/bright_texels.hpp): level 0 of the
// environment with every texel's luminance clamped to a threshold, chroma kept, then
// box-averaged over uStep x uStep texels into level 0 of a base (a face uStep times
// smaller: the finest level any sample reads; splitBaseTopLevel). Up to two bases, each
// with its threshold, from one read of each texel. A texel that is not finite
// (a half float that overflowed) becomes grey at the threshold: its flux is in the lights,
// summed from the float map. On the GPU, so that the split reads nothing back and uploads
// no cube (a 512^2 half-float cube is 12 MB each way). Near the bright texels
// clamp_near_lights.comp then rewrites the bases' texels from the map clamped.
#include "common/luminance.glsl"
#include "bake/luminance_clamp.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(FORMAT, binding = 1) readonly uniform imageCube uSource;
// The environment's level 1 (uStep >= 2): a 2 x 2 block whose average is at most a quarter
// of the lower threshold has no texel above either (luminance is not negative, so no texel
// exceeds the block's sum), and its average is what the clamp would give. Such a block is
// read once instead of four times; on most maps that is most of the sky.
layout(FORMAT, binding = 3) readonly uniform imageCube uSourceLevel1;
layout(binding = 0) writeonly uniform imageCube uTarget;
layout(binding = 2) writeonly uniform imageCube uSecondTarget;

uniform int uSize; // the base's face
uniform int uStep;
uniform vec2 uThresholds;
uniform int uTargets; // 1: uTarget only, 2: both

void main()
{
    ivec3 texel = ivec3(gl_GlobalInvocationID.xy, int(gl_GlobalInvocationID.z));
    if (texel.x >= uSize || texel.y >= uSize)
        return;
    vec3 first = vec3(0.0), second = vec3(0.0);
    int blocks = uStep >= 2 ? uStep / 2 : 1; // per edge
    int blockStep = uStep >= 2 ? 2 : 1;
    float lower = min(uThresholds.x, uThresholds.y);
    for (int by = 0; by < blocks; ++by)
        for (int bx = 0; bx < blocks; ++bx) {
            ivec2 block = texel.xy * blocks + ivec2(bx, by);
            if (uStep >= 2) {
                vec3 average = imageLoad(uSourceLevel1, ivec3(block, texel.z)).rgb;
                if (4.0 * rec709Luminance(average) <= lower) {
                    first += 4.0 * average;
                    second += 4.0 * average;
                    continue;
                }
            }
            for (int dy = 0; dy < blockStep; ++dy)
                for (int dx = 0; dx < blockStep; ++dx) {
                    vec3 rgb = imageLoad(uSource, ivec3(block * blockStep + ivec2(dx, dy), texel.z)).rgb;
                    float y = rec709Luminance(rgb);
                    first += clamped(rgb, y, uThresholds.x);
                    second += clamped(rgb, y, uThresholds.y);
                }
        }
    float texels = float(uStep * uStep);
    imageStore(uTarget, texel, vec4(first / texels, 1.0));
    if (uTargets > 1)
        imageStore(uSecondTarget, texel, vec4(second / texels, 1.0));
}
