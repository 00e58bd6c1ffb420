// Diffuse irradiance by cosine-weighted importance sampling: with l drawn with density
// cos(theta) / pi, E = integral L cos dOmega is estimated by (1/N) sum L cos / pdf
// = (pi / N) sum L(l_i). With uMipFiltering each sample reads the source mip whose texels
// match its share of the sphere (prefilter_lod.glsl), which turns N point samples of a
// high-resolution map into N box-filtered ones: no fireflies from a small bright source.
#include "common/conventions.glsl"
#include "common/sampling.glsl"
#include "common/prefilter_lod.glsl"
#include "bake/cube_texel.glsl"

uniform samplerCube uEnvironment;
uniform int uSampleCount;
uniform int uMipFiltering;     // 0: always mip 0
uniform float uMipBias;        // added to the pdf-derived lod
uniform float uSourceFaceSize;
uniform int uExactTexelSolidAngle; // 1: the texel read (sourceLodFromPdfAt), 0: the face average // of the environment's mip 0
uniform float uMaxSourceLod;

void main()
{
    ivec2 texel;
    if (!outputTexel(texel))
        return;
    mat3 frame = tangentFrame(outputTexelDirection(texel));
    vec3 sum = vec3(0.0);
    for (int i = 0; i < uSampleCount; ++i) {
        vec3 local = sampleCosineHemisphere(hammersley(uint(i), uint(uSampleCount)));
        vec3 l = frame * local;
        float lod = 0.0;
        if (uMipFiltering != 0) {
            float pdf = pdfCosineHemisphere(local.z);
            lod = uExactTexelSolidAngle != 0 ? sourceLodFromPdfAt(l, pdf, float(uSampleCount), uSourceFaceSize, uMipBias)
                                             : sourceLodFromPdf(pdf, float(uSampleCount), uSourceFaceSize, uMipBias);
            lod = clamp(lod, 0.0, uMaxSourceLod);
        }
        sum += textureLod(uEnvironment, l, lod).rgb;
    }
    storeOutput(texel, sum * (IBL_PI / float(uSampleCount)));
}
