// Display transform: exposure, then a tone-mapping operator, then the sRGB OETF. ONE
// definition, compiled both as GLSL (through the shader library) and as C++
// (renderer/ibl/tonemap.hpp includes this file with glm in scope). Same rules as
// conventions.glsl: the common subset of GLSL 4.50 and C++/glm (no swizzles, no out
// parameters, no arrays, float literals with an f suffix, functions marked IBL_FN).
//
// Every operator takes scene-linear, already exposed, non-negative Rec.709 RGB and returns
// display-linear RGB in [0, 1]; toneMap() clamps negative input to 0 first (SH ringing can
// produce small negative radiance).
//
// Operator ids (mirrored by iblab::ToneMapOperator; keep the values stable, they travel
// through uniforms and command lines):
const int IBL_TONEMAP_NONE = 0;           // clamp to [0, 1]
const int IBL_TONEMAP_REINHARD = 1;       // x / (1 + x), per channel
const int IBL_TONEMAP_ACES_NARKOWICZ = 2; // Narkowicz 2015 curve fit to the ACES RRT+ODT
const int IBL_TONEMAP_ACES_HILL = 3;      // Stephen Hill's fit, with the AP1 round trip
const int IBL_TONEMAP_HABLE = 4;          // Uncharted 2 filmic (John Hable 2010)
const int IBL_TONEMAP_PBR_NEUTRAL = 5;    // Khronos PBR Neutral (2024)
const int IBL_TONEMAP_AGX = 6;            // AgX (Sobotka), as Filament and three.js ship it
const int IBL_TONEMAP_COUNT = 7;

IBL_FN vec3 toneMapNone(vec3 x)
{
    return clamp(x, 0.0f, 1.0f);
}

IBL_FN vec3 toneMapReinhard(vec3 x)
{
    return x / (1.0f + x);
}

// Krzysztof Narkowicz, "ACES Filmic Tone Mapping Curve" (2015): a rational fit of the ACES
// reference rendering + sRGB output transform's luminance curve, applied per channel.
IBL_FN vec3 toneMapAcesNarkowicz(vec3 x)
{
    const float a = 2.51f;
    const float b = 0.03f;
    const float c = 2.43f;
    const float d = 0.59f;
    const float e = 0.14f;
    return clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0f, 1.0f);
}

// Stephen Hill's ACES fit (BakingLab, ACES.hlsl): sRGB -> AP1 with the RRT saturation folded in,
// a rational fit of RRT + ODT per channel, then back to sRGB with the ODT saturation.
// Hill lists the matrices by rows for HLSL's mul(M, v). GLSL's mat3(...) and glm's mat3(...)
// both take COLUMNS, so the listings below are Hill's rows read down the columns; M * v then
// computes the same product in both languages.
IBL_FN mat3 acesHillInputMatrix()
{
    return mat3(0.59719f, 0.07600f, 0.02840f,  // column 0 = Hill's first entries of each row
                0.35458f, 0.90834f, 0.13383f,  // column 1
                0.04823f, 0.01566f, 0.83777f); // column 2
}

IBL_FN mat3 acesHillOutputMatrix()
{
    return mat3(1.60475f, -0.10208f, -0.00327f,
                -0.53108f, 1.10813f, -0.07276f,
                -0.07367f, -0.00605f, 1.07602f);
}

IBL_FN vec3 acesHillRrtOdtFit(vec3 v)
{
    vec3 a = v * (v + 0.0245786f) - 0.000090537f;
    vec3 b = v * (0.983729f * v + 0.4329510f) + 0.238081f;
    return a / b;
}

IBL_FN vec3 toneMapAcesHill(vec3 x)
{
    vec3 v = acesHillInputMatrix() * x;
    v = acesHillRrtOdtFit(v);
    v = acesHillOutputMatrix() * v;
    return clamp(v, 0.0f, 1.0f);
}

// John Hable's Uncharted 2 filmic curve ("Filmic Tonemapping Operators", 2010), with his
// published constants: shoulder strength A, linear strength B, linear angle C, toe strength
// D, toe numerator E, toe denominator F; linear white point W = 11.2; exposure bias 2.0.
IBL_FN vec3 hableCurve(vec3 x)
{
    const float A = 0.15f;
    const float B = 0.50f;
    const float C = 0.10f;
    const float D = 0.20f;
    const float E = 0.02f;
    const float F = 0.30f;
    return ((x * (A * x + C * B) + D * E) / (x * (A * x + B) + D * F)) - E / F;
}

IBL_FN vec3 toneMapHable(vec3 x)
{
    const float exposureBias = 2.0f;
    const float W = 11.2f;
    vec3 whiteScale = 1.0f / hableCurve(vec3(W));
    return clamp(hableCurve(exposureBias * x) * whiteScale, 0.0f, 1.0f);
}

// Khronos PBR Neutral (KhronosGroup/ToneMapping, PBR_Neutral/pbrNeutral.glsl and its spec):
// a toe that removes a 0.04 offset (F90 of common dielectrics) from dark colours, identity
// below startCompression = 0.8 - 0.04 (on the offset colour), and above it a hue-preserving
// highlight compression with desaturation towards white at the compressed peak.
IBL_FN vec3 toneMapPbrNeutral(vec3 color)
{
    const float startCompression = 0.8f - 0.04f;
    const float desaturation = 0.15f;

    float x = min(color.x, min(color.y, color.z));
    float offset = x < 0.08f ? x - 6.25f * x * x : 0.04f;
    color -= offset;

    float peak = max(color.x, max(color.y, color.z));
    if (peak < startCompression) return color;

    const float d = 1.0f - startCompression;
    float newPeak = 1.0f - d * d / (peak + d - startCompression);
    color *= newPeak / peak;

    float g = 1.0f - 1.0f / (desaturation * (peak - newPeak) + 1.0f);
    return mix(color, newPeak * vec3(1.0f), g);
}

