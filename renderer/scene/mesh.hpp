#pragma once
// Triangle meshes on the CPU, before upload: the one vertex layout every scene source
// (procedural spheres, glTF files) produces, so the renderer has a single path.
//
// Conventions (glTF 2.0's, so that loaded and generated meshes agree):
//  - right-handed, +Y up; front faces wind counter-clockwise seen from outside;
//  - uv (0,0) is the top-left of a texture image, v grows downwards;
//  - tangent.xyz points along +u, and the bitangent, cross(normal, tangent.xyz) *
//    tangent.w, points towards the top of the image (-v): a normal map's green channel
//    is "up" in the image (the OpenGL / glTF / Blender convention).
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace iblab {

// Axis-aligned box; default-constructed it is empty (min > max) and extending it by any
// point makes it that point.
struct Bounds {
    glm::vec3 min{std::numeric_limits<float>::infinity()};
    glm::vec3 max{-std::numeric_limits<float>::infinity()};

    bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
    void extend(const glm::vec3& p)
    {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    void extend(const Bounds& other)
    {
        if (!other.empty()) {
            extend(other.min);
            extend(other.max);
        }
    }
    glm::vec3 center() const { return empty() ? glm::vec3(0.0f) : 0.5f * (min + max); }
    glm::vec3 size() const { return empty() ? glm::vec3(0.0f) : max - min; }
    // Radius of the bounding sphere around center(): what a camera needs to frame it.
    float radius() const { return 0.5f * glm::length(size()); }
};

struct MeshData {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;   // unit length
    std::vector<glm::vec4> tangents;  // xyz unit length and orthogonal to the normal, w = +-1
    std::vector<glm::vec2> uvs;       // TEXCOORD_0; empty when the source has none
    std::vector<glm::vec2> uvs1;      // TEXCOORD_1; empty unless a material may use it
    std::vector<std::uint32_t> indices; // triangle list

    std::size_t vertexCount() const { return positions.size(); }
    std::size_t triangleCount() const { return indices.size() / 3; }

    // Throws iblab::Error("<subject>: <problem>") when an attribute array's size differs
    // from the vertex count (normals and tangents must be present, uvs may be empty),
    // the index count is not a multiple of 3, an index is >= the vertex count, or a
    // position is not finite.
    void validate(std::string_view subject = "mesh") const;
};

Bounds computeBounds(const MeshData& mesh);

// Smooth vertex normals: each triangle adds its unnormalised face normal (|cross| is
// twice its area, so big triangles weigh more) to its three vertices, then the sums are
// normalised. Vertices shared through the index buffer are smoothed over; split vertices
// (uv seams, hard edges) keep their own normals. Vertices no triangle touches, or whose
// triangles cancel out, get +Y so that nothing downstream sees a NaN.
// Note: glTF asks for FLAT normals when a file has none; iblab smooths on purpose, since
// an artist previewing materials gains nothing from faceting an indexed mesh (a
// non-indexed triangle soup comes out flat anyway).
void computeSmoothNormals(MeshData& mesh);

// Tangents from uvs, for meshes that bring none (needs normals):
//   per triangle, dP/du and dP/dv from the edge vectors and their uv deltas (Lengyel's
//   method), summed per vertex; then tangent = Gram-Schmidt(sum dP/du) against the
//   normal, and w = +1 when cross(n, t) agrees with the image-up direction -sum dP/dv
//   (see the conventions above), else -1.
// This is not bit-identical to MikkTSpace (which weighs by corner angle and may split
// vertices), so normal maps baked against MikkTSpace can differ slightly on irregular
// uv layouts; on regular layouts such as the spheres the two agree. Triangles with a
// degenerate uv mapping contribute nothing; vertices left without a usable tangent (or a
// mesh without uvs) get an arbitrary unit vector orthogonal to the normal, w = +1.
void generateTangents(MeshData& mesh);

// Applies a node transform in place: positions by M, normals by the inverse transpose
// of M's upper 3x3 (so they stay perpendicular to the surface under non-uniform scale),
// tangents by M itself (they lie in the surface), all re-normalised. A mirroring
// transform (negative determinant) would turn the mesh inside out, so the winding of
// every triangle and the tangents' w are flipped to keep front faces and bitangents
// right. Returns false, leaving the mesh untouched, when M is singular or not finite.
bool transformMesh(MeshData& mesh, const glm::mat4& matrix);

} // namespace iblab
