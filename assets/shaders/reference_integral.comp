// The reference renderer's integral: for every surface pixel of one screen tile, the sum
// over a band of rows of the reference environment of
//   specular: L(w) D(h) Vis(n.v, n.w) F(v.h) (n.w) dOmega   (rgb; alpha: the same with
//             L = F = 1, the single-scattering albedo E_ss that energy compensation needs)
//   irradiance: L(w) (n.w) dOmega
// with h = normalize(v + w), every texel seen in its centre direction with its exact solid
// angle: renderer/ibl/reference.cpp's referenceSpecular and referenceIrradiance, texel for
// texel. No split sum and no N = V = R. N and V arrive in the environment's frame.
//
// Each invocation owns one pixel and adds rows to its running sums in row order, whatever
// the tile and band sizes: the slicing changes when work happens, not the float result.
#include "common/brdf.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D uGNormal;   // N, coverage
uniform sampler2D uGView;     // V, perceptual roughness
uniform sampler2D uGSpecular; // F0, metallic
uniform sampler2D uReferenceEnvironment; // read with texelFetch: one constant radiance per texel
uniform ivec2 uTileOrigin;
uniform ivec2 uTileEnd; // exclusive: the groups of 8 x 8 overhang tiles of other sizes, and the frame's edge
uniform int uFirstRow;
uniform int uEndRow;
uniform int uGeometry; // GEOMETRY_* of brdf.glsl

layout(std430, binding = 1) readonly buffer RowSolidAngles { float rowSolidAngle[]; };
layout(rgba32f, binding = 0) uniform image2D uSpecularImage; // the sums as images: uSpecularSum names their sampler elsewhere
layout(rgba32f, binding = 1) uniform image2D uIrradianceImage;

void main()
{
    ivec2 pixel = uTileOrigin + ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= uTileEnd.x || pixel.y >= uTileEnd.y) return;
    vec4 normal = texelFetch(uGNormal, pixel, 0);
    if (normal.w == 0.0) return; // background: the environment itself, drawn by the resolve
    vec4 view = texelFetch(uGView, pixel, 0);
    vec3 F0 = texelFetch(uGSpecular, pixel, 0).rgb;
    vec3 N = normalize(normal.xyz);
    vec3 V = normalize(view.xyz);
    // As shadeSplitSum and shadeSampled: n.v clamped rather than the pixel dropped at the
    // silhouette, and alpha kept off 0, where D is a Dirac delta no texel sum can hold.
    float NdotV = max(dot(N, V), 1e-4);
    float alpha = max(view.w * view.w, 1e-3);

    ivec2 size = textureSize(uReferenceEnvironment, 0);
    vec4 specular = imageLoad(uSpecularImage, pixel);
    vec4 irradiance = imageLoad(uIrradianceImage, pixel);
    for (int row = uFirstRow; row < uEndRow; ++row) {
        float v = (float(row) + 0.5) / float(size.y);
        vec4 rowSpecular = vec4(0.0);
        vec3 rowIrradiance = vec3(0.0);
        for (int x = 0; x < size.x; ++x) {
            vec3 w = equirectUvToDirection(vec2((float(x) + 0.5) / float(size.x), v));
            float NdotL = dot(N, w);
            if (NdotL <= 0.0) continue;
            vec3 L = texelFetch(uReferenceEnvironment, ivec2(x, row), 0).rgb;
            vec3 H = normalize(V + w);
            float NdotH = max(dot(N, H), 0.0);
            float VdotH = max(dot(V, H), 0.0);
            float brdfCos = ggxD(NdotH, alpha) * geometryVisibility(uGeometry, NdotV, NdotL, alpha) * NdotL;
            rowSpecular += vec4(L * fresnelSchlick(VdotH, F0) * brdfCos, brdfCos);
            rowIrradiance += L * NdotL;
        }
        specular += rowSpecular * rowSolidAngle[row];
        irradiance.rgb += rowIrradiance * rowSolidAngle[row];
    }
    imageStore(uSpecularImage, pixel, specular);
    imageStore(uIrradianceImage, pixel, irradiance);
}
