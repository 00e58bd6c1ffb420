// MeshData helpers: validation, bounds, smooth normals, tangent generation and node
// transforms. Expected values are worked out by hand on tiny meshes.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "io/error.hpp"
#include "scene/mesh.hpp"
#include "scene/sphere.hpp"

using namespace iblab;

namespace {

// A unit quad in the z = 0 plane facing +Z, counter-clockwise seen from +Z, with glTF
// uvs: (0,0) at the top-left corner (x = 0, y = 1), v growing downwards (-y).
MeshData quad()
{
    MeshData m;
    m.positions = {{0, 1, 0}, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
    m.uvs = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
    m.indices = {0, 1, 2, 0, 2, 3};
    m.normals.assign(4, glm::vec3(0, 0, 1));
    m.tangents.assign(4, glm::vec4(1, 0, 0, 1));
    return m;
}

std::string errorOf(const MeshData& m)
{
    try {
        m.validate("quad");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

glm::vec3 faceNormal(const MeshData& m, std::size_t t)
{
    const glm::vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]], c = m.positions[m.indices[3 * t + 2]];
    return glm::cross(b - a, c - a);
}

} // namespace

TEST(Mesh, ValidateAcceptsAWellFormedMesh) { EXPECT_EQ(errorOf(quad()), ""); }

TEST(Mesh, ValidateNamesTheBrokenPart)
{
    MeshData m = quad();
    m.normals.pop_back();
    EXPECT_EQ(errorOf(m), "quad: normals has 3 entries for 4 vertices");

    m = quad();
    m.uvs.clear(); // uvs may be absent altogether
    EXPECT_EQ(errorOf(m), "");
    m.uvs.assign(2, glm::vec2(0));
    EXPECT_EQ(errorOf(m), "quad: uvs has 2 entries for 4 vertices");

    m = quad();
    m.indices[4] = 4;
    EXPECT_EQ(errorOf(m), "quad: index 4 at position 4 is past the 4 vertices");

    m = quad();
    m.indices.pop_back();
    EXPECT_EQ(errorOf(m), "quad: 5 indices is not a whole number of triangles");

    m = quad();
    m.positions[2].y = std::nanf("");
    EXPECT_EQ(errorOf(m), "quad: position 2 is not finite");
}

TEST(Mesh, BoundsCoverAllPositionsAndStartEmpty)
{
    EXPECT_TRUE(computeBounds(MeshData{}).empty());
    EXPECT_EQ(computeBounds(MeshData{}).radius(), 0.0f);
    MeshData m;
    m.positions = {{-1, 2, 3}, {4, -5, 6}, {0, 0, -7}};
    const Bounds b = computeBounds(m);
    EXPECT_EQ(b.min, glm::vec3(-1, -5, -7));
    EXPECT_EQ(b.max, glm::vec3(4, 2, 6));
    EXPECT_EQ(b.center(), glm::vec3(1.5f, -1.5f, -0.5f));
}

TEST(Mesh, SmoothNormalsWeighTrianglesByArea)
{
    // Vertex 0 is shared by a triangle of area 2 facing +Z and one of area 0.5 facing +X:
    // the sum of the unnormalised face normals is (1, 0, 4).
    MeshData m;
    m.positions = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 1, 0}, {0, 0, 1}};
    m.indices = {0, 1, 2, 0, 3, 4};
    computeSmoothNormals(m);
    const glm::vec3 expected = glm::normalize(glm::vec3(1, 0, 4));
    EXPECT_NEAR(glm::distance(m.normals[0], expected), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::distance(m.normals[1], glm::vec3(0, 0, 1)), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::distance(m.normals[4], glm::vec3(1, 0, 0)), 0.0f, 1e-6f);
}

TEST(Mesh, SmoothNormalsOfUntouchedOrDegenerateVerticesAreFinite)
{
    MeshData m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {5, 5, 5}}; // a line, and a loose vertex
    m.indices = {0, 1, 2};
    computeSmoothNormals(m);
    for (const glm::vec3& n : m.normals) EXPECT_EQ(n, glm::vec3(0, 1, 0));
}

