// glTF metallic-roughness material under image-based lighting. METHOD selects the
// estimator at compile time (0 split sum, 1 runtime importance sampling, 2 no estimate:
// the G-buffer the reference renderer integrates over); everything else is a uniform so
// that sliders never trigger a recompile.
#include "common/ibl_lighting.glsl"

in vec3 vWorldPosition;
in vec3 vNormal;
in vec4 vTangent;
in vec2 vUv0;
in vec2 vUv1;
#if METHOD == 2
// The surface in the environment's own frame (the reference sums over its texels) and
// every input of combineLobes; coverage 0 (the clear value) marks the background.
layout(location = 0) out vec4 gNormal;    // N, coverage 1
layout(location = 1) out vec4 gView;      // V, perceptual roughness
layout(location = 2) out vec4 gSpecular;  // F0, metallic
layout(location = 3) out vec4 gBaseColor; // base colour, occlusion
layout(location = 4) out vec4 gEmissive;
#else
out vec4 fragColor;
#endif

uniform vec3 uCameraPosition;

// Factors (glTF semantics) and optional textures; a texture unit of -1 means "absent".
uniform vec4 uBaseColorFactor;
uniform float uMetallicFactor;
uniform float uRoughnessFactor;
uniform vec3 uEmissiveFactor;
uniform float uOcclusionStrength;
uniform float uNormalScale;
uniform float uSpecular; // dielectric F0 = 0.16 specular^2 (Filament's reflectance)
uniform float uAmbientOcclusion; // the material panel's AO slider, on top of any texture
uniform sampler2D uBaseColorTexture;         // sRGB-decoded by the texture format
uniform sampler2D uMetallicRoughnessTexture; // G = roughness, B = metallic
uniform sampler2D uNormalTexture;
uniform sampler2D uOcclusionTexture;         // R
uniform sampler2D uEmissiveTexture;          // sRGB
uniform bool uHasBaseColorTexture;
uniform bool uHasMetallicRoughnessTexture;
uniform bool uHasNormalTexture;
uniform bool uHasOcclusionTexture;
uniform bool uHasEmissiveTexture;
uniform ivec4 uTexCoordSets;   // base colour, metallic-roughness, normal, occlusion: 0 or 1
uniform int uEmissiveTexCoordSet;

vec2 uvSet(int set) { return set == 0 ? vUv0 : vUv1; }

vec3 shadingNormal()
{
    vec3 n = normalize(vNormal);
    if (!gl_FrontFacing) n = -n; // double-sided materials see their back faces lit from behind
    if (!uHasNormalTexture) return n;
    vec3 t = normalize(vTangent.xyz - n * dot(n, vTangent.xyz)); // re-orthogonalised after interpolation
    vec3 b = cross(n, t) * vTangent.w;
    vec3 m = texture(uNormalTexture, uvSet(uTexCoordSets.z)).xyz * 2.0 - 1.0;
    m.xy *= uNormalScale;
    return normalize(mat3(t, b, n) * m);
}

SurfacePoint surfacePoint()
{
    SurfacePoint s;
    s.N = shadingNormal();
    s.V = normalize(uCameraPosition - vWorldPosition);
    vec4 baseColor = uBaseColorFactor;
    if (uHasBaseColorTexture) baseColor *= texture(uBaseColorTexture, uvSet(uTexCoordSets.x));
    s.baseColor = baseColor.rgb;
    s.metallic = uMetallicFactor;
    s.roughness = uRoughnessFactor;
    if (uHasMetallicRoughnessTexture) {
        vec4 mr = texture(uMetallicRoughnessTexture, uvSet(uTexCoordSets.y));
        s.roughness *= mr.g;
        s.metallic *= mr.b;
    }
    s.metallic = clamp(s.metallic, 0.0, 1.0);
    s.roughness = clamp(s.roughness, 0.0, 1.0);
    s.occlusion = uAmbientOcclusion;
    if (uHasOcclusionTexture) s.occlusion *= mix(1.0, texture(uOcclusionTexture, uvSet(uTexCoordSets.w)).r, uOcclusionStrength);
    s.F0 = mix(vec3(0.16 * uSpecular * uSpecular), s.baseColor, s.metallic);
    return s;
}

vec3 emission()
{
    vec3 emissive = uEmissiveFactor;
    if (uHasEmissiveTexture) emissive *= texture(uEmissiveTexture, uvSet(uEmissiveTexCoordSet)).rgb;
    return emissive;
}

void main()
{
    SurfacePoint s = surfacePoint();
#if METHOD == 0
    fragColor = vec4(shadeSplitSum(s) + emission(), 1.0);
#elif METHOD == 1
    fragColor = vec4(shadeSampled(s) + emission(), 1.0);
#else
    gNormal = vec4(toEnvironment(s.N), 1.0);
    gView = vec4(toEnvironment(s.V), s.roughness);
    gSpecular = vec4(s.F0, s.metallic);
    gBaseColor = vec4(s.baseColor, s.occlusion);
    gEmissive = vec4(emission(), 1.0);
#endif
}
