// Radiance SH9 projection of an equirect: L_lm = sum over texels of L Y_lm(texel centre)
// dOmega(row), renderer/ibl/sh.cpp's projectEquirect term for term. Each work group sums
// ROWS_PER_GROUP rows (64 lanes, one reduction through shared memory) and writes its nine
// partial sums; the host adds the groups in double. The rows' solid angles come from the
// host, computed exactly in double (a difference of cosines, which float would round badly
// near the poles) and only then rounded to float.
// One group per row would cost a barrier-synchronised reduction per row, which on llvmpipe
// (barriers are coroutine switches) took twice as long as the arithmetic.
#include "common/conventions.glsl"
#include "common/sh9.glsl"

layout(local_size_x = 64) in;

uniform sampler2D uEquirect; // read with texelFetch: no filtering, no mips
uniform int uRowsPerGroup;

layout(std430, binding = 0) writeonly buffer GroupSums { vec4 groupSums[]; }; // [group * 9 + i]
layout(std430, binding = 1) readonly buffer RowSolidAngles { float rowSolidAngle[]; };

shared vec3 partial[64][9];

void main()
{
    int lane = int(gl_LocalInvocationID.x);
    int group = int(gl_WorkGroupID.x);
    ivec2 size = textureSize(uEquirect, 0);
    vec3 sum[9];
    for (int i = 0; i < 9; ++i)
        sum[i] = vec3(0.0);
    int firstRow = group * uRowsPerGroup;
    int endRow = min(firstRow + uRowsPerGroup, size.y);
    for (int row = firstRow; row < endRow; ++row) {
        float v = (float(row) + 0.5) / float(size.y);
        vec3 rowSum[9];
        for (int i = 0; i < 9; ++i)
            rowSum[i] = vec3(0.0);
        for (int x = lane; x < size.x; x += 64) {
            vec3 L = texelFetch(uEquirect, ivec2(x, row), 0).rgb;
            float Y[9];
            sh9Basis(equirectUvToDirection(vec2((float(x) + 0.5) / float(size.x), v)), Y);
            for (int i = 0; i < 9; ++i)
                rowSum[i] += L * Y[i];
        }
        for (int i = 0; i < 9; ++i)
            sum[i] += rowSum[i] * rowSolidAngle[row];
    }
    for (int i = 0; i < 9; ++i)
        partial[lane][i] = sum[i];
    barrier();
    // Tree reduction: partial sums of similar size, log2(64) additions deep.
    for (int stride = 32; stride > 0; stride >>= 1) {
        if (lane < stride)
            for (int i = 0; i < 9; ++i)
                partial[lane][i] += partial[lane + stride][i];
        barrier();
    }
    if (lane == 0)
        for (int i = 0; i < 9; ++i)
            groupSums[group * 9 + i] = vec4(partial[0][i], 0.0);
}
