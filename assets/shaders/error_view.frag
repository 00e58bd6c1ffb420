// ViewMode::Error: each surface pixel's relative error against the reference in false
// colour, on the linear HDR radiance or on the display values after exposure and tone
// mapping. The pixels the error does not measure (isMeasuredPixel: the background, which
// the reference shares with the frame, and MSAA edge pixels that are part sky) are shown
// as a dim grey version of the frame, so the heatmap keeps its context.
#include "common/tonemap.glsl"
#include "common/error_metrics.glsl"
#include "common/luminance.glsl"

out vec4 fragColor;

uniform sampler2D uHdrFrame;       // the frame being judged, coverage in alpha
uniform sampler2D uReferenceFrame; // the reference, same size
uniform sampler2D uGNormal;        // coverage in alpha
uniform float uExposureEv; // TONEMAP_OPERATOR: a compile-time constant, as in tonemap.frag
uniform bool uDisplaySpace;
uniform float uErrorScale; // relative error at the top of the colour bar

void main()
{
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 frame = texelFetch(uHdrFrame, pixel, 0);
    vec3 value = frame.rgb;
    if (!isMeasuredPixel(frame.a, texelFetch(uGNormal, pixel, 0).a)) {
        vec3 shown = displayEncode(value, uExposureEv, TONEMAP_OPERATOR);
        fragColor = vec4(vec3(0.3 * rec709Luminance(shown)), 1.0);
        return;
    }
    vec3 reference = texelFetch(uReferenceFrame, pixel, 0).rgb;
    if (uDisplaySpace) {
        value = displayEncode(value, uExposureEv, TONEMAP_OPERATOR);
        reference = displayEncode(reference, uExposureEv, TONEMAP_OPERATOR);
    }
    fragColor = vec4(falseColour(relativeError(value, reference) / uErrorScale), 1.0);
}
