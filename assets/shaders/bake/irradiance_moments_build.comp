// The environment cube grouped into the texels of a coarse cube (uGroupFaceSize^2 per face),
// each group summarised by what the clamped-cosine integral needs of it, per channel c:
//   flux      Phi_c = integral over the group of L_c dOmega
//   moment    mu_c  = (integral of L_c w dOmega) / Phi_c, a vector of length <= 1
// and for the luminance the first and second moments (moment_texel.glsl;
// irradiance_moments.comp explains why that is exact for every group above the horizon).
// One invocation per group, looping over the group's texels of the environment level the
// host binds (no shared-memory reduction: on llvmpipe its barriers cost more than the loop).
// FORMAT: the environment's image format qualifier (rgba16f, rgba32f).
#include "common/conventions.glsl"
#include "common/luminance.glsl"
#include "bake/moment_texel.glsl"
#include "common/prefilter_lod.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(FORMAT, binding = 1) readonly uniform imageCube uEnvironment;

layout(std430, binding = 0) writeonly buffer MomentTexels {
    vec4 momentTexels[];
};

uniform int uGroupFaceSize;
uniform int uFineFaceSize; // of the level bound as uEnvironment

void main()
{
    ivec3 group = ivec3(gl_GlobalInvocationID);
    if (group.x >= uGroupFaceSize || group.y >= uGroupFaceSize)
        return;
    ivec2 first = group.xy * uFineFaceSize / uGroupFaceSize;
    ivec2 end = (group.xy + 1) * uFineFaceSize / uGroupFaceSize;
    vec3 flux = vec3(0.0);
    vec3 momentR = vec3(0.0);
    vec3 momentG = vec3(0.0);
    vec3 momentB = vec3(0.0);
    float fluxY = 0.0;
    vec3 momentY = vec3(0.0);
    vec3 secondDiagonal = vec3(0.0); // xx, yy, zz
    vec3 secondOff = vec3(0.0);      // xy, xz, yz
    for (int y = first.y; y < end.y; ++y)
        for (int x = first.x; x < end.x; ++x) {
            vec3 w = cubeFaceUvToDirection(group.z, (vec2(x, y) + 0.5) / float(uFineFaceSize));
            float omega = cubeTexelSolidAngle(w, float(uFineFaceSize));
            vec3 radiance = imageLoad(uEnvironment, ivec3(x, y, group.z)).rgb * omega;
            flux += radiance;
            momentR += radiance.r * w;
            momentG += radiance.g * w;
            momentB += radiance.b * w;
            // Rec. 709 luminance; a group of any colour still gets a spread from its texels'
            // solid angle where it is black (the 1e-6 floor).
            float y709 = rec709Luminance(radiance) + 1e-6 * omega;
            fluxY += y709;
            momentY += y709 * w;
            secondDiagonal += y709 * w * w;
            secondOff += y709 * vec3(w.x * w.y, w.x * w.z, w.y * w.z);
        }
    // A black channel contributes nothing; its moment only has to be finite.
    vec3 safe = max(flux, vec3(1e-30));
    fluxY = max(fluxY, 1e-30);
    vec3 sDiagonal = secondDiagonal / fluxY;
    vec3 sOff = secondOff / fluxY;
    int base = ((group.z * uGroupFaceSize + group.y) * uGroupFaceSize + group.x) * kMomentTexelVec4s;
    momentTexels[base] = vec4(flux, 0.0);                               // flux
    momentTexels[base + 1] = vec4(momentR / safe.r, sDiagonal.x);       // momentRAndSxx
    momentTexels[base + 2] = vec4(momentG / safe.g, sDiagonal.y);       // momentGAndSyy
    momentTexels[base + 3] = vec4(momentB / safe.b, sDiagonal.z);       // momentBAndSzz
    momentTexels[base + 4] = vec4(momentY / fluxY, sOff.x);             // momentYAndSxy
    momentTexels[base + 5] = vec4(sOff.y, sOff.z, 0.0, 0.0);            // secondMomentXzYz
}
