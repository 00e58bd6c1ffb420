#include "scene/mesh.hpp"

#include <cmath>
#include <string>

#include "io/error.hpp"

namespace iblab {
namespace {

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Any unit vector orthogonal to n (Frisvad-style branch on the dominant axis keeps it
// well conditioned).
glm::vec3 anyOrthogonal(const glm::vec3& n)
{
    const glm::vec3 axis = std::abs(n.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
    return glm::normalize(glm::cross(axis, n));
}

void checkSize(std::string_view subject, const char* what, std::size_t size, std::size_t expected, bool mayBeEmpty)
{
    if (size == expected || (mayBeEmpty && size == 0))
        return;
    throw Error(subject, std::string(what) + " has " + std::to_string(size) + " entries for " +
                             std::to_string(expected) + " vertices");
}

} // namespace

void MeshData::validate(std::string_view subject) const
{
    const std::size_t n = positions.size();
    checkSize(subject, "normals", normals.size(), n, false);
    checkSize(subject, "tangents", tangents.size(), n, false);
    checkSize(subject, "uvs", uvs.size(), n, true);
    checkSize(subject, "uvs1", uvs1.size(), n, true);
    if (indices.size() % 3 != 0)
        throw Error(subject, std::to_string(indices.size()) + " indices is not a whole number of triangles");
    for (std::size_t i = 0; i < indices.size(); ++i)
        if (indices[i] >= n)
            throw Error(subject, "index " + std::to_string(indices[i]) + " at position " + std::to_string(i) +
                                     " is past the " + std::to_string(n) + " vertices");
    for (std::size_t i = 0; i < n; ++i)
        if (!finite(positions[i]))
            throw Error(subject, "position " + std::to_string(i) + " is not finite");
}

Bounds computeBounds(const MeshData& mesh)
{
    Bounds b;
    for (const glm::vec3& p : mesh.positions) b.extend(p);
    return b;
}

void computeSmoothNormals(MeshData& mesh)
{
    std::vector<glm::vec3> sums(mesh.positions.size(), glm::vec3(0.0f));
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const std::uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
        const glm::vec3 faceNormal = glm::cross(mesh.positions[i1] - mesh.positions[i0], mesh.positions[i2] - mesh.positions[i0]);
        if (!finite(faceNormal))
            continue;
        sums[i0] += faceNormal;
        sums[i1] += faceNormal;
        sums[i2] += faceNormal;
    }
    mesh.normals.resize(sums.size());
    for (std::size_t i = 0; i < sums.size(); ++i) {
        const float len = glm::length(sums[i]);
        // The threshold only rejects exact cancellation and underflow: the sums are
        // unnormalised areas, so a tiny but clean mesh still has a meaningful direction.
        mesh.normals[i] = (len > 1e-30f && std::isfinite(len)) ? sums[i] / len : glm::vec3(0.0f, 1.0f, 0.0f);
    }
}

void generateTangents(MeshData& mesh)
{
    const std::size_t n = mesh.positions.size();
    std::vector<glm::vec3> dPdu(n, glm::vec3(0.0f)), dPdv(n, glm::vec3(0.0f));
    if (mesh.uvs.size() == n) {
        for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
            const std::uint32_t i[3] = {mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]};
            const glm::vec3 e1 = mesh.positions[i[1]] - mesh.positions[i[0]];
            const glm::vec3 e2 = mesh.positions[i[2]] - mesh.positions[i[0]];
            const glm::vec2 d1 = mesh.uvs[i[1]] - mesh.uvs[i[0]];
            const glm::vec2 d2 = mesh.uvs[i[2]] - mesh.uvs[i[0]];
            // [e1 e2] = [dP/du dP/dv] [d1 d2]; invert the 2x2 uv matrix.
            const float det = d1.x * d2.y - d2.x * d1.y;
            if (!(std::abs(det) > 1e-20f))
                continue; // the triangle maps to a line or point in uv space
            const glm::vec3 su = (e1 * d2.y - e2 * d1.y) / det;
            const glm::vec3 sv = (e2 * d1.x - e1 * d2.x) / det;
            if (!finite(su) || !finite(sv))
                continue;
            for (std::uint32_t k : i) {
                dPdu[k] += su;
                dPdv[k] += sv;
            }
        }
    }
    mesh.tangents.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const glm::vec3& nrm = mesh.normals[i];
        glm::vec3 t = dPdu[i] - nrm * glm::dot(nrm, dPdu[i]);
        const float len = glm::length(t);
        if (!(len > 1e-20f) || !std::isfinite(len)) {
            mesh.tangents[i] = glm::vec4(anyOrthogonal(nrm), 1.0f);
            continue;
        }
        t /= len;
        // -dP/dv: uv v grows downwards in the image, the bitangent points up.
        const float w = glm::dot(glm::cross(nrm, t), -dPdv[i]) < 0.0f ? -1.0f : 1.0f;
        mesh.tangents[i] = glm::vec4(t, w);
    }
}

bool transformMesh(MeshData& mesh, const glm::mat4& matrix)
{
    const glm::mat3 linear(matrix);
    const float det = glm::determinant(linear);
    if (!(std::abs(det) > 0.0f) || !std::isfinite(det))
        return false;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(matrix[c][r]))
                return false;
    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(linear));
    for (glm::vec3& p : mesh.positions) p = glm::vec3(matrix * glm::vec4(p, 1.0f));
    for (std::size_t i = 0; i < mesh.normals.size(); ++i) {
        const glm::vec3 n = normalMatrix * mesh.normals[i];
        const float len = glm::length(n);
        mesh.normals[i] = len > 0.0f && std::isfinite(len) ? n / len : glm::vec3(0.0f, 1.0f, 0.0f);
    }
    const float handedness = det < 0.0f ? -1.0f : 1.0f;
    for (std::size_t i = 0; i < mesh.tangents.size(); ++i) {
        const glm::vec3 nrm = i < mesh.normals.size() ? mesh.normals[i] : glm::vec3(0.0f, 1.0f, 0.0f);
        glm::vec3 t = linear * glm::vec3(mesh.tangents[i]);
        // Exact arithmetic keeps M t perpendicular to M^-T n; re-orthogonalising removes
        // the rounding so downstream TBN matrices stay orthonormal.
        t -= nrm * glm::dot(nrm, t);
        const float len = glm::length(t);
        t = len > 1e-20f && std::isfinite(len) ? t / len : anyOrthogonal(nrm);
        mesh.tangents[i] = glm::vec4(t, mesh.tangents[i].w * handedness);
    }
    if (det < 0.0f)
        for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
    return true;
}

} // namespace iblab
