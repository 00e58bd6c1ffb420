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
const int IBL_TONEMAP_COUNT = 6;

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

// Display-linear RGB in [0, 1] from exposed scene-linear RGB. Unknown ids fall back to none.
IBL_FN vec3 toneMap(vec3 hdr, int op)
{
    vec3 x = max(hdr, vec3(0.0f));
    if (op == IBL_TONEMAP_REINHARD) return toneMapReinhard(x);
    if (op == IBL_TONEMAP_ACES_NARKOWICZ) return toneMapAcesNarkowicz(x);
    if (op == IBL_TONEMAP_ACES_HILL) return toneMapAcesHill(x);
    if (op == IBL_TONEMAP_HABLE) return toneMapHable(x);
    if (op == IBL_TONEMAP_PBR_NEUTRAL) return toneMapPbrNeutral(x);
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
