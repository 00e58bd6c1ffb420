// The fitted lobe's residual (renderer/frame/shading_lights_texture.hpp): one rough mip of the
// bake's prefiltered cube less each shading light's exact prefilter, clamped at 0, as
// subtractShadingLights (renderer/ibl/shading_lights.cpp) computes it on the CPU for the
// accuracy study; tests/gl/shading_lights_gltest.cpp compares the two at every texel. The
// kernel is the bake's, uScale ggxPrefilterWeight (brdf.glsl) = D(h) max(0, n.l) / Z(alpha),
// with 1 - n.l taken as |n - l|^2 / 2, which keeps its digits where n.l is near 1 (a narrow
// lobe's peak, where the light's share is most of the texel and the residual is what is left
// of it).
#include "common/conventions.glsl"
#include "common/brdf.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(FORMAT, binding = 1) readonly uniform imageCube uSource; // the bake's mip
layout(binding = 0) writeonly uniform imageCube uTarget;         // the residual's mip

uniform int uSize;
uniform float uAlpha2;
uniform float uScale;   // alpha^2 / (pi Z(alpha))
uniform float uCosNear; // nearer than this to a group's centroid, its points; farther, the centroid
uniform int uGroups;

// Per group: (centroid, first point), (flux, point count); then the points: (direction, 0), (flux, 0).
layout(std430, binding = 0) readonly buffer ShadingLightData { vec4 uLights[]; };

float kernel(vec3 n, vec3 l)
{
    vec3 d = n - l;
    return ggxPrefilterWeight(dot(n, l), 0.5 * dot(d, d), uAlpha2);
}

void main()
{
    ivec3 texel = ivec3(gl_GlobalInvocationID.xy, int(gl_GlobalInvocationID.z));
    if (texel.x >= uSize || texel.y >= uSize)
        return;
    vec3 n = cubeFaceUvToDirection(texel.z, (vec2(texel.xy) + 0.5) / float(uSize));
    vec3 sum = vec3(0.0);
    for (int g = 0; g < uGroups; ++g) {
        vec4 groupLight = uLights[2 * g], groupFlux = uLights[2 * g + 1];
        float c = dot(n, groupLight.xyz);
        if (c > uCosNear) {
            int first = int(groupLight.w), points = int(groupFlux.w);
            for (int p = 0; p < points; ++p)
                sum += uLights[first + 2 * p + 1].rgb * kernel(n, uLights[first + 2 * p].xyz);
        } else if (c > 0.0) {
            sum += groupFlux.rgb * kernel(n, groupLight.xyz);
        }
    }
    vec3 residual = max(imageLoad(uSource, texel).rgb - uScale * sum, vec3(0.0));
    imageStore(uTarget, texel, vec4(residual, 1.0));
}
