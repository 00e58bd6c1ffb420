// Equirect -> one cube face (rows of it), each cube texel the average of the equirect over
// the texel's footprint. A single bilinear tap per texel would alias wherever the equirect
// is denser than the cube: towards the poles an equirect row shrinks to a point while a cube
// texel stays the same size, so a texel there covers many equirect columns. The footprint
// (the texel's two edge vectors mapped to equirect uv) is filtered the way anisotropic
// hardware does it, explicitly so that it does not depend on the driver: up to 4 trilinear
// taps along the longer axis, at the mip that matches the shorter one (equirect_footprint.glsl).
#include "common/conventions.glsl"
#include "bake/cube_texel.glsl"
#include "bake/equirect_footprint.glsl"

uniform sampler2D uEquirect; // mip-mapped, REPEAT in s, CLAMP_TO_EDGE in t

vec3 sampleFootprint(EquirectFootprint f)
{
    vec3 sum = vec3(0.0);
    for (float k = 0.0; k < f.taps; k += 1.0)
        sum += textureLod(uEquirect, equirectFootprintTap(f, k), f.lod).rgb;
    return sum / f.taps;
}

void main()
{
    ivec2 texel;
    if (!outputTexel(texel))
        return;
    storeOutput(texel, sampleFootprint(equirectFootprint(outputFace(), outputTexelFaceUv(texel), uFaceSize, vec2(textureSize(uEquirect, 0)))));
}
