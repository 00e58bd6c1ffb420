#include "scene/sphere.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "io/error.hpp"

namespace iblab {
namespace {

// Offsets that centre `count` items `spacing` apart on 0.
float centredOffset(int index, int count, float spacing) { return (float(index) - 0.5f * float(count - 1)) * spacing; }

float unitRamp(int index, int count) { return count > 1 ? float(index) / float(count - 1) : 0.0f; }

// Tick values sit this many spacings from the sphere centres they label: clear of a unit
// sphere at the default 2.5 spacing, and nearer to it than to the next row.
constexpr float kTickOffset = 0.75f;

void requireSpacing(const char* subject, float spacing)
{
    if (!(spacing > 0.0f) || !std::isfinite(spacing))
        throw Error(subject, "spacing must be finite and > 0, got " + std::to_string(spacing));
}

} // namespace

std::string tickText(float value)
{
    char text[16];
    std::snprintf(text, sizeof text, "%.2f", double(value));
    return text;
}

MeshData makeUvSphere(float radius, int segments, int rings)
{
    if (!(radius > 0.0f) || !std::isfinite(radius))
        throw Error("uvSphere", "radius must be finite and > 0, got " + std::to_string(radius));
    if (segments < 3 || segments > 4096 || rings < 2 || rings > 4096)
        throw Error("uvSphere", "needs 3..4096 segments and 2..4096 rings, got " + std::to_string(segments) + " x " +
                                    std::to_string(rings));

    MeshData mesh;
    const std::size_t vertexCount = 2 * std::size_t(segments) + std::size_t(rings - 1) * std::size_t(segments + 1);
    mesh.positions.reserve(vertexCount);
    mesh.normals.reserve(vertexCount);
    mesh.tangents.reserve(vertexCount);
    mesh.uvs.reserve(vertexCount);

    // Trigonometry in double, and exact values at the poles and the seam, so that the
    // seam's two columns and each pole's vertices coincide bit for bit.
    const auto addVertex = [&](double u, double v, int column, int ring) {
        const double theta = ring == 0 ? 0.0 : ring == rings ? std::numbers::pi : std::numbers::pi * v;
        const double phi = column == segments ? 0.0 : 2.0 * std::numbers::pi * u;
        const double sinTheta = ring == 0 || ring == rings ? 0.0 : std::sin(theta);
        const double cosTheta = ring == 0 ? 1.0 : ring == rings ? -1.0 : std::cos(theta);
        const glm::vec3 n(float(sinTheta * std::sin(phi)), float(cosTheta), float(sinTheta * std::cos(phi)));
        mesh.positions.push_back(radius * n);
        mesh.normals.push_back(n);
        mesh.tangents.emplace_back(float(std::cos(phi)), 0.0f, float(-std::sin(phi)), 1.0f);
        mesh.uvs.emplace_back(float(u), float(v));
    };

    for (int i = 0; i < segments; ++i) addVertex((i + 0.5) / segments, 0.0, i, 0);
    for (int j = 1; j < rings; ++j)
        for (int i = 0; i <= segments; ++i) addVertex(double(i) / segments, double(j) / rings, i, j);
    for (int i = 0; i < segments; ++i) addVertex((i + 0.5) / segments, 1.0, i, rings);

    const auto ringStart = [&](int j) { return std::uint32_t(segments + (j - 1) * (segments + 1)); };
    const std::uint32_t southStart = ringStart(rings);
    mesh.indices.reserve(std::size_t(segments) * std::size_t(rings - 1) * 6);
    // Quad (a b / c d) with a top-left, seen from outside: (a, c, d) and (a, d, b) wind
    // counter-clockwise. At the caps one of the two collapses and is left out.
    for (int i = 0; i < segments; ++i) {
        const std::uint32_t c = ringStart(1) + std::uint32_t(i);
        mesh.indices.insert(mesh.indices.end(), {std::uint32_t(i), c, c + 1});
    }
    for (int j = 1; j + 1 < rings; ++j)
        for (int i = 0; i < segments; ++i) {
            const std::uint32_t a = ringStart(j) + std::uint32_t(i), b = a + 1;
            const std::uint32_t c = ringStart(j + 1) + std::uint32_t(i), d = c + 1;
            mesh.indices.insert(mesh.indices.end(), {a, c, d, a, d, b});
        }
    for (int i = 0; i < segments; ++i) {
        const std::uint32_t a = ringStart(rings - 1) + std::uint32_t(i);
        mesh.indices.insert(mesh.indices.end(), {a, southStart + std::uint32_t(i), a + 1});
    }
    return mesh;
}

SphereGrid sphereGrid(int rows, int columns, float spacing)
{
    if (rows < 1 || columns < 1 || std::int64_t(rows) * columns > 65536)
        throw Error("sphereGrid", "needs 1..65536 spheres, got " + std::to_string(rows) + " x " + std::to_string(columns));
    requireSpacing("sphereGrid", spacing);

    SphereGrid grid;
    grid.rows = rows;
    grid.columns = columns;
    grid.spacing = spacing;
    grid.spheres.reserve(std::size_t(rows) * std::size_t(columns));
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < columns; ++c) {
            GridSphere s;
            s.row = r;
            s.column = c;
            s.metallic = unitRamp(r, rows);
            s.roughness = unitRamp(c, columns);
            s.transform = glm::translate(glm::mat4(1.0f), glm::vec3(centredOffset(c, columns, spacing),
                                                                    centredOffset(r, rows, spacing), 0.0f));
            grid.spheres.push_back(s);
        }

    const float left = centredOffset(0, columns, spacing);
    const float bottom = centredOffset(0, rows, spacing);
    grid.labels.push_back({"metallic 0..1", glm::vec3(left - 1.5f * spacing, 0.0f, 0.0f), true});
    grid.labels.push_back({"roughness 0..1", glm::vec3(0.0f, bottom - 1.5f * spacing, 0.0f), true});
    for (int r = 0; r < rows; ++r)
        grid.labels.push_back({tickText(unitRamp(r, rows)),
                               glm::vec3(left - kTickOffset * spacing, centredOffset(r, rows, spacing), 0.0f), false});
    for (int c = 0; c < columns; ++c)
        grid.labels.push_back({tickText(unitRamp(c, columns)),
                               glm::vec3(centredOffset(c, columns, spacing), bottom - kTickOffset * spacing, 0.0f), false});
    return grid;
}

std::vector<glm::mat4> countingStrip(int k, float spacing)
{
    if (k < 1 || k > 65536)
        throw Error("countingStrip", "needs 1..65536 spheres, got " + std::to_string(k));
    requireSpacing("countingStrip", spacing);
    std::vector<glm::mat4> transforms;
    transforms.reserve(std::size_t(k));
    for (int i = 0; i < k; ++i)
        transforms.push_back(glm::translate(glm::mat4(1.0f), glm::vec3(centredOffset(i, k, spacing), 0.0f, 0.0f)));
    return transforms;
}

std::vector<GridLabel> stripLabels(const std::vector<std::string>& texts, float spacing)
{
    const std::vector<glm::mat4> strip = countingStrip(int(texts.size()), spacing);
    std::vector<GridLabel> labels;
    labels.reserve(texts.size());
    for (std::size_t i = 0; i < texts.size(); ++i) labels.push_back({texts[i], glm::vec3(strip[i][3]) - glm::vec3(0.0f, kTickOffset * spacing, 0.0f), false});
    return labels;
}

} // namespace iblab
