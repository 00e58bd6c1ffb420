// Equirect -> one cube face (rows of it), each cube texel the average of the equirect over
// the texel's footprint. A single bilinear tap per texel would alias wherever the equirect
// is denser than the cube: towards the poles an equirect row shrinks to a point while a cube
// texel stays the same size, so a texel there covers many equirect columns. The footprint
// (the texel's two edge vectors mapped to equirect uv) is filtered the way anisotropic
// hardware does it, explicitly so that it does not depend on the driver: up to kMaxTaps
// trilinear taps along the longer axis, at the mip that matches the shorter one.
#include "common/conventions.glsl"
#include "bake/cube_texel.glsl"

uniform sampler2D uEquirect; // mip-mapped, REPEAT in s, CLAMP_TO_EDGE in t

const float kMaxTaps = 4.0;

// The change of equirect uv for a small change dd of the unit direction d, to first order
// (the differential of conventions.glsl's map): with rho^2 = x^2 + z^2,
//   du = (-z dx + x dz) / (2 pi rho^2)     from u = 0.5 + atan(x, -z) / (2 pi)
//   dv = -dy / (pi rho)                    from v = acos(y) / pi.
// Cheaper than mapping neighbouring directions through atan and acos, and free of the
// u = 0 / 1 wrap, which a difference of two uv would have to undo.
vec2 equirectUvDifferential(vec3 d, vec3 dd)
{
    float rho2 = max(d.x * d.x + d.z * d.z, 1e-12);
    return vec2((d.x * dd.z - d.z * dd.x) / (2.0 * IBL_PI * rho2), -dd.y / (IBL_PI * sqrt(rho2)));
}

vec3 sampleFootprint(vec2 uv, vec2 axisA, vec2 axisB)
{
    vec2 size = vec2(textureSize(uEquirect, 0));
    vec2 a = axisA * size; // in mip-0 texels
    vec2 b = axisB * size;
    vec2 major = dot(a, a) >= dot(b, b) ? axisA : axisB;
    float lengthMajor = max(length(a), length(b));
    // The footprint is the parallelogram (a, b); its extent across the major axis is its area
    // over the major length. min(|a|, |b|) would not do: near a pole both edges of a cube
    // texel run mostly along u, and the parallelogram is thin although both edges are long.
    float lengthMinor = max(abs(a.x * b.y - a.y * b.x) / max(lengthMajor, 1e-6), 1e-6);
    float taps = min(ceil(lengthMajor / lengthMinor), kMaxTaps);
    // The mip matches the shorter axis. Where the footprint is more elongated than kMaxTaps
    // (within ~15 degrees of a pole, where the elongation is 1 / cos(latitude) and only an
    // artefact of the parameterisation) the taps are spread further apart rather than
    // blurred across: they are still a fraction of a cube texel apart on the sphere,
    // whereas a coarser mip would average whole rows around the pole into the texel.
    float lod = log2(max(lengthMinor, 1.0));
    vec3 sum = vec3(0.0);
    for (float k = 0.0; k < taps; k += 1.0)
        sum += textureLod(uEquirect, uv + major * ((k + 0.5) / taps - 0.5), lod).rgb;
    return sum / taps;
}

void main()
{
    ivec2 texel;
    if (!outputTexel(texel))
        return;
    vec2 st = outputTexelFaceUv(texel);
    float halfTexel = 0.5 / float(uFaceSize);
    int face = outputFace();
    vec3 d = cubeFaceUvToDirection(face, st);
    // The texel's edges as direction changes (central differences across the texel).
    vec3 ds = cubeFaceUvToDirection(face, st + vec2(halfTexel, 0.0)) - cubeFaceUvToDirection(face, st - vec2(halfTexel, 0.0));
    vec3 dt = cubeFaceUvToDirection(face, st + vec2(0.0, halfTexel)) - cubeFaceUvToDirection(face, st - vec2(0.0, halfTexel));
    storeOutput(texel, sampleFootprint(directionToEquirectUv(d), equirectUvDifferential(d, ds), equirectUvDifferential(d, dt)));
}
