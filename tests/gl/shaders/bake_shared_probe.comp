// Evaluates the shared GLSL of common/brdf.glsl, sampling.glsl, sh9.glsl and
// prefilter_lod.glsl for bake_shared_glsl_gltest, which compares with the C++ core.
// MODE 0: (n.v, n.l, n.h, alpha) -> (ggxD, schlickGgxVisibility, smithGgxCorrelatedVisibility,
//         geometryG(schlick))
// MODE 1: (cos, F0.r, F0.g, roughness) -> (fresnelSchlick(cos, F0).rg, fresnelSchlickRoughness(...).rg), F0.b = 0.5
// MODE 2: (i, n, alpha, -) -> (sampleGgxHalfVector(hammersley(i, n), alpha), radicalInverseVdC(i))
// MODE 3: (i, n, -, -) -> (sampleCosineHemisphere(hammersley(i, n)), pdfCosineHemisphere(z))
// MODE 4: (normal, -) -> tangentFrame(normal) * (0.3, -0.5, 0.81)
// MODE 5: (direction, -) -> sh9Evaluate(uCoefficients, direction)
// MODE 6: (direction, faceSize) -> (cubeTexelSolidAngle, sourceLodFromPdfAt(0.37, 64, faceSize, 0.5),
//         sourceLodFromPdf(0.37, 64, faceSize, 0.5), prefilterRoughnessFromMip(2, 5, quadratic) + prefilterMipFromRoughness(0.3, 5, linear)
//         + prefilterMipFromRoughness(0.3, 6, quadratic))
// MODE 7: (c, 1 - c, alpha^2, -) -> (ggxPrefilterWeight(c, 1 - c, alpha^2), -, -, -)
// MODE 8: (rgb, -) -> (rec709Luminance(rgb), kLuminanceWeights)
#include "probe_layout.glsl"
#include "common/brdf.glsl"
#include "common/sampling.glsl"
#include "common/sh9.glsl"
#include "common/prefilter_lod.glsl"
#include "common/luminance.glsl"

uniform vec3 uCoefficients[9];

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= uint(uCount))
        return;
    vec4 v = inputs[i];
#if MODE == 0
    outputs[i] = vec4(ggxD(v.z, v.w), schlickGgxVisibility(v.x, v.y, v.w), smithGgxCorrelatedVisibility(v.x, v.y, v.w),
                      geometryG(GEOMETRY_SCHLICK_GGX, v.x, v.y, v.w));
#elif MODE == 1
    vec3 F0 = vec3(v.y, v.z, 0.5);
    outputs[i] = vec4(fresnelSchlick(v.x, F0).rg, fresnelSchlickRoughness(v.x, F0, v.w).rg);
#elif MODE == 2
    outputs[i] = vec4(sampleGgxHalfVector(hammersley(uint(v.x), uint(v.y)), v.z), radicalInverseVdC(uint(v.x)));
#elif MODE == 3
    vec3 l = sampleCosineHemisphere(hammersley(uint(v.x), uint(v.y)));
    outputs[i] = vec4(l, pdfCosineHemisphere(l.z));
#elif MODE == 4
    outputs[i] = vec4(tangentFrame(v.xyz) * vec3(0.3, -0.5, 0.81), 0.0);
#elif MODE == 5
    outputs[i] = vec4(sh9Evaluate(uCoefficients, v.xyz), 0.0);
#elif MODE == 7
    outputs[i] = vec4(ggxPrefilterWeight(v.x, v.y, v.z), 0.0, 0.0, 0.0);
#elif MODE == 8
    outputs[i] = vec4(rec709Luminance(v.xyz), kLuminanceWeights);
#else
    vec3 d = normalize(v.xyz);
    outputs[i] = vec4(cubeTexelSolidAngle(d, v.w), sourceLodFromPdfAt(d, 0.37, 64.0, v.w, 0.5), sourceLodFromPdf(0.37, 64.0, v.w, 0.5),
                      prefilterRoughnessFromMip(2.0, 5.0, PREFILTER_LAYOUT_QUADRATIC) +
                          prefilterMipFromRoughness(0.3, 5.0, PREFILTER_LAYOUT_LINEAR) +
                          prefilterMipFromRoughness(0.3, 6.0, PREFILTER_LAYOUT_QUADRATIC));
#endif
}
