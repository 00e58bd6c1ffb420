// Procedural spheres, the metallic x roughness grid and the counting strip, checked
// against the closed forms in sphere.hpp.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>
#include <string>

#include "io/error.hpp"
#include "scene/sphere.hpp"

using namespace iblab;

namespace {

struct Resolution {
    float radius;
    int segments;
    int rings;
};

class UvSphere : public ::testing::TestWithParam<Resolution> {};

bool finite(const glm::vec4& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w); }

} // namespace

TEST_P(UvSphere, HasTheDocumentedTopology)
{
    const auto [radius, segments, rings] = GetParam();
    const MeshData m = makeUvSphere(radius, segments, rings);
    EXPECT_NO_THROW(m.validate("sphere"));
    EXPECT_EQ(m.vertexCount(), std::size_t(2 * segments + (rings - 1) * (segments + 1)));
    // Two triangles per quad, minus the collapsed one in each cap quad.
    EXPECT_EQ(m.triangleCount(), std::size_t(2 * segments * (rings - 1)));
}

TEST_P(UvSphere, NormalsAreUnitAndEqualPositionOverRadius)
{
    const auto [radius, segments, rings] = GetParam();
    const MeshData m = makeUvSphere(radius, segments, rings);
    for (std::size_t i = 0; i < m.vertexCount(); ++i) {
        EXPECT_NEAR(glm::length(m.normals[i]), 1.0f, 1e-6f) << i;
        EXPECT_NEAR(glm::distance(m.normals[i], m.positions[i] / radius), 0.0f, 1e-6f) << i;
    }
}

TEST_P(UvSphere, TangentsAreUnitOrthogonalAndFiniteEvenAtThePoles)
{
    const auto [radius, segments, rings] = GetParam();
    const MeshData m = makeUvSphere(radius, segments, rings);
    for (std::size_t i = 0; i < m.vertexCount(); ++i) {
        ASSERT_TRUE(finite(m.tangents[i])) << i;
        EXPECT_NEAR(glm::length(glm::vec3(m.tangents[i])), 1.0f, 1e-6f) << i;
        EXPECT_NEAR(glm::dot(glm::vec3(m.tangents[i]), m.normals[i]), 0.0f, 1e-6f) << i;
        EXPECT_EQ(m.tangents[i].w, 1.0f);
    }
}

TEST_P(UvSphere, UvsStayInTheUnitSquareAndPolesSitMidSegment)
{
    const auto [radius, segments, rings] = GetParam();
    const MeshData m = makeUvSphere(radius, segments, rings);
    std::set<float> poleUs;
    for (std::size_t i = 0; i < m.vertexCount(); ++i) {
        const glm::vec2 uv = m.uvs[i];
        EXPECT_TRUE(uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f) << i;
        // v = 0 is the north pole (+Y), v = 1 the south pole.
        EXPECT_NEAR(m.normals[i].y, std::cos(std::numbers::pi_v<float> * uv.y), 1e-5f) << i;
        if (uv.y == 0.0f) {
            poleUs.insert(uv.x);
            EXPECT_NEAR(std::fmod(uv.x * float(segments) - 0.5f, 1.0f), 0.0f, 1e-5f);
        }
    }
    EXPECT_EQ(poleUs.size(), std::size_t(segments));
}

TEST_P(UvSphere, TrianglesFaceOutwardsAndNoneIsDegenerate)
{
    const auto [radius, segments, rings] = GetParam();
    const MeshData m = makeUvSphere(radius, segments, rings);
    for (std::size_t t = 0; t < m.triangleCount(); ++t) {
        const glm::vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
                        c = m.positions[m.indices[3 * t + 2]];
        const glm::vec3 n = glm::cross(b - a, c - a);
        EXPECT_GT(glm::length(n), 0.0f) << "triangle " << t;
        EXPECT_GT(glm::dot(n, a + b + c), 0.0f) << "triangle " << t << " faces inwards";
    }
}

TEST_P(UvSphere, SeamColumnsCoincideBitForBit)
{
    const auto [radius, segments, rings] = GetParam();
    const MeshData m = makeUvSphere(radius, segments, rings);
    for (int j = 1; j < rings; ++j) {
        const std::size_t first = std::size_t(segments + (j - 1) * (segments + 1));
        const std::size_t last = first + std::size_t(segments);
        EXPECT_EQ(m.positions[first], m.positions[last]);
        EXPECT_EQ(m.uvs[first].x, 0.0f);
        EXPECT_EQ(m.uvs[last].x, 1.0f);
    }
}

TEST(UvSphereTangents, AgreeWithThoseGeneratedFromTheUvs)
{
    // The analytic tangents must be what generateTangents() derives from the uvs, or a
    // normal map would shade differently on a sphere and on a loaded model. Generated
    // tangents follow the triangles' chords, so they only converge with resolution:
    // at 64 x 32 the worst vertex (on the ring next to a pole) is 2.8 degrees off;
    // 0.998 allows 3.6.
    const MeshData m = makeUvSphere(1.0f, 64, 32);
    MeshData generated = m;
    generateTangents(generated);
    for (std::size_t i = 0; i < m.vertexCount(); ++i) {
        EXPECT_GT(glm::dot(glm::vec3(m.tangents[i]), glm::vec3(generated.tangents[i])), 0.998f) << i;
        EXPECT_EQ(m.tangents[i].w, generated.tangents[i].w) << i;
    }
}

