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
#include "common/luminance.glsl"
#include "bake/cube_texel.glsl"
#include "bake/source_samples.glsl"

// BRIGHT_CAPACITY > 0: the environment's brightest texels, split off by the host
// (renderer/bake/bright_texels.hpp), summed exactly with the GGX weight of each; the source
// cube the samples read is then the rest of the environment. The block's layout is
// bright_texels_block.hpp's: uBrightCount far cells, (direction, first light),
// (flux, light count), then their lights, (direction, 0), (flux, 0).
#if BRIGHT_CAPACITY > 0
layout(std140, binding = 1) uniform BrightTexels {
    vec4 brightTexels[BRIGHT_CAPACITY];
};
uniform int uBrightCount;   // far cells
uniform float uNearCos;     // a cell nearer than this cosine is summed light by light
uniform float uAlpha2;      // alpha^2 = roughness^4
uniform float uBrightScale; // alpha^2 / (pi Z(alpha)), Z the integral of D(h) max(0, n.l)

// flux D(h) max(0, n.l) without the constant alpha^2 / pi (brdf.glsl's ggxPrefilterWeight).
vec3 brightTerm(float c, vec3 flux)
{
    return flux * ggxPrefilterWeight(c, 1.0 - c, uAlpha2);
}

vec3 sumBrightTexels(vec3 n)
{
    vec3 sum = vec3(0.0);
    for (int j = 0; j < uBrightCount; ++j) {
        vec4 cell = brightTexels[2 * j];
        vec4 cellFlux = brightTexels[2 * j + 1];
        float c = dot(n, cell.xyz);
        if (c > uNearCos) {
            int first = int(cell.w);
            int count = int(cellFlux.w);
            for (int k = first; k < first + count; ++k)
                sum += brightTerm(dot(n, brightTexels[2 * k].xyz), brightTexels[2 * k + 1].xyz);
        } else {
            sum += brightTerm(c, cellFlux.xyz);
        }
    }
    return sum * uBrightScale;
}

// uTileLightsPerEdge > 0 (mips 1 and 2): lights listed per tile of 8 x 8 texels, a work
// group (renderer/bake/tile_lights.hpp: mip 1's band below its block's threshold, mip 2's
// lights): (index of its first light's entry, light count, 0, 0) per tile, then the lights,
// (direction, 0), (flux, 0). Every lane of a group reads the same entries.
layout(std430, binding = 3) readonly buffer TileLights {
    vec4 tileLights[];
};
uniform int uTileLightsPerEdge;

vec3 sumTileLights(vec3 n, ivec2 texel)
{
    const int tileTexels = 8; // cube_texel.glsl's work group, tile_lights.hpp's kTileLightsTile
    ivec2 tile = texel / tileTexels;
    vec4 list = tileLights[(outputFace() * uTileLightsPerEdge + tile.y) * uTileLightsPerEdge + tile.x];
    int first = int(list.x), end = first + 2 * int(list.y);
    vec3 sum = vec3(0.0);
    for (int k = first; k < end; k += 2)
        sum += brightTerm(dot(n, tileLights[k].xyz), tileLights[k + 1].xyz);
    return sum * uBrightScale;
}

// uExactCount > 0: the base summed over every texel of one of its mips (texels at most
// alpha / 2 across, so that the weight is nearly constant over each; the host chooses it,
// bright_texels.hpp's exactSumSourceLevel), each texel weighted by D(h) max(0, n.l) times its
// solid angle, and normalised by the weights' sum: a constant map stays exact. The host
// lists the texels (PrefilterBrightTexels::Level::exactTexels: (direction, 0), (radiance x
// solid angle, solid angle)), so that every lane reads the same entry at the same time and
// no texture: on llvmpipe a cube read per texel made mip 4 cost about twice as much. The
// table is a uniform block where it fits (EXACT_CAPACITY > 0, as source_samples.glsl's sample
// tables: mip 4 took 2.9 ms on courtyard.exr against 5.1 from a storage buffer), else a
// storage buffer. Where the samples see a large bright area through a few reads that move with
// the texel, this sees every texel of it with its weight. A mip whose source is too large for
// one table (the default's mip 3) sums per-tile cuts of it instead (exact_tiles.hpp): the host
// binds each tile's list as this block for that tile's work group alone, with its uExactCount.
#if EXACT_CAPACITY > 0
layout(std140, binding = 2) uniform ExactTexels {
    vec4 exactTexels[EXACT_CAPACITY];
};
#else
layout(std430, binding = 2) readonly buffer ExactTexels {
    vec4 exactTexels[];
};
#endif
uniform int uExactCount;

