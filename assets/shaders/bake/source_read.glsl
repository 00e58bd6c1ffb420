// The environment cube as the bake passes that integrate over it read it, with PDF-based
// source-mip selection (prefilter_lod.glsl): a sample that stands for Omega_s steradians
// reads the mip whose texels are that large. The sample's term of the lod (from Omega_s and
// the bias) is the caller's; the texel's term, from the solid angle of the source texel the
// sample falls in or the face average, is computed here per read.
#include "common/conventions.glsl"
#include "common/prefilter_lod.glsl"

uniform samplerCube uEnvironment;
uniform int uMipFiltering;         // 0: always mip 0
uniform float uSourceFaceSize;     // of the environment's mip 0
uniform int uExactTexelSolidAngle; // 1: the texel read (cubeTexelSolidAngle), 0: the face average
uniform float uMaxSourceLod;

// Radiance arriving from world direction l (unit length).
vec3 readSource(float lodSampleTerm, vec3 l)
{
    float lod = 0.0;
    if (uMipFiltering != 0) {
        float texelSolidAngle = uExactTexelSolidAngle != 0 ? cubeTexelSolidAngle(l, uSourceFaceSize)
                                                           : cubeAverageTexelSolidAngle(uSourceFaceSize);
        lod = clamp(sourceLodFromSampleTerm(lodSampleTerm, texelSolidAngle), 0.0, uMaxSourceLod);
    }
    return textureLod(uEnvironment, l, lod).rgb;
}
