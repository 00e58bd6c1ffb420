// How roughness is laid out over the mips of the prefiltered specular cube, and how a
// sample's density picks the mip of the source cube it reads. ONE definition, compiled both
// as GLSL (bake shaders now, material shading later) and as C++
// (renderer/bake/prefilter_lod.hpp), so the bake and whoever samples its output cannot
// disagree. Same dialect rules as conventions.glsl: common subset, f suffixes, IBL_FN.

// Roughness per mip, one of two layouts (a bake records which; shading reads it back):
//  - PREFILTER_LAYOUT_LINEAR, LearnOpenGL's and the glTF sample viewer's:
//      lod / (levelCount - 1) = roughness;
//  - PREFILTER_LAYOUT_QUADRATIC, Filament's (cmgen and its shading):
//      lod / (levelCount - 1) = roughness (2 - roughness),
//    a fit of log2(roughness) that spends the mips where the lobe narrows fastest: with 6
//    levels, mips 1-3 hold roughness 0.11, 0.23, 0.37 where linear has 0.2, 0.4, 0.6. Blending
//    two adjacent mips approximates the lobe in between far better when they are that close,
//    and roughness 1 lands on a small face that many samples per texel make cheap.
// Either way mip 0 is the mirror (roughness 0) and the last mip roughness 1. A single-level
// chain holds roughness 0 only.
#define PREFILTER_LAYOUT_LINEAR 0
#define PREFILTER_LAYOUT_QUADRATIC 1

IBL_FN float prefilterRoughnessFromMip(float mip, float levelCount, int roughnessLayout)
{
    if (levelCount <= 1.0f) return 0.0f;
    float t = clamp(mip / (levelCount - 1.0f), 0.0f, 1.0f);
    return roughnessLayout == PREFILTER_LAYOUT_QUADRATIC ? 1.0f - sqrt(1.0f - t) : t;
}

// The inverse: the (fractional) lod a shader passes to textureLod for a roughness.
IBL_FN float prefilterMipFromRoughness(float roughness, float levelCount, int roughnessLayout)
{
    float r = clamp(roughness, 0.0f, 1.0f);
    float t = roughnessLayout == PREFILTER_LAYOUT_QUADRATIC ? r * (2.0f - r) : r;
    return t * max(levelCount - 1.0f, 0.0f);
}

// Solid angle of the source cube's mip-0 texel that direction d (unit length) falls in. On a
// face, texel (2/f)^2 of the plane at distance 1 seen at (x, y) covers
// (2/f)^2 / (1 + x^2 + y^2)^(3/2) sr, and 1 + x^2 + y^2 = 1 / m^2 with m the largest |component|
// of d, so Omega_p = 4 m^3 / f^2: from 4 / f^2 at a face centre down to 0.19 x that in a
// corner (the face average, 4 pi / (6 f^2), lies between).
IBL_FN float cubeTexelSolidAngle(vec3 d, float faceSize)
{
    vec3 a = abs(d);
    float m = max(a.x, max(a.y, a.z));
    return 4.0f * m * m * m / (faceSize * faceSize);
}

// The face average, 4 pi / (6 f^2): what LearnOpenGL and Filament use for every texel.
IBL_FN float cubeAverageTexelSolidAngle(float faceSize)
{
    return 12.566370614359172f / (6.0f * faceSize * faceSize);
}

// The source lod whose texels are as large as a sample's share of the sphere: a mip texel
// covers 4^lod base texels, so lod = log4(Omega_s / Omega_p) = 0.5 log2(Omega_s / Omega_p),
// plus a bias. Negative means finer than mip 0; the caller clamps to the chain.
// Split in a sample's term and a texel's term, so that a pass whose samples come from a
// table (renderer/bake/source_samples.hpp) computes the first once per sample on the host
// and only the second per texel read.
IBL_FN float sourceLodSampleTerm(float sampleSolidAngle, float bias)
{
    return 0.5f * log2(sampleSolidAngle) + bias;
}

IBL_FN float sourceLodFromSampleTerm(float sampleTerm, float texelSolidAngle)
{
    return sampleTerm - 0.5f * log2(texelSolidAngle);
}

IBL_FN float sourceLodFromSolidAngle(float sampleSolidAngle, float texelSolidAngle, float bias)
{
    return sourceLodFromSampleTerm(sourceLodSampleTerm(sampleSolidAngle, bias), texelSolidAngle);
}

// PDF-based source-mip selection ("filtered importance sampling", Krivanek & Colbert 2008,
// GPU Gems 3 ch. 20): N samples drawn with density pdf (w.r.t. solid angle) each stand for
// Omega_s = 1 / (N pdf) steradians. This is LearnOpenGL's formula with the face-average
// texel, Omega_p = 4 pi / (6 f^2), bias 0; Filament's cmgen uses log4(K Omega_s / Omega_p)
// with K = 4, i.e. bias +1: one mip blurrier (less noise from sparse samples over bright
// texels, more blur).
IBL_FN float sourceLodFromPdf(float pdf, float sampleCount, float sourceFaceSize, float bias)
{
    return sourceLodFromSolidAngle(1.0f / (sampleCount * pdf), cubeAverageTexelSolidAngle(sourceFaceSize), bias);
}

// The same with Omega_p the solid angle of the texel the sample actually reads, in direction
// d (unit length). With the face average, the lod is off by -0.47 (face centres, where texels
// are 1.9x the average) to +0.72 mips (corners, 0.37x). The bake uses this one: at equal cost
// it has 5-15% less prefilter error than the face average (docs/bake.md).
IBL_FN float sourceLodFromPdfAt(vec3 d, float pdf, float sampleCount, float sourceFaceSize, float bias)
{
    return sourceLodFromSolidAngle(1.0f / (sampleCount * pdf), cubeTexelSolidAngle(d, sourceFaceSize), bias);
}
