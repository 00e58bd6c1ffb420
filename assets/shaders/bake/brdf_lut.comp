// The split-sum BRDF integration LUT (split-sum part 2), renderer/ibl/brdf_lut.hpp on the
// GPU: texel (x, y) holds, for n.v = (x + 0.5) / size and perceptual roughness
// (y + 0.5) / size (row 0 = roughness near 0),
//   R = A = mean of (1 - Fc) w,  G = B = mean of Fc w,  B = A + B (E_ss, for energy
//   compensation),  w = Vis * 4 (n.l)(v.h) / (n.h),  Fc = (1 - v.h)^5,
// over N GGX half vectors from a Hammersley set; samples below the horizon count as 0 but
// stay in N (they are part of the estimator's sample space).
#include "common/brdf.glsl"
#include "common/sampling.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

uniform int uSize;
uniform int uSampleCount;
uniform int uGeometry; // GEOMETRY_SCHLICK_GGX or GEOMETRY_HEIGHT_CORRELATED_SMITH
uniform int uRowOffset;
uniform int uRowCount;

layout(binding = 0) writeonly uniform image2D uLut;

void main()
{
    ivec2 texel = ivec2(gl_GlobalInvocationID.x, int(gl_GlobalInvocationID.y) + uRowOffset);
    if (texel.x >= uSize || int(gl_GlobalInvocationID.y) >= uRowCount || texel.y >= uSize)
        return;
    float NdotV = (float(texel.x) + 0.5) / float(uSize);
    float roughness = (float(texel.y) + 0.5) / float(uSize);
    float alpha = roughness * roughness;
    // Isotropic lobe: only the angle between v and n matters, so v lies in the xz plane.
    vec3 v = vec3(sqrt(1.0 - NdotV * NdotV), 0.0, NdotV);
    float A = 0.0;
    float B = 0.0;
    for (int i = 0; i < uSampleCount; ++i) {
        vec3 h = sampleGgxHalfVector(hammersley(uint(i), uint(uSampleCount)), alpha);
        float VdotH = dot(v, h);
        float NdotL = 2.0 * VdotH * h.z - v.z;
        if (NdotL <= 0.0 || VdotH <= 0.0)
            continue;
        float w = geometryVisibility(uGeometry, NdotV, NdotL, alpha) * 4.0 * NdotL * VdotH / h.z;
        float Fc = schlickWeight(VdotH);
        A += (1.0 - Fc) * w;
        B += Fc * w;
    }
    A /= float(uSampleCount);
    B /= float(uSampleCount);
    imageStore(uLut, texel, vec4(A, B, A + B, 1.0));
}
