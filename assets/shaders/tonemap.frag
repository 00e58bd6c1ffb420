// HDR frame -> exposure -> tone curve -> sRGB, the last pass of every frame.
#include "common/tonemap.glsl"

in vec2 vUv;
out vec4 fragColor;

uniform sampler2D uHdrFrame;
uniform float uExposureEv;
// TONEMAP_OPERATOR (IBL_TONEMAP_*) is a compile-time constant, so that only its curve is
// compiled: llvmpipe evaluates every branch of a switch on a uniform.

void main()
{
    vec3 hdr = texelFetch(uHdrFrame, ivec2(gl_FragCoord.xy), 0).rgb;
    fragColor = vec4(displayEncode(hdr, uExposureEv, TONEMAP_OPERATOR), 1.0);
}
