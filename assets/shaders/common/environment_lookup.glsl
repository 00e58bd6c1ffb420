// The environment as seen from the world: the user's yaw and intensity, applied in one
// place for every lookup (sky, irradiance, prefiltered and sampled radiance).
#include "common/conventions.glsl"

uniform sampler2D uEquirect;         // the source map, linear RGB with mips
uniform float uEnvironmentYaw;       // radians, see rotateAboutY
uniform float uEnvironmentIntensity; // linear scale, 2^EV

// World direction -> the direction in the environment's own frame.
vec3 toEnvironment(vec3 worldDirection) { return rotateAboutY(worldDirection, -uEnvironmentYaw); }

// Equirect lookup with derivatives that do not explode across the u = 0/1 seam: of the
// two continuous parameterisations u and fract(u + 0.5) - 0.5, take the one whose screen
// derivative is smaller (Tarini 2012). Without this, pixels on the seam pick the
// coarsest mip and draw a visible line.
vec3 sampleEquirectSeamless(sampler2D map, vec3 direction)
{
    vec2 uv = directionToEquirectUv(direction);
    float uAlt = fract(uv.x + 0.5) - 0.5;
    vec2 dx = vec2(dFdx(uv.x), dFdx(uv.y));
    vec2 dy = vec2(dFdy(uv.x), dFdy(uv.y));
    float dxAlt = dFdx(uAlt);
    float dyAlt = dFdy(uAlt);
    if (abs(dxAlt) + abs(dyAlt) < abs(dx.x) + abs(dy.x)) {
        dx.x = dxAlt;
        dy.x = dyAlt;
    }
    return textureGrad(map, uv, dx, dy).rgb;
}

vec3 environmentRadiance(vec3 worldDirection)
{
    return sampleEquirectSeamless(uEquirect, toEnvironment(worldDirection)) * uEnvironmentIntensity;
}
