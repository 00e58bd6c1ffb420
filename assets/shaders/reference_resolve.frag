// The reference frame from the integral's sums: the same combineLobes as the estimators
// of pbr.frag, fed exact irradiance and specular sums instead of baked approximations.
// Background pixels are discarded: the sky pass has already drawn the environment there.
#include "common/ibl_lighting.glsl"

out vec4 fragColor;

uniform sampler2D uGNormal;   // N, coverage
uniform sampler2D uGView;     // V, perceptual roughness
uniform sampler2D uGSpecular; // F0, metallic
uniform sampler2D uGBaseColor; // base colour, occlusion
uniform sampler2D uGEmissive;
uniform sampler2D uSpecularSum;   // specular radiance, E_ss
uniform sampler2D uIrradianceSum; // E

void main()
{
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 normal = texelFetch(uGNormal, pixel, 0);
    if (normal.w == 0.0) discard;
    vec4 view = texelFetch(uGView, pixel, 0);
    vec4 specularInputs = texelFetch(uGSpecular, pixel, 0);
    vec4 base = texelFetch(uGBaseColor, pixel, 0);
    SurfacePoint s;
    s.N = normalize(normal.xyz);
    s.V = normalize(view.xyz);
    s.roughness = view.w;
    s.F0 = specularInputs.rgb;
    s.metallic = specularInputs.a;
    s.baseColor = base.rgb;
    s.occlusion = base.a;
    vec4 specularSum = texelFetch(uSpecularSum, pixel, 0);
    vec3 specular = specularSum.rgb * energyCompensation(s.F0, specularSum.a) * uEnvironmentIntensity;
    vec3 irradianceOverPi = texelFetch(uIrradianceSum, pixel, 0).rgb * (uEnvironmentIntensity / IBL_PI);
    float NdotV = max(dot(s.N, s.V), 1e-4);
    fragColor = vec4(combineLobes(s, NdotV, irradianceOverPi, specular) + texelFetch(uGEmissive, pixel, 0).rgb, 1.0);
}
