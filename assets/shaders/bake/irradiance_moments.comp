// Diffuse irradiance E(n) = integral L(w) max(0, n.w) dOmega as a sum over the groups of
// environment texels that bake/equirect_moments.hpp summarised. For a group wholly above
// n's horizon max(0, n.w) = n.w is linear in w, so the group's exact share is
//   integral L_c (n.w) dOmega = n . (integral L_c w dOmega) = Phi_c (n . mu_c)
// whatever the radiance inside it looks like: a sun anywhere in the group lands where it is.
// Only a group that straddles the horizon is approximated: its share is Phi_c times the mean
// of max(0, t) over a uniform spread of t = n.w with the group's mean x = n . mu_c and its
// luminance-weighted variance var = n^T S n - (n . mu_Y)^2, i.e. over [x - r, x + r] with
// r = sqrt(3 var):
//   clampedCosine(x, r) = x (x >= r), 0 (x <= -r), (x + r)^2 / (4 r) between.
// The variance, not the group's size, sets r: a point of light straddles nothing, and a
// group lit at one edge spreads only as far as its light does.
// Exact for every group the sum does not approximate, with no sampling noise, and cheap: a
// few multiply-adds per group instead of a filtered texture read per sample.
#include "common/conventions.glsl"
#include "bake/moment_texel.glsl"
#include "bake/cube_texel.glsl"

// GROUPS: the number of groups. A uniform block, not a storage buffer: every invocation
// reads the same group at the same time, which llvmpipe serves from a uniform block three
// times faster than from a storage buffer (7 vs 23 ms for the default cube).
layout(std140, binding = 0) uniform MomentTexels {
    vec4 momentTexels[GROUPS * kMomentTexelVec4s];
};
// The same number as a uniform: a constant loop bound would have the compiler unroll all
// GROUPS iterations, which costs milliseconds to load in every process.
uniform int uGroupCount;

// r > 0; quarterOverR = 1 / (4 r), shared by the three channels.
float clampedCosine(float x, float r, float quarterOverR)
{
    float inside = clamp(x + r, 0.0, 2.0 * r);
    return inside * inside * quarterOverR + max(x - r, 0.0);
}

void main()
{
    ivec2 texel;
    if (!outputTexel(texel))
        return;
    vec3 n = outputTexelDirection(texel);
    vec3 nn = n * n;
    vec3 cross2 = 2.0 * vec3(n.x * n.y, n.x * n.z, n.y * n.z);
    vec3 irradiance = vec3(0.0);
    for (int j = 0; j < uGroupCount; ++j) {
        int base = j * kMomentTexelVec4s;
        MomentTexel t = MomentTexel(momentTexels[base], momentTexels[base + 1], momentTexels[base + 2], momentTexels[base + 3],
                                    momentTexels[base + 4], momentTexels[base + 5]);
        float secondMoment = dot(nn, vec3(t.momentRAndSxx.w, t.momentGAndSyy.w, t.momentBAndSzz.w)) +
                             dot(cross2, vec3(t.momentYAndSxy.w, t.secondMomentXzYz.xy));
        float meanY = dot(n, t.momentYAndSxy.xyz);
        float r = max(sqrt(3.0 * max(secondMoment - meanY * meanY, 0.0)), 1e-6);
        float quarterOverR = 0.25 / r;
        irradiance += t.flux.rgb * vec3(clampedCosine(dot(n, t.momentRAndSxx.xyz), r, quarterOverR),
                                        clampedCosine(dot(n, t.momentGAndSyy.xyz), r, quarterOverR),
                                        clampedCosine(dot(n, t.momentBAndSzz.xyz), r, quarterOverR));
    }
    storeOutput(texel, irradiance);
}
