// How roughness is laid out over the mips of the prefiltered specular cube, and how a
// sample's density picks the mip of the source cube it reads. ONE definition, compiled both
// as GLSL (bake shaders now, material shading later) and as C++
// (renderer/bake/prefilter_lod.hpp), so the bake and whoever samples its output cannot
// disagree. Same dialect rules as conventions.glsl: common subset, f suffixes, IBL_FN.

// Roughness per mip: linear in the mip index, as LearnOpenGL does,
//   perceptual roughness = mip / (levelCount - 1),
// so mip 0 is the mirror (roughness 0) and the last mip is roughness 1. Linear is not the
// most even use of the mips (the lobe narrows fastest near roughness 0, and Filament uses a
// quadratic map there), but it is the tutorial's, and keeping it lets its output be read by
// its shading. A single-level chain holds roughness 0 only.
IBL_FN float prefilterRoughnessFromMip(float mip, float levelCount)
{
    return levelCount > 1.0f ? mip / (levelCount - 1.0f) : 0.0f;
}

// The inverse: the (fractional) lod a shader passes to textureLod for a roughness.
IBL_FN float prefilterMipFromRoughness(float roughness, float levelCount)
{
    return roughness * max(levelCount - 1.0f, 0.0f);
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

// The source lod whose texels are as large as a sample's share of the sphere: a mip texel
// covers 4^lod base texels, so lod = log4(Omega_s / Omega_p) = 0.5 log2(Omega_s / Omega_p),
// plus a bias. Negative means finer than mip 0; the caller clamps to the chain.
IBL_FN float sourceLodFromSolidAngle(float sampleSolidAngle, float texelSolidAngle, float bias)
{
    return 0.5f * log2(sampleSolidAngle / texelSolidAngle) + bias;
}

// PDF-based source-mip selection ("filtered importance sampling", Krivanek & Colbert 2008,
// GPU Gems 3 ch. 20): N samples drawn with density pdf (w.r.t. solid angle) each stand for
// Omega_s = 1 / (N pdf) steradians. This is LearnOpenGL's formula with the face-average
// texel, Omega_p = 4 pi / (6 f^2), bias 0; Filament's cmgen uses log4(K Omega_s / Omega_p)
// with K = 4, i.e. bias +1: one mip blurrier (less noise from sparse samples over bright
// texels, more blur).
IBL_FN float sourceLodFromPdf(float pdf, float sampleCount, float sourceFaceSize, float bias)
{
    return sourceLodFromSolidAngle(1.0f / (sampleCount * pdf), 12.566370614359172f / (6.0f * sourceFaceSize * sourceFaceSize),
                                   bias);
}

// The same with Omega_p the solid angle of the texel the sample actually reads, in direction
// d (unit length). With the face average, the lod is off by -0.47 (face centres, where texels
// are 1.9x the average) to +0.72 mips (corners, 0.37x). The bake uses this one: at equal cost
// it has 5-15% less prefilter error than the face average (docs/bake.md).
IBL_FN float sourceLodFromPdfAt(vec3 d, float pdf, float sampleCount, float sourceFaceSize, float bias)
{
    return sourceLodFromSolidAngle(1.0f / (sampleCount * pdf), cubeTexelSolidAngle(d, sourceFaceSize), bias);
}
