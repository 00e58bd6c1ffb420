// One mip of the GGX-prefiltered specular cube (split-sum part 1, Karis 2013; LearnOpenGL's
// prefilter with the same N = V = R assumption): the cos-weighted average of the
// environment over the GGX lobe around n,
//   sum L(l_i) (n.l_i) / sum (n.l_i),  h_i ~ D(h)(n.h),  l_i = reflect(-n, h_i),
// which converges to renderer/ibl/reference.hpp's referencePrefilteredRadiance.
// With uMipFiltering each sample reads the source mip that matches its share of the lobe
// (the density of l is D(h)(n.h) / (4 v.h) = D / 4 with v = n), see prefilter_lod.glsl.
// Roughness 0 is a delta lobe: with uMirrorCopy the mirror level is the environment itself,
// read at uCopyLod (the source mip with this level's texel size, so it is a box-filtered
// copy, not a point sample that aliases when the source is larger). Without, the loop runs
// as LearnOpenGL's does: alpha = 0 puts every half vector on n, and every sample reads n
// (at mip 0: the roughness-0 pdf is a delta, there is no footprint to filter).
#include "common/conventions.glsl"
#include "common/brdf.glsl"
#include "common/sampling.glsl"
#include "common/prefilter_lod.glsl"
#include "bake/cube_texel.glsl"

uniform samplerCube uEnvironment;
uniform float uRoughness;      // perceptual; alpha = roughness^2
uniform int uSampleCount;
uniform int uMipFiltering;
uniform float uMipBias;
uniform float uSourceFaceSize;
uniform int uExactTexelSolidAngle; // 1: the texel read (sourceLodFromPdfAt), 0: the face average
uniform float uMaxSourceLod;
uniform float uCopyLod;
uniform int uMirrorCopy;

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
    float alpha = uRoughness * uRoughness;
    mat3 frame = tangentFrame(n);
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (int i = 0; i < uSampleCount; ++i) {
        vec3 hLocal = sampleGgxHalfVector(hammersley(uint(i), uint(uSampleCount)), alpha);
        // In the local frame n = v = (0, 0, 1): v.h = n.h = h.z and n.l = 2 (n.h)^2 - 1.
        float NdotH = hLocal.z;
        float NdotL = 2.0 * NdotH * NdotH - 1.0;
        if (NdotL <= 0.0)
            continue;
        vec3 l = frame * (2.0 * NdotH * hLocal - vec3(0.0, 0.0, 1.0));
        float lod = 0.0;
        if (uMipFiltering != 0 && alpha > 0.0) {
            float pdf = pdfGgxReflected(pdfGgxHalfVector(NdotH, alpha), NdotH);
            lod = uExactTexelSolidAngle != 0 ? sourceLodFromPdfAt(l, pdf, float(uSampleCount), uSourceFaceSize, uMipBias)
                                             : sourceLodFromPdf(pdf, float(uSampleCount), uSourceFaceSize, uMipBias);
            lod = clamp(lod, 0.0, uMaxSourceLod);
        }
        sum += textureLod(uEnvironment, l, lod).rgb * NdotL;
        weight += NdotL;
    }
    storeOutput(texel, weight > 0.0 ? sum / weight : textureLod(uEnvironment, n, 0.0).rgb);
}