vec3 exactBaseSum(vec3 n)
{
    vec3 sum = vec3(0.0);
    float weightSum = 0.0;
    for (int i = 0; i < uExactCount; ++i) {
        vec4 texel = exactTexels[2 * i];
        vec4 radiance = exactTexels[2 * i + 1];
        float c = dot(n, texel.xyz);
        float w = ggxPrefilterWeight(c, 1.0 - c, uAlpha2);
        sum += w * radiance.rgb;
        weightSum += w * radiance.w;
    }
    return sum / weightSum;
}
#endif

uniform float uRoughness;      // perceptual; 0 selects the mirror level
uniform float uWeightSum;      // sum of n.l over the table
uniform float uCopyLod;
uniform int uMirrorCopy;
// uRefineCount > 0: the table holds a second set after the first uSampleCount entries, of
// uRefineCount samples (their n.l summing to uRefineWeightSum), which a texel whose first
// samples' luminances spread by more than uRefineSpread takes instead. Near the edge of a
// large bright area of the base a few samples, each reading a mip the edge cuts, alias it;
// where they agree the texel sees a smooth neighbourhood and keeps them. A texel whose
// samples' mean has a standard error above uRefineError takes it too: on texel noise each
// sample reads a different handful of texels, their spread stays below uRefineSpread, and
// the mean of 8 is still off by a twentieth of the map.
uniform int uRefineCount;
uniform float uRefineSpread;
uniform float uRefineWeightSum;
uniform float uRefineError;

// The samples' n.l-weighted sum of radiance, and the range and weighted sum of squares of
// their luminances.
vec3 sampledSum(mat3 frame, int first, int count, out vec2 luminanceRange, out float luminanceSquares)
{
    vec3 sum = vec3(0.0);
    luminanceRange = vec2(1e30, 0.0);
    luminanceSquares = 0.0;
    for (int i = first; i < first + count; ++i) {
        vec4 s = sourceSamples[i];
        vec3 radiance = readSource(s.w, frame * s.xyz);
        float luminance = rec709Luminance(radiance);
        luminanceRange = vec2(min(luminanceRange.x, luminance), max(luminanceRange.y, luminance));
        luminanceSquares += luminance * luminance * s.z;
        sum += radiance * s.z;
    }
    return sum;
}

// Whether the first set's estimate needs the refined set: its samples disagree by more than
// the spread, or the variance of their weighted mean (the samples' variance over their count)
// exceeds uRefineError^2.
bool needsRefinement(vec2 range, float luminanceSquares, vec3 mean)
{
    float meanLuminance = rec709Luminance(mean);
    float variance = max(luminanceSquares / uWeightSum - meanLuminance * meanLuminance, 0.0);
    return range.y - range.x > uRefineSpread || variance > uRefineError * uRefineError * float(uSampleCount);
}

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
    vec3 radiance;
#if BRIGHT_CAPACITY > 0
    if (uExactCount > 0)
        radiance = exactBaseSum(n);
    else
#endif
    {
        mat3 frame = tangentFrame(n);
        vec2 range;
        float squares;
        radiance = sampledSum(frame, 0, uSampleCount, range, squares) / uWeightSum;
        if (uRefineCount > 0 && needsRefinement(range, squares, radiance))
            radiance = sampledSum(frame, uSampleCount, uRefineCount, range, squares) / uRefineWeightSum;
    }
#if BRIGHT_CAPACITY > 0
    radiance += sumBrightTexels(n);
    if (uTileLightsPerEdge > 0)
        radiance += sumTileLights(n, texel);
#endif
    storeOutput(texel, radiance);
}
