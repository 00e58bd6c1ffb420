// inputs[i] = (r, g, b, exposure EV); the operator is OPERATOR.
#include "probe_layout.glsl"
#include "common/tonemap.glsl"

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= uint(uCount)) return;
    outputs[i] = vec4(displayEncode(inputs[i].xyz, inputs[i].w, OPERATOR), 1.0);
}
