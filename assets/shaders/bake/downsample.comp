// One mip level from the level above it: the 2x2 box average glGenerateMipmap computes, as a
// compute pass. On llvmpipe glGenerateMipmap blits through a fragment shader that is
// JIT-compiled on first use in every process (100-200 ms per format, not disk-cached),
// while this program is compiled once and cached. The z dimension of the dispatch is the
// cube face (CUBE 1) or 0 (a 2D texture). FORMAT: the image format qualifier (rgba16f,
// rgba32f), needed to read an image. Odd sizes drop the last row or column, as GL may.
layout(local_size_x = 8, local_size_y = 8) in;

#if CUBE
layout(FORMAT, binding = 1) readonly uniform imageCube uSource;
layout(binding = 0) writeonly uniform imageCube uTarget;
#define COORD(xy) ivec3(xy, int(gl_GlobalInvocationID.z))
#else
layout(FORMAT, binding = 1) readonly uniform image2D uSource;
layout(binding = 0) writeonly uniform image2D uTarget;
#define COORD(xy) (xy)
#endif

uniform ivec2 uTargetSize;
uniform ivec2 uSourceSize;

void main()
{
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (texel.x >= uTargetSize.x || texel.y >= uTargetSize.y)
        return;
    ivec2 a = 2 * texel;
    ivec2 b = min(a + 1, uSourceSize - 1);
    vec4 sum = imageLoad(uSource, COORD(a)) + imageLoad(uSource, COORD(ivec2(b.x, a.y))) +
               imageLoad(uSource, COORD(ivec2(a.x, b.y))) + imageLoad(uSource, COORD(b));
    imageStore(uTarget, COORD(texel), 0.25 * sum);
}
