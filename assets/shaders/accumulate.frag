// Progressive refinement: the new frame's radiance, blended into the running mean with
// constant alpha 1 / (n + 1) (set by the renderer), so frame n of the accumulation holds
// the average of n + 1 independent sample sets. Alpha, the frame's coverage, is the same
// in every frame of one mean; the renderer's blend copies it.
out vec4 fragColor;
uniform sampler2D uHdrFrame;

void main() { fragColor = texelFetch(uHdrFrame, ivec2(gl_FragCoord.xy), 0); }
