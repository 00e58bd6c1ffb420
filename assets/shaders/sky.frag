// The environment as the background: one view ray per pixel from the inverse camera.
#include "common/environment_lookup.glsl"

in vec2 vUv;
out vec4 fragColor;

uniform mat4 uInverseViewProjection; // rotation-only view: the sky is at infinity

void main()
{
    vec4 clip = vec4(vUv * 2.0 - 1.0, 1.0, 1.0);
    vec4 world = uInverseViewProjection * clip;
    vec3 direction = normalize(world.xyz / world.w);
    fragColor = vec4(environmentRadiance(direction), 1.0);
}
