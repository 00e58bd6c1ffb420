// glTF metallic-roughness material under image-based lighting. METHOD selects the
// estimator at compile time (0 split sum or the fitted lobe, 1 runtime importance sampling,
// 2 no estimate: the G-buffer the reference renderer integrates over), as do FITTED_LOBE
// and DIFFUSE_SOURCE (ibl_lighting.glsl): choices a user makes in a combo, each compiled
// once. Everything a slider moves is a uniform, so that dragging never recompiles.
#include "common/ibl_lighting.glsl"

// Inputs are interpolated at the pixel centre, where a single-sampled frame and the
// reference shade. With MSAA a triangle is shaded once for the samples it covers, and the
// centre may lie outside it: inside the mesh that is harmless (the neighbour's plane
// continues the same smooth attributes), so a pixel the mesh covers wholly resolves to
// nearly the single-sampled radiance (frame_gltest measures how nearly), even where several
// small triangles share it. Past a silhouette, though, the extrapolated normal faces away
// from the viewer and reflects a grazing, Fresnel-brightened environment: a bright fringe.
// There interpolants() takes the inputs at the centroid, inside the triangle. Centroid
// everywhere would move the shading of every pixel a triangle edge crosses (most pixels of
// a finely tessellated mesh) off its centre: on llvmpipe that changed pixels wholly inside
// a sphere lit by builtin:studio by up to 27% (0.5% this way).
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
out vec4 fragColor; // alpha 1: the frame's alpha is surface coverage (the sky writes 0)
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

struct Interpolants {
    vec3 position;
    vec3 normal; // facing the side being drawn: double-sided materials see their back faces lit from behind
    vec4 tangent;
    vec2 uv0;
    vec2 uv1;
};

// The centre's inputs, or the centroid's where the centre lies past a silhouette.
Interpolants interpolants()
{
    float facing = gl_FrontFacing ? 1.0 : -1.0;
    Interpolants i = Interpolants(vWorldPosition, facing * vNormal, vTangent, vUv0, vUv1);
    if (dot(i.normal, uCameraPosition - i.position) >= 0.0) return i;
    return Interpolants(interpolateAtCentroid(vWorldPosition), facing * interpolateAtCentroid(vNormal), interpolateAtCentroid(vTangent),
                        interpolateAtCentroid(vUv0), interpolateAtCentroid(vUv1));
}

vec2 uvSet(Interpolants i, int set) { return set == 0 ? i.uv0 : i.uv1; }

vec3 shadingNormal(Interpolants i)
{
    vec3 n = normalize(i.normal);
    if (!uHasNormalTexture) return n;
    vec3 t = normalize(i.tangent.xyz - n * dot(n, i.tangent.xyz)); // re-orthogonalised after interpolation
    vec3 b = cross(n, t) * i.tangent.w;
    vec3 m = texture(uNormalTexture, uvSet(i, uTexCoordSets.z)).xyz * 2.0 - 1.0;
    m.xy *= uNormalScale;
    return normalize(mat3(t, b, n) * m);
}

SurfacePoint surfacePoint(Interpolants i)
{
    SurfacePoint s;
    s.N = shadingNormal(i);
    s.V = normalize(uCameraPosition - i.position);
    vec4 baseColor = uBaseColorFactor;
    if (uHasBaseColorTexture) baseColor *= texture(uBaseColorTexture, uvSet(i, uTexCoordSets.x));
    s.baseColor = baseColor.rgb;
    s.metallic = uMetallicFactor;
    s.roughness = uRoughnessFactor;
    if (uHasMetallicRoughnessTexture) {
        vec4 mr = texture(uMetallicRoughnessTexture, uvSet(i, uTexCoordSets.y));
        s.roughness *= mr.g;
        s.metallic *= mr.b;
    }
    s.metallic = clamp(s.metallic, 0.0, 1.0);
    s.roughness = clamp(s.roughness, 0.0, 1.0);
    s.occlusion = uAmbientOcclusion;
    if (uHasOcclusionTexture) s.occlusion *= mix(1.0, texture(uOcclusionTexture, uvSet(i, uTexCoordSets.w)).r, uOcclusionStrength);
    s.F0 = mix(vec3(0.16 * uSpecular * uSpecular), s.baseColor, s.metallic);
    return s;
}

vec3 emission(Interpolants i)
{
    vec3 emissive = uEmissiveFactor;
    if (uHasEmissiveTexture) emissive *= texture(uEmissiveTexture, uvSet(i, uEmissiveTexCoordSet)).rgb;
    return emissive;
}

void main()
{
    Interpolants i = interpolants();
    SurfacePoint s = surfacePoint(i);
#if METHOD == 0
    fragColor = vec4(shadeSplitSum(s) + emission(i), 1.0);
#elif METHOD == 1
    fragColor = vec4(shadeSampled(s) + emission(i), 1.0);
#else
    gNormal = vec4(toEnvironment(s.N), 1.0);
    gView = vec4(toEnvironment(s.V), s.roughness);
    gSpecular = vec4(s.F0, s.metallic);
    gBaseColor = vec4(s.baseColor, s.occlusion);
    gEmissive = vec4(emission(i), 1.0);
#endif
}
