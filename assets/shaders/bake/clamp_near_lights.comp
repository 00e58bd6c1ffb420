// The split's bases near the bright texels (renderer/bake/near_lights.hpp): each listed base
// texel rewritten as the environment pass's own filter applied to the map clamped
// (equirect_footprint.glsl), after clamp_luminance.comp has clamped the environment's texels.
// The lights hold each bright map texel's excess over the threshold, and the environment
// pass spreads a bright map texel over several cube texels, whose spread parts can fall under
// the threshold; clamped in the cube they stayed in the base and were counted twice (about a
// quarter of the light on a map of 400 small lamps, whose many lights raise the threshold to
// their own level; docs/bake.md). Resampled from the map clamped, base plus lights is the map.
// A pass of its own over a list: in the clamp pass the filter's code slowed every texel.
#include "common/conventions.glsl"
#include "common/luminance.glsl"
#include "bake/luminance_clamp.glsl"
#include "bake/equirect_footprint.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Texels {
    ivec4 texels[]; // (x, y, face, 0) of the base
};
layout(binding = 0) writeonly uniform imageCube uTarget;
layout(binding = 2) writeonly uniform imageCube uSecondTarget;

uniform sampler2D uEquirect; // the map the environment pass read (level 0: float)
uniform int uCount;
uniform int uStep;           // environment level-0 texels per base texel, per edge
uniform int uSourceSize;     // the environment's level-0 face
uniform vec2 uThresholds;
uniform int uTargets;        // 1: uTarget only, 2: both

// Texel p of the map clamped at both thresholds, with the sampler's wrap: REPEAT in s,
// CLAMP_TO_EDGE in t.
void addClampedMapTexel(ivec2 p, ivec2 size, float weight, inout vec3 first, inout vec3 second)
{
    p.x = ((p.x % size.x) + size.x) % size.x;
    p.y = clamp(p.y, 0, size.y - 1);
    vec3 rgb = texelFetch(uEquirect, p, 0).rgb;
    float y = rec709Luminance(rgb);
    first += weight * clamped(rgb, y, uThresholds.x);
    second += weight * clamped(rgb, y, uThresholds.y);
}

// Level-0 texel `texel` of the environment as the environment pass filtered the map, the map
// clamped first: its taps, each bilinear at level 0 (the pass's read of a map whose level 0
// it samples; a map with mips it reads at a coarser lod, and there this is a close stand-in).
void addFilteredClampedMap(int face, ivec2 texel, inout vec3 first, inout vec3 second)
{
    ivec2 size = textureSize(uEquirect, 0);
    EquirectFootprint f = equirectFootprint(face, (vec2(texel) + 0.5) / float(uSourceSize), uSourceSize, vec2(size));
    float perTap = 1.0 / f.taps;
    for (float k = 0.0; k < f.taps; k += 1.0) {
        vec2 st = equirectFootprintTap(f, k) * vec2(size) - 0.5;
        ivec2 p = ivec2(floor(st));
        vec2 w = st - floor(st);
        addClampedMapTexel(p, size, perTap * (1.0 - w.x) * (1.0 - w.y), first, second);
        addClampedMapTexel(p + ivec2(1, 0), size, perTap * w.x * (1.0 - w.y), first, second);
        addClampedMapTexel(p + ivec2(0, 1), size, perTap * (1.0 - w.x) * w.y, first, second);
        addClampedMapTexel(p + ivec2(1, 1), size, perTap * w.x * w.y, first, second);
    }
}

void main()
{
    int index = int(gl_GlobalInvocationID.x);
    if (index >= uCount)
        return;
    ivec3 texel = texels[index].xyz;
    vec3 first = vec3(0.0), second = vec3(0.0);
    for (int dy = 0; dy < uStep; ++dy)
        for (int dx = 0; dx < uStep; ++dx)
            addFilteredClampedMap(texel.z, texel.xy * uStep + ivec2(dx, dy), first, second);
    float perBaseTexel = float(uStep * uStep);
    imageStore(uTarget, texel, vec4(first / perBaseTexel, 1.0));
    if (uTargets > 1)
        imageStore(uSecondTarget, texel, vec4(second / perBaseTexel, 1.0));
}
