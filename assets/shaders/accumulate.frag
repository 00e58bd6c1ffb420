// Progressive refinement: the new frame's radiance, blended into the running mean with
// constant alpha 1 / (n + 1) (set by the renderer), so frame n of the accumulation holds
// the average of n + 1 independent sample sets.
out vec4 fragColor;
uniform sampler2D uHdrFrame;

void main() { fragColor = vec4(texelFetch(uHdrFrame, ivec2(gl_FragCoord.xy), 0).rgb, 1.0); }