// AgX (Troy Sobotka; Blender 4's default view transform), in the variant Filament ships
// (ToneMapper.cpp, AgxToneMapper with AgxLook::NONE) and three.js ported (r162+,
// tonemapping_pars_fragment AgXToneMapping), which Godot 4.4 follows closely:
//   linear sRGB -> linear Rec.2020 -> Filament's inset matrix -> log2 encoding over
//   [-12.47393, 4.026069] EV (mid grey 0.18 at 10 stops below the top) -> Blender's default
//   contrast sigmoid as Benjamin Wrensch's 6th-order polynomial fit (iolite, "Minimal AgX",
//   mean squared error 3.7e-6) -> outset matrix -> 2.2 power -> linear Rec.2020 -> sRGB.
// The matrices are listed as COLUMNS (GLSL's and glm's mat3 order). The published forms are
// Rec.2020 -> sRGB by rows (ITU-R BT.2407) and the outset matrix's inverse; the inverses
// below were computed from them in double precision (tests/cpu/tonemap_test.cpp checks
// that each pair multiplies to the identity).
IBL_FN mat3 agxSrgbToRec2020()
{
    return mat3(0.62740944046172165f, 0.069124839044179098f, 0.016423358026501966f,
                0.32926025219386862f, 0.91954861378641906f, 0.088047847623886816f,
                0.043271893589722402f, 0.01132076676217352f, 0.89561671368517703f);
}

IBL_FN mat3 agxRec2020ToSrgb()
{
    return mat3(1.6605f, -0.1246f, -0.0182f,
                -0.5876f, 1.1329f, -0.1006f,
                -0.0728f, -0.0083f, 1.1187f);
}

IBL_FN mat3 agxInsetMatrix()
{
    return mat3(0.856627153315983f, 0.137318972929847f, 0.11189821299995f,
                0.0951212405381588f, 0.761241990602591f, 0.0767994186031903f,
                0.0482516061458583f, 0.101439036467562f, 0.811302368396859f);
}

IBL_FN mat3 agxOutsetMatrix()
{
    return mat3(1.1271005818144368f, -0.14132976349843829f, -0.14132976349843826f,
                -0.11060664309660322f, 1.1578237022162718f, -0.11060664309660294f,
                -0.016493938717834569f, -0.016493938717834257f, 1.2519364065950402f);
}

// Wrensch's fit of the default contrast sigmoid on [0, 1] (log-encoded in, display-encoded out).
IBL_FN vec3 agxContrastApprox(vec3 x)
{
    vec3 x2 = x * x;
    vec3 x4 = x2 * x2;
    return 15.5f * x4 * x2 - 40.14f * x4 * x + 31.96f * x4 - 6.868f * x2 * x + 0.4298f * x2 + 0.1191f * x - 0.00232f;
}

IBL_FN vec3 toneMapAgx(vec3 color)
{
    const float minEv = -12.47393f;
    const float maxEv = 4.026069f;
    vec3 v = max(agxSrgbToRec2020() * color, vec3(0.0f));
    v = agxInsetMatrix() * v;
    v = clamp((log2(max(v, vec3(1e-10f))) - minEv) / (maxEv - minEv), 0.0f, 1.0f);
    v = agxContrastApprox(v);
    v = agxOutsetMatrix() * v;
    v = pow(max(v, vec3(0.0f)), vec3(2.2f));
    return clamp(agxRec2020ToSrgb() * v, 0.0f, 1.0f);
}

// Display-linear RGB in [0, 1] from exposed scene-linear RGB. Unknown ids fall back to none.
IBL_FN vec3 toneMap(vec3 hdr, int op)
{
    vec3 x = max(hdr, vec3(0.0f));
    if (op == IBL_TONEMAP_REINHARD) return toneMapReinhard(x);
    if (op == IBL_TONEMAP_ACES_NARKOWICZ) return toneMapAcesNarkowicz(x);
    if (op == IBL_TONEMAP_ACES_HILL) return toneMapAcesHill(x);
    if (op == IBL_TONEMAP_HABLE) return toneMapHable(x);
    if (op == IBL_TONEMAP_PBR_NEUTRAL) return toneMapPbrNeutral(x);
    if (op == IBL_TONEMAP_AGX) return toneMapAgx(x);
    return toneMapNone(x);
}

// Photographic exposure: +1 EV doubles the light.
IBL_FN vec3 applyExposure(vec3 hdr, float exposureEv)
{
    return hdr * exp2(exposureEv);
}

// The sRGB OETF (IEC 61966-2-1): linear below 0.0031308, a 1/2.4 power with offset above.
// The two pieces meet at 0.0031308 -> 0.04045 (continuous to ~1e-7).
IBL_FN float srgbOetf(float x)
{
    return x <= 0.0031308f ? 12.92f * x : 1.055f * pow(x, 1.0f / 2.4f) - 0.055f;
}

IBL_FN vec3 srgbEncode(vec3 c)
{
    return vec3(srgbOetf(c.x), srgbOetf(c.y), srgbOetf(c.z));
}

// The whole display transform: sRGB-encoded values in [0, 1] ready for an 8-bit target or a
// non-sRGB framebuffer (do not also enable GL_FRAMEBUFFER_SRGB).
IBL_FN vec3 displayEncode(vec3 hdr, float exposureEv, int op)
{
    return srgbEncode(toneMap(applyExposure(hdr, exposureEv), op));
}
