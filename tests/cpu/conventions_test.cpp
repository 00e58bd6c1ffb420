// Pins iblab's direction conventions (assets/shaders/common/conventions.glsl) to the values
// its header comment promises and to the OpenGL cube-map table, independently of the code.
#include <cmath>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibl/conventions.hpp"

namespace {

using iblab::kPi;

// The shared code runs in float: directions and uvs carry ~1e-7 relative error, and acos near
// the poles amplifies it (d acos / dy = 1/sin), so round trips are checked to 1e-5 away from
// the poles.
constexpr float kTol = 1e-5f;

void expectNear(glm::vec3 a, glm::vec3 b, float tol)
{
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

TEST(Conventions, EquirectRoundTripOverGrid)
{
    for (int j = 1; j < 64; ++j)
        for (int i = 0; i < 128; ++i) {
            const glm::vec2 uv((i + 0.5f) / 128.0f, j / 64.0f);
            const glm::vec3 d = iblab::equirectUvToDirection(uv);
            EXPECT_NEAR(glm::length(d), 1.0f, 1e-6f);
            const glm::vec2 back = iblab::directionToEquirectUv(d);
            EXPECT_NEAR(back.x, uv.x, kTol) << i << "," << j;
            EXPECT_NEAR(back.y, uv.y, kTol) << i << "," << j;
        }
}

TEST(Conventions, EquirectLandmarks)
{
    // Zenith on the first row, nadir on the last.
    EXPECT_NEAR(iblab::directionToEquirectUv({0, 1, 0}).y, 0.0f, 1e-6f);
    EXPECT_NEAR(iblab::directionToEquirectUv({0, -1, 0}).y, 1.0f, 1e-6f);
    // Straight ahead (-Z) is the centre of the panorama, +X a quarter turn to the right,
    // +Z the seam, -X a quarter to the left; all on the horizon v = 0.5.
    const glm::vec2 front = iblab::directionToEquirectUv({0, 0, -1});
    EXPECT_NEAR(front.x, 0.5f, 1e-6f);
    EXPECT_NEAR(front.y, 0.5f, 1e-6f);
    EXPECT_NEAR(iblab::directionToEquirectUv({1, 0, 0}).x, 0.75f, 1e-6f);
    EXPECT_NEAR(iblab::directionToEquirectUv({-1, 0, 0}).x, 0.25f, 1e-6f);
    const float seam = iblab::directionToEquirectUv({0, 0, 1}).x;
    EXPECT_TRUE(std::abs(seam) < 1e-6f || std::abs(seam - 1.0f) < 1e-6f) << seam;
    // And back: uv -> direction.
    expectNear(iblab::equirectUvToDirection({0.5f, 0.5f}), {0, 0, -1}, 1e-6f);
    expectNear(iblab::equirectUvToDirection({0.75f, 0.5f}), {1, 0, 0}, 1e-6f);
    expectNear(iblab::equirectUvToDirection({0.3f, 0.0f}), {0, 1, 0}, 1e-6f);
}

// OpenGL 4.6 core, table 8.19: major axis -> (sc, tc); s = (sc/|ma| + 1)/2, t = (tc/|ma| + 1)/2.
// Written out here from the table, not from conventions.glsl's code.
glm::vec3 glTable(int face, glm::vec3 r)
{
    float sc = 0, tc = 0, ma = 0;
    switch (face) {
    case 0: sc = -r.z; tc = -r.y; ma = r.x; break;
    case 1: sc = r.z; tc = -r.y; ma = r.x; break;
    case 2: sc = r.x; tc = r.z; ma = r.y; break;
    case 3: sc = r.x; tc = -r.z; ma = r.y; break;
    case 4: sc = r.x; tc = -r.y; ma = r.z; break;
    default: sc = -r.x; tc = -r.y; ma = r.z; break;
    }
    ma = std::abs(ma);
    return {float(face), 0.5f * (sc / ma + 1.0f), 0.5f * (tc / ma + 1.0f)};
}

TEST(Conventions, CubeFaceRoundTripAllFaces)
{
    for (int face = 0; face < 6; ++face)
        for (int j = 0; j < 16; ++j)
            for (int i = 0; i < 16; ++i) {
                // Texel centres of a 16^2 face: never exactly on an edge, where the face
                // choice between two faces is a tie.
                const glm::vec2 st((i + 0.5f) / 16.0f, (j + 0.5f) / 16.0f);
                const glm::vec3 d = iblab::cubeFaceUvToDirection(face, st);
                EXPECT_NEAR(glm::length(d), 1.0f, 1e-6f);
                const glm::vec3 back = iblab::directionToCubeFaceUv(d);
                EXPECT_EQ(int(back.x), face);
                EXPECT_NEAR(back.y, st.x, 1e-6f);
                EXPECT_NEAR(back.z, st.y, 1e-6f);
                // The same direction through the GL table.
                const glm::vec3 gl = glTable(face, d);
                EXPECT_NEAR(gl.y, st.x, 1e-6f);
                EXPECT_NEAR(gl.z, st.y, 1e-6f);
            }
}

TEST(Conventions, CubeFaceCentresAreTheAxes)
{
    const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (int face = 0; face < 6; ++face) {
        expectNear(iblab::cubeFaceUvToDirection(face, {0.5f, 0.5f}), axes[face], 1e-7f);
        const glm::vec3 f = iblab::directionToCubeFaceUv(axes[face]);
        EXPECT_EQ(int(f.x), face);
        EXPECT_NEAR(f.y, 0.5f, 1e-7f);
        EXPECT_NEAR(f.z, 0.5f, 1e-7f);
    }
    // One corner direction per face, straight from the table: on +X, s = 1 means sc = -rz = 1.
    expectNear(iblab::cubeFaceUvToDirection(0, {1.0f, 0.5f}), glm::normalize(glm::vec3(1, 0, -1)), 1e-6f);
    // On +Y, t = 1 means tc = +rz = 1; on -Y, t = 1 means rz = -1.
    expectNear(iblab::cubeFaceUvToDirection(2, {0.5f, 1.0f}), glm::normalize(glm::vec3(0, 1, 1)), 1e-6f);
    expectNear(iblab::cubeFaceUvToDirection(3, {0.5f, 1.0f}), glm::normalize(glm::vec3(0, -1, -1)), 1e-6f);
    // On -Z, s = 1 means sc = -rx = 1; t = 1 on any side face points down.
    expectNear(iblab::cubeFaceUvToDirection(5, {1.0f, 0.5f}), glm::normalize(glm::vec3(-1, 0, -1)), 1e-6f);
    expectNear(iblab::cubeFaceUvToDirection(4, {0.5f, 1.0f}), glm::normalize(glm::vec3(0, -1, 1)), 1e-6f);
}

TEST(Conventions, RotateAboutY)
{
    // The right-handed rotation about +Y, R(yaw) = [[c, 0, s], [0, 1, 0], [-s, 0, c]]:
    // at +90 degrees -Z goes to -X and +X comes round to -Z (what was on the right is now
    // straight ahead, i.e. the panorama turned towards +X).
    const float q = float(kPi / 2);
    expectNear(iblab::rotateAboutY({0, 0, -1}, q), {-1, 0, 0}, 1e-6f);
    expectNear(iblab::rotateAboutY({1, 0, 0}, q), {0, 0, -1}, 1e-6f);
    expectNear(iblab::rotateAboutY({0, 1, 0}, q), {0, 1, 0}, 1e-6f);
    // A general angle against the matrix, and the inverse rotation undoing it.
    const float yaw = 0.7f;
    const glm::vec3 d = glm::normalize(glm::vec3(0.3f, -0.4f, 0.8f));
    const glm::vec3 expected(std::cos(yaw) * d.x + std::sin(yaw) * d.z, d.y, -std::sin(yaw) * d.x + std::cos(yaw) * d.z);
    expectNear(iblab::rotateAboutY(d, yaw), expected, 1e-6f);
    expectNear(iblab::rotateAboutY(iblab::rotateAboutY(d, yaw), -yaw), d, 1e-6f);
    // Rotating by yaw moves the panorama's longitude u by yaw / (2 pi) (sign: -Z's u = 0.5 goes
    // to -X's u = 0.25 for +90 degrees).
    const glm::vec2 uv0 = iblab::directionToEquirectUv(d);
    const glm::vec2 uv1 = iblab::directionToEquirectUv(iblab::rotateAboutY(d, yaw));
    EXPECT_NEAR(std::fmod(uv0.x - uv1.x + 1.0f, 1.0f), yaw / float(2 * kPi), 1e-5f);
    EXPECT_NEAR(uv0.y, uv1.y, 1e-6f);
}

} // namespace
