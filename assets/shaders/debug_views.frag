// Debug views of the baked data, drawn over the whole frame. The layout (which tile shows
// what) is computed on the CPU (renderer/debug_layout.cpp) and passed as tile rectangles,
// so that the UI can label tiles and read texels under the cursor from the same numbers.
//   VIEW 1: prefiltered mips, each as a cube cross (4 x 3 faces: -X +Z +X -Z across the middle
//           row, +Y above +Z, -Y below), tile t = mip t
//   VIEW 2: BRDF LUTs, tile 0 = Schlick-GGX, tile 1 = height-correlated Smith;
//           x = n.v, y = roughness (up), shown as (R, G) = (A, B), the familiar red-green
//           picture (A + B, the third channel, is in the readout)
#include "common/environment_lookup.glsl"

in vec2 vUv;
out vec4 fragColor;

uniform samplerCube uPrefiltered;
uniform sampler2D uLutSchlick;
uniform sampler2D uLutCorrelated;
uniform int uTileCount;
uniform vec4 uTiles[16]; // (x0, y0, x1, y1) in pixels, y up

// Face index (GL order) of each cross cell (column, row from the bottom), -1 = empty.
int crossFace(int column, int row)
{
    if (row == 1) return column == 0 ? 1 : column == 1 ? 4 : column == 2 ? 0 : 5;
    if (column != 1) return -1;
    return row == 2 ? 2 : row == 0 ? 3 : -1;
}

void main()
{
    vec2 pixel = gl_FragCoord.xy;
    fragColor = vec4(0.02, 0.02, 0.025, 1.0);
    for (int t = 0; t < uTileCount; ++t) {
        vec4 tile = uTiles[t];
        if (pixel.x < tile.x || pixel.y < tile.y || pixel.x >= tile.z || pixel.y >= tile.w) continue;
        vec2 local = (pixel - tile.xy) / (tile.zw - tile.xy); // 0..1, y up
#if VIEW == 1
        vec2 cell = local * vec2(4.0, 3.0);
        int face = crossFace(int(cell.x), int(cell.y));
        if (face < 0) return;
        // Cross cells show faces as seen from inside the cube: face-local t = 0 is the top row.
        vec2 st = vec2(fract(cell.x), 1.0 - fract(cell.y));
        vec3 radiance = textureLod(uPrefiltered, cubeFaceUvToDirection(face, st), float(t)).rgb * uEnvironmentIntensity;
        fragColor = vec4(radiance, 1.0);
#else
        vec2 lut = t == 0 ? texture(uLutSchlick, local).rg : texture(uLutCorrelated, local).rg;
        fragColor = vec4(lut, 0.0, 1.0);
#endif
        return;
    }
}
