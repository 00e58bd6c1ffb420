// Where, and how wide, the specular IBL reads the prefiltered cube. ONE definition, compiled
// both as GLSL and as C++ (renderer/ibl/specular_approximations.hpp), so that the CPU study
// that measured these formulas (docs/accuracy-study.md) and a shader that uses them cannot
// disagree. Same dialect rules as conventions.glsl: common subset, no swizzles, no out
// parameters, f suffixes, IBL_FN.
//
// The split sum reads prefiltered(R, roughness), a lobe prefiltered with N = V = R. The
// true reflected lobe at n.v < 1 is not that lobe: it leans towards N (the off-specular
// peak), is cut by the surface's horizon, and is narrower across the plane of N and V than
// along it. Every function here keeps "prefiltered radiance times (F0 A + B)" and changes
// only the direction and roughness the cube is read at (and, for two taps, mixes two reads
// with weights that sum to 1), so none of them changes the white furnace.

// Frostbite's dominant direction (Lagarde & de Rousiers 2014, "Moving Frostbite to PBR",
// listing 22, getSpecularDominantDir): lerp(N, R, s (sqrt(s) + a)), s = 1 - a. Frostbite's
// `roughness` there is alpha = perceptualRoughness^2 (its "linearRoughness" is the
// perceptual one; Unity HDRP, by the same author, feeds it perceptualRoughness^2 too).
IBL_FN float frostbiteDominantLerp(float alpha)
{
    float s = clamp(1.0f - alpha, 0.0f, 1.0f);
    return s * (sqrt(s) + alpha);
}

// Filament's getReflectedVector / getSpecularDominantDirection: mix(R, N, a^2) with
// a = pixel.roughness = perceptualRoughness^2, i.e. t = perceptualRoughness^4 towards N.
IBL_FN float filamentDominantTowardsNormal(float alpha)
{
    return alpha * alpha;
}

// The split sum's lookup direction as a setting (SamplingSettings::specularDirection; the
// values are frame/settings.hpp's SpecularDirection): R itself, or one of the two dominant
// directions above, as the fraction of the way from R towards N that lobeTapDirection takes.
#define SPECULAR_DIRECTION_REFLECTION 0
#define SPECULAR_DIRECTION_FROSTBITE 1
#define SPECULAR_DIRECTION_FILAMENT 2

IBL_FN float specularDirectionTowardsNormal(int specularDirection, float alpha)
{
    // Frostbite lerps from N to R by frostbiteDominantLerp: 1 minus that from R to N.
    if (specularDirection == SPECULAR_DIRECTION_FROSTBITE) return 1.0f - frostbiteDominantLerp(alpha);
    if (specularDirection == SPECULAR_DIRECTION_FILAMENT) return filamentDominantTowardsNormal(alpha);
    return 0.0f;
}

// A read of the prefiltered cube between R (t = 0) and N (t = 1), unit length. t < 0 leans
// past R, away from N. A cube lookup does not need the normalisation; the CPU does.
IBL_FN vec3 lobeTapDirection(vec3 N, vec3 R, float towardsNormal)
{
    return normalize(mix(R, N, towardsNormal));
}

// The fitted lobe's table texel (specular_approximations.hpp, LobeFitTable) decoded, by
// layout (`fitLayout`: `layout` is a GLSL keyword):
//  1, one tap:       p = (t, r_eff, -, -);
//  2, two taps:      p = (t_0, t_1, r_eff, w_1), w_0 = 1 - w_1, radiance sum_k w_k read_k;
//  3, Fresnel split: p = (t_A, r_A, t_B, r_B): tap 0 is the read that multiplies F0 A, tap 1
//     the one that multiplies B (the LUT's two terms get lobes of their own); weights 1.
//  4, Fresnel split with a two-read A: p as layout 3, and a second texel (the table's second
//     plane) q = (t_A2, r_A2, w_A2, -): the F0 A radiance is (1 - w_A2) read_0 + w_A2 read_2,
//     read_2 at lobeTapDirection(N, R, t_A2) and roughness r_A2. Two reads of different
//     width mixed with weights that sum to 1 shape the lobe's profile (a sharper peak with
//     wider tails, or the reverse) and, apart, stretch it along the plane of N and V,
//     which one isotropic read cannot; still none changes the white furnace.
// Taps 0 and 1 below; tap 2 of layout 4 is q's (lobeSecondATowardsNormal and its kin).
IBL_FN float lobeTapTowardsNormal(vec4 p, int fitLayout, int k)
{
    if (fitLayout == 1) return p.x;
    if (fitLayout >= 3) return k == 0 ? p.x : p.z;
    return k == 0 ? p.x : p.y;
}

IBL_FN float lobeTapRoughness(vec4 p, int fitLayout, int k)
{
    if (fitLayout == 1) return p.y;
    if (fitLayout >= 3) return k == 0 ? p.y : p.w;
    return p.z;
}

IBL_FN float lobeTapWeight(vec4 p, int fitLayout, int k)
{
    if (fitLayout != 2) return 1.0f;
    return k == 0 ? 1.0f - p.w : p.w;
}

// Layout 4's second A read, from the second plane's texel q.
IBL_FN float lobeSecondATowardsNormal(vec4 q) { return q.x; }
IBL_FN float lobeSecondARoughness(vec4 q) { return q.y; }
IBL_FN float lobeSecondAWeight(vec4 q) { return clamp(q.z, 0.0f, 1.0f); }

// How many planes (texels per cell) a layout's table has.
IBL_FN int lobeFitPlanes(int fitLayout) { return fitLayout == 4 ? 2 : 1; }

// Where plane `plane` of a table of `planes` planes stacked along y (each `rows` rows of
// roughness, texel centres at (i + 0.5) / rows) is read for `roughness`: clamped to its own
// edge texels, so that bilinear filtering never mixes two planes. With one plane this is
// the plain clamp to edge.
IBL_FN float lobeFitPlaneY(float roughness, int plane, int planes, float rows)
{
    return (float(plane) * rows + clamp(roughness * rows, 0.5f, rows - 0.5f)) / (float(planes) * rows);
}

// The recommended method (docs/accuracy-study.md) is layout 3 (or its refinement, 4), the Fresnel split: with p the
// table texel at (n.v, roughness) (bilinear, clamp to edge; x = n.v, y = perceptual
// roughness, texel centres (i + 0.5) / 16),
//   specular = F0 A read(lobeTapDirection(N, R, p.x), p.y) + B read(lobeTapDirection(N, R, p.z), p.w)
// times the energy compensation, where read(d, r) = textureLod(prefiltered, d,
// prefilterMipFromRoughness(r, levels, layout)) and A, B are the split-sum LUT's.
