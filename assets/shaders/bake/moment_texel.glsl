// One group of environment texels as the moment irradiance reads it (irradiance_moments.comp
// reads it, renderer/bake/equirect_moments.hpp writes it; renderer/bake/bake_passes.cpp sizes the
// buffer: kMomentTexelVec4s vec4 per group). Per channel c: the flux Phi_c = integral of L_c
// dOmega over the group and the first moment mu_c = (integral of L_c w dOmega) / Phi_c; for
// the luminance Y the first moment mu_Y and the second, S = (integral of Y w w^T dOmega) /
// Phi_Y, from which the spread of n.w over the group follows: var = n^T S n - (n . mu_Y)^2.
// The buffers are flat vec4 arrays, not arrays of this struct: GL reports every member of
// every element of a struct array as an active uniform, thousands to enumerate at link.
struct MomentTexel {
    vec4 flux;             // rgb: Phi_c
    vec4 momentRAndSxx;    // xyz: mu_r; w: S_xx
    vec4 momentGAndSyy;
    vec4 momentBAndSzz;
    vec4 momentYAndSxy;    // xyz: mu_Y; w: S_xy
    vec4 secondMomentXzYz; // x: S_xz; y: S_yz
};
const int kMomentTexelVec4s = 6;
