// The background: one view ray per pixel from the inverse camera, showing the environment,
// its irradiance, one prefiltered mip, or a solid colour (BackgroundMode).
#include "common/ibl_lighting.glsl"

in vec2 vUv;
out vec4 fragColor;

// BACKGROUND: 0 environment, 1 irradiance, 2 prefiltered mip, 3 solid (BackgroundMode), a
// compile-time constant for the reason ibl_lighting.glsl gives. SKY_FROM_CUBE (with 0): the
// bake's environment cube, the radiance the lighting integrates, so that the background and
// the lighting always come from the same bake (an environment switch shows both at once,
// a mirror sphere reflects exactly the sky behind it); 0 before a bake exists: the map.
uniform mat4 uInverseViewProjection; // rotation-only view: the sky is at infinity
uniform float uBackgroundMip;
uniform vec3 uSolidColour;

void main()
{
    vec4 clip = vec4(vUv * 2.0 - 1.0, 1.0, 1.0);
    vec4 world = uInverseViewProjection * clip;
    vec3 direction = normalize(world.xyz / world.w);
#if BACKGROUND == 0 && SKY_FROM_CUBE
    vec3 colour = texture(uEnvironmentCube, toEnvironment(direction)).rgb * uEnvironmentIntensity;
#elif BACKGROUND == 0
    vec3 colour = environmentRadiance(direction);
#elif BACKGROUND == 1
    // Irradiance shown as the radiance of a white Lambertian surface facing that way (E / pi),
    // so it sits at the brightness of the sky it comes from.
    vec3 colour = diffuseIrradiance(direction) * (1.0 / IBL_PI);
#elif BACKGROUND == 2
    vec3 colour = textureLod(uPrefiltered, toEnvironment(direction), uBackgroundMip).rgb * uEnvironmentIntensity;
#else
    vec3 colour = uSolidColour;
#endif
    fragColor = vec4(colour, 0.0); // coverage 0: the frame's alpha counts surface samples only
}