INSTANTIATE_TEST_SUITE_P(Resolutions, UvSphere,
                         ::testing::Values(Resolution{1.0f, 64, 32}, Resolution{2.5f, 3, 2}, Resolution{0.25f, 7, 5}));

TEST(UvSphereParameters, AreCheckedWithOneLineErrors)
{
    const auto message = [](float r, int s, int g) -> std::string {
        try {
            makeUvSphere(r, s, g);
        } catch (const Error& e) {
            return e.what();
        }
        return "";
    };
    EXPECT_EQ(message(1.0f, 2, 8), "uvSphere: needs 3..4096 segments and 2..4096 rings, got 2 x 8");
    EXPECT_EQ(message(1.0f, 8, 1), "uvSphere: needs 3..4096 segments and 2..4096 rings, got 8 x 1");
    EXPECT_NE(message(0.0f, 8, 8).find("radius"), std::string::npos);
    EXPECT_NE(message(std::nanf(""), 8, 8).find("radius"), std::string::npos);
}

TEST(SphereGrid, SevenBySevenVariesMetallicByRowAndRoughnessByColumn)
{
    const SphereGrid g = sphereGrid(7, 7, 2.5f);
    ASSERT_EQ(g.spheres.size(), 49u);
    for (int r = 0; r < 7; ++r)
        for (int c = 0; c < 7; ++c) {
            const GridSphere& s = g.spheres[std::size_t(r * 7 + c)];
            EXPECT_EQ(s.row, r);
            EXPECT_EQ(s.column, c);
            EXPECT_FLOAT_EQ(s.metallic, r / 6.0f);
            EXPECT_FLOAT_EQ(s.roughness, c / 6.0f);
            // Centred on the origin, rows upwards, columns to the right.
            EXPECT_FLOAT_EQ(s.transform[3][0], (c - 3) * 2.5f);
            EXPECT_FLOAT_EQ(s.transform[3][1], (r - 3) * 2.5f);
            EXPECT_EQ(s.transform[3][2], 0.0f);
        }
    // Both ends are exact: the grid must show the true extremes.
    EXPECT_EQ(g.spheres.front().metallic, 0.0f);
    EXPECT_EQ(g.spheres.back().metallic, 1.0f);
    EXPECT_EQ(g.spheres.back().roughness, 1.0f);
}

TEST(SphereGrid, LabelsNameTheAxesOutsideTheGrid)
{
    const SphereGrid g = sphereGrid(7, 5, 2.0f);
    ASSERT_EQ(g.labels.size(), 2u + 7u + 5u);
    EXPECT_EQ(g.labels[0].text, "metallic 0..1");
    EXPECT_TRUE(g.labels[0].axisTitle);
    EXPECT_LT(g.labels[0].position.x, -2.0f * 2.0f - 1.0f); // left of the leftmost column (x = -4)
    EXPECT_EQ(g.labels[0].position.y, 0.0f);
    EXPECT_EQ(g.labels[1].text, "roughness 0..1");
    EXPECT_LT(g.labels[1].position.y, -3.0f * 2.0f - 1.0f); // below the bottom row (y = -6)
    EXPECT_EQ(g.labels[2].text, "0.00");
    EXPECT_EQ(g.labels[2 + 6].text, "1.00");
    EXPECT_FLOAT_EQ(g.labels[2 + 6].position.y, 6.0f);
    EXPECT_EQ(g.labels[2 + 7 + 2].text, "0.50");
    EXPECT_FLOAT_EQ(g.labels[2 + 7 + 2].position.x, 0.0f);
}

TEST(SphereGrid, SingleRowOrColumnGetsZero)
{
    const SphereGrid g = sphereGrid(1, 3, 1.0f);
    ASSERT_EQ(g.spheres.size(), 3u);
    for (const GridSphere& s : g.spheres) EXPECT_EQ(s.metallic, 0.0f);
    EXPECT_THROW(sphereGrid(0, 7, 1.0f), Error);
    EXPECT_THROW(sphereGrid(7, 7, 0.0f), Error);
}

TEST(CountingStrip, PlacesKSpheresInACentredRow)
{
    const auto t = countingStrip(4, 3.0f);
    ASSERT_EQ(t.size(), 4u);
    const float expected[] = {-4.5f, -1.5f, 1.5f, 4.5f};
    for (std::size_t i = 0; i < 4; ++i) {
        EXPECT_FLOAT_EQ(t[i][3][0], expected[i]);
        EXPECT_EQ(t[i][3][1], 0.0f);
        EXPECT_EQ(glm::mat3(t[i]), glm::mat3(1.0f));
    }
    EXPECT_EQ(countingStrip(1)[0], glm::mat4(1.0f));
    EXPECT_THROW(countingStrip(0), Error);
}

TEST(CountingStrip, LabelsSitBelowEachSphereInOrder)
{
    const auto labels = stripLabels({"N = 1", "N = 2", "N = 3"}, 2.0f);
    ASSERT_EQ(labels.size(), 3u);
    const float expectedX[] = {-2.0f, 0.0f, 2.0f};
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(labels[i].text, "N = " + std::to_string(i + 1));
        EXPECT_FALSE(labels[i].axisTitle);
        EXPECT_FLOAT_EQ(labels[i].position.x, expectedX[i]);
        EXPECT_FLOAT_EQ(labels[i].position.y, -0.75f * 2.0f); // where the grid's column ticks sit
        EXPECT_EQ(labels[i].position.z, 0.0f);
    }
    EXPECT_THROW(stripLabels({}), Error);
}
