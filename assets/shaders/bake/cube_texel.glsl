// The invocation -> output texel mapping shared by every pass that writes a cube map. One
// dispatch covers rows [uRowOffset, uRowOffset + uRowCount) of faces uFirstFace + z for the
// dispatch's z range, of one mip (the host binds that mip as a layered image; layer = face in
// GL order +X, -X, +Y, -Y, +Z, -Z). Work is split by rows so that a bake step in the GUI can
// stay a few milliseconds long, and merged across faces where a face is less than a step:
// one dispatch per face and mip would leave all but one of llvmpipe's threads idle on the
// small mips (an 8x8 face is a single work group) and pay a glFinish per face.
// Texel (x, row) of a face has face-local (s, t) = ((x + 0.5) / size, (row + 0.5) / size):
// row 0 is the first row GL stores for the face, which is t = 0 in conventions.glsl.
#include "common/conventions.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

uniform int uFirstFace;
uniform int uFaceSize;   // of the mip being written
uniform int uColumnOffset; // 0 but where a dispatch is one tile (the prefilter's per-tile exact sums)
uniform int uRowOffset;
uniform int uRowCount;
uniform float uStoreMax; // largest finite value of the output format (65504 for half floats)

// No format qualifier: write-only images may omit it, and the host binds RGBA16F or RGBA32F.
layout(binding = 0) writeonly uniform imageCube uOutput;

int outputFace() { return uFirstFace + int(gl_GlobalInvocationID.z); }

bool outputTexel(out ivec2 texel)
{
    texel = ivec2(int(gl_GlobalInvocationID.x) + uColumnOffset, int(gl_GlobalInvocationID.y) + uRowOffset);
    return texel.x < uFaceSize && int(gl_GlobalInvocationID.y) < uRowCount && texel.y < uFaceSize;
}

vec2 outputTexelFaceUv(ivec2 texel)
{
    return (vec2(texel) + 0.5) / float(uFaceSize);
}

vec3 outputTexelDirection(ivec2 texel)
{
    return cubeFaceUvToDirection(outputFace(), outputTexelFaceUv(texel));
}

// Clamped to the format's range: a half-float store of a brighter value would be +Inf,
// which every later filter would spread.
void storeOutput(ivec2 texel, vec3 value)
{
    imageStore(uOutput, ivec3(texel, outputFace()), vec4(min(value, vec3(uStoreMax)), 1.0));
}
