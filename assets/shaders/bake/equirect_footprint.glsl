// The footprint of a cube texel on the equirect, as the environment cube pass filters it
// (equirect_to_cube.comp): the texel's two edge vectors mapped to equirect uv, read as
// anisotropic hardware reads it but explicitly, so that it does not depend on the driver.
// The bright-texel split's bases (clamp_near_lights.comp) read the same taps of the clamped
// map, so that a base is the environment pass's filter applied to the map clamped at its
// threshold: base plus lights is then the map, with nothing counted twice.
// Needs common/conventions.glsl.

const float kMaxFootprintTaps = 4.0;

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

struct EquirectFootprint {
    vec2 uv;     // the texel centre's
    vec2 major;  // the longer edge, in uv
    float taps;  // along it
    float lod;   // of the equirect's mips, matching the shorter edge
};

// Texel (face, st) of a faceSize cube on an equirect of equirectSize texels (level 0).
EquirectFootprint equirectFootprint(int face, vec2 st, int faceSize, vec2 equirectSize)
{
    float halfTexel = 0.5 / float(faceSize);
    vec3 d = cubeFaceUvToDirection(face, st);
    // The texel's edges as direction changes (central differences across the texel).
    vec3 ds = cubeFaceUvToDirection(face, st + vec2(halfTexel, 0.0)) - cubeFaceUvToDirection(face, st - vec2(halfTexel, 0.0));
    vec3 dt = cubeFaceUvToDirection(face, st + vec2(0.0, halfTexel)) - cubeFaceUvToDirection(face, st - vec2(0.0, halfTexel));
    vec2 axisA = equirectUvDifferential(d, ds);
    vec2 axisB = equirectUvDifferential(d, dt);
    vec2 a = axisA * equirectSize; // in mip-0 texels
    vec2 b = axisB * equirectSize;
    EquirectFootprint f;
    f.uv = directionToEquirectUv(d);
    f.major = dot(a, a) >= dot(b, b) ? axisA : axisB;
    float lengthMajor = max(length(a), length(b));
    // The footprint is the parallelogram (a, b); its extent across the major axis is its area
    // over the major length. min(|a|, |b|) would not do: near a pole both edges of a cube
    // texel run mostly along u, and the parallelogram is thin although both edges are long.
    float lengthMinor = max(abs(a.x * b.y - a.y * b.x) / max(lengthMajor, 1e-6), 1e-6);
    f.taps = min(ceil(lengthMajor / lengthMinor), kMaxFootprintTaps);
    // The mip matches the shorter axis. Where the footprint is more elongated than the taps
    // (within ~15 degrees of a pole, where the elongation is 1 / cos(latitude) and only an
    // artefact of the parameterisation) the taps are spread further apart rather than
    // blurred across: they are still a fraction of a cube texel apart on the sphere,
    // whereas a coarser mip would average whole rows around the pole into the texel.
    f.lod = log2(max(lengthMinor, 1.0));
    return f;
}

// Where tap k of the footprint reads, in uv.
vec2 equirectFootprintTap(EquirectFootprint f, float k)
{
    return f.uv + f.major * ((k + 0.5) / f.taps - 0.5);
}
