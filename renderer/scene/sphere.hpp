#pragma once
// Procedural scenes: the UV sphere every material study uses, the classic metallic x
// roughness grid, and a row of spheres for side-by-side comparisons.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/mesh.hpp"

namespace iblab {

// A UV sphere centred at the origin, following mesh.hpp's conventions:
//   theta = pi v (0 at +Y, the north pole), phi = 2 pi u,
//   p = radius (sin theta sin phi, cos theta, sin theta cos phi),
// so u = 0.5 faces -Z, u = 0 / 1 is the seam facing +Z, and u grows to the right seen
// from +Z. Normals are p / radius, tangents the analytic d p / d phi direction
// (cos phi, 0, -sin phi) with w = +1.
// The seam column is duplicated (u = 0 and u = 1) with bit-identical positions, so there
// is no crack. Each pole has one vertex per segment, at that segment's mid-longitude
// u = (i + 0.5) / segments: the cap triangles then have a proper uv footprint and their
// tangents stay well defined (no NaN from a zero-length d p / d u at the poles).
// Requires 3 <= segments <= 4096, 2 <= rings <= 4096 and a finite radius > 0; throws
// iblab::Error("uvSphere", ...) otherwise.
MeshData makeUvSphere(float radius = 1.0f, int segments = 64, int rings = 32);

struct GridSphere {
    glm::mat4 transform{1.0f}; // places a unit-radius-ish sphere; translation only
    float metallic = 0.0f;
    float roughness = 0.0f;    // perceptual roughness (alpha = roughness^2); 0 is kept
                               // exact here, shading may clamp it
    int row = 0;
    int column = 0;
};

// A text anchor in world space (z = 0 plane, text reads along +X, facing +Z).
struct GridLabel {
    std::string text;
    glm::vec3 position{0.0f};
    bool axisTitle = false; // "metallic 0..1" / "roughness 0..1" rather than a tick value
};

struct SphereGrid {
    int rows = 0;
    int columns = 0;
    float spacing = 0.0f;
    std::vector<GridSphere> spheres; // row-major: index = row * columns + column
    std::vector<GridLabel> labels;   // the two axis titles first, then row ticks, then column ticks
};

// rows x columns spheres in the z = 0 plane, centred on the origin, `spacing` apart.
// Metallic varies with the row: row 0 is the BOTTOM row, metallic = row / (rows - 1),
// increasing upwards; roughness varies with the column: column 0 is the LEFT column,
// roughness = column / (columns - 1), increasing to the right (a single row or column
// gets 0). Labels: "metallic 0..1" left of the grid and "roughness 0..1" below it, at
// 1.5 spacings from the outermost sphere centres; tick values ("0.00", "0.17", ...) at
// 0.75 spacings, level with their row or column. Requires rows, columns >= 1 and
// 1 <= rows * columns <= 65536, spacing > 0; throws iblab::Error("sphereGrid", ...).
SphereGrid sphereGrid(int rows = 7, int columns = 7, float spacing = 2.5f);

// Transforms for k spheres in a row along +X, centred on the origin, `spacing` apart
// (e.g. the same material at increasing sample counts). Requires 1 <= k <= 65536 and
// spacing > 0; throws iblab::Error("countingStrip", ...).
std::vector<glm::mat4> countingStrip(int k, float spacing = 2.5f);

// One text anchor per text, below the spheres of countingStrip(texts.size(), spacing) in
// order (left to right), as far below their centres as the grid's column ticks are below
// its bottom row. Throws like countingStrip for an empty list.
std::vector<GridLabel> stripLabels(const std::vector<std::string>& texts, float spacing = 2.5f);

// A value as the grid's ticks print it: two decimals ("0.17").
std::string tickText(float value);

} // namespace iblab
