// MODE 0: direction (xyz) -> equirect uv; MODE 1: direction -> (face, s, t);
// MODE 2: (face, s, t) -> direction; MODE 3: (direction, yaw) -> rotated direction.
#include "probe_layout.glsl"
#include "common/conventions.glsl"

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= uint(uCount)) return;
    vec4 v = inputs[i];
#if MODE == 0
    outputs[i] = vec4(directionToEquirectUv(v.xyz), 0.0, 0.0);
#elif MODE == 1
    outputs[i] = vec4(directionToCubeFaceUv(v.xyz), 0.0);
#elif MODE == 2
    outputs[i] = vec4(cubeFaceUvToDirection(int(v.x), v.yz), 0.0);
#else
    outputs[i] = vec4(rotateAboutY(v.xyz, v.w), 0.0);
#endif
}