TEST(Mesh, GeneratedTangentsFollowTheGltfConvention)
{
    // u grows along +X, v grows along -Y: tangent +X, bitangent (image up) +Y =
    // cross(+Z, +X), so w = +1.
    MeshData m = quad();
    m.tangents.clear();
    generateTangents(m);
    for (const glm::vec4& t : m.tangents) {
        EXPECT_NEAR(glm::distance(glm::vec3(t), glm::vec3(1, 0, 0)), 0.0f, 1e-6f);
        EXPECT_EQ(t.w, 1.0f);
    }
    // The same quad with its texture flipped vertically (v grows upwards): the image's
    // up is now -Y, so the bitangent must flip: w = -1.
    for (glm::vec2& uv : m.uvs) uv.y = 1.0f - uv.y;
    generateTangents(m);
    for (const glm::vec4& t : m.tangents) {
        EXPECT_NEAR(glm::distance(glm::vec3(t), glm::vec3(1, 0, 0)), 0.0f, 1e-6f);
        EXPECT_EQ(t.w, -1.0f);
    }
}

TEST(Mesh, TangentsWithoutUvsAreStillOrthonormal)
{
    MeshData m = quad();
    m.uvs.clear();
    m.tangents.clear();
    generateTangents(m);
    ASSERT_EQ(m.tangents.size(), 4u);
    for (std::size_t i = 0; i < 4; ++i) {
        EXPECT_NEAR(glm::length(glm::vec3(m.tangents[i])), 1.0f, 1e-6f);
        EXPECT_NEAR(glm::dot(glm::vec3(m.tangents[i]), m.normals[i]), 0.0f, 1e-6f);
    }
}

TEST(Mesh, NonUniformScaleKeepsNormalsPerpendicularToTheSurface)
{
    // A sphere scaled by S becomes an ellipsoid whose normal at S p is S^-1 n, normalised.
    MeshData m = makeUvSphere(1.0f, 16, 8);
    const MeshData original = m;
    const glm::vec3 s(2.0f, 1.0f, 0.5f);
    ASSERT_TRUE(transformMesh(m, glm::scale(glm::mat4(1.0f), s)));
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
        EXPECT_NEAR(glm::distance(m.positions[i], original.positions[i] * s), 0.0f, 1e-6f);
        const glm::vec3 expected = glm::normalize(original.normals[i] / s);
        EXPECT_NEAR(glm::distance(m.normals[i], expected), 0.0f, 1e-5f) << i;
        EXPECT_NEAR(glm::dot(glm::vec3(m.tangents[i]), m.normals[i]), 0.0f, 1e-5f) << i;
        EXPECT_NEAR(glm::length(glm::vec3(m.tangents[i])), 1.0f, 1e-5f);
    }
}

TEST(Mesh, MirroringFlipsWindingAndHandedness)
{
    MeshData m = quad();
    ASSERT_TRUE(transformMesh(m, glm::scale(glm::mat4(1.0f), glm::vec3(-1, 1, 1))));
    for (std::size_t t = 0; t < m.triangleCount(); ++t)
        EXPECT_GT(glm::dot(faceNormal(m, t), m.normals[m.indices[3 * t]]), 0.0f) << "triangle " << t << " turned inside out";
    for (const glm::vec4& t : m.tangents) {
        EXPECT_NEAR(glm::distance(glm::vec3(t), glm::vec3(-1, 0, 0)), 0.0f, 1e-6f);
        // The bitangent must still point to +Y: cross(+Z, -X) = -Y, so w = -1.
        EXPECT_EQ(t.w, -1.0f);
    }
}

TEST(Mesh, SingularOrNonFiniteTransformsAreRefusedWithoutChanges)
{
    MeshData m = quad();
    EXPECT_FALSE(transformMesh(m, glm::scale(glm::mat4(1.0f), glm::vec3(1, 0, 1))));
    glm::mat4 nan(1.0f);
    nan[3][0] = std::nanf("");
    EXPECT_FALSE(transformMesh(m, nan));
    EXPECT_EQ(m.positions, quad().positions);
    EXPECT_EQ(m.indices, quad().indices);
}
