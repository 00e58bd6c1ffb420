// HDR frame -> exposure -> tone curve -> sRGB, the last pass of every frame.
#include "common/tonemap.glsl"

in vec2 vUv;
out vec4 fragColor;

uniform sampler2D uHdrFrame;
uniform float uExposureEv;
uniform int uToneMapOperator;

void main()
{
    vec3 hdr = texelFetch(uHdrFrame, ivec2(gl_FragCoord.xy), 0).rgb;
    fragColor = vec4(displayEncode(hdr, uExposureEv, uToneMapOperator), 1.0);
}
