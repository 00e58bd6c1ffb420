#include "frame/gpu_mesh.hpp"

#include <cstddef>
#include <vector>

namespace iblab {
namespace {

struct Vertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec4 tangent;
    glm::vec2 uv0;
    glm::vec2 uv1;
};

} // namespace

GpuMesh::GpuMesh(const MeshData& mesh)
{
    mesh.validate("mesh upload");
    std::vector<Vertex> interleaved(mesh.vertexCount());
    for (std::size_t i = 0; i < interleaved.size(); ++i) {
        Vertex& v = interleaved[i];
        v.position = mesh.positions[i];
        v.normal = mesh.normals[i];
        v.tangent = mesh.tangents[i];
        // A mesh without texture coordinates samples every texture at (0, 0): its material
        // then behaves as its factors times one texel, which is what glTF viewers do.
        v.uv0 = mesh.uvs.empty() ? glm::vec2(0.0f) : mesh.uvs[i];
        v.uv1 = mesh.uvs1.empty() ? v.uv0 : mesh.uvs1[i];
    }
    vertices_ = gl::createBufferWith<Vertex>(interleaved);
    indices_ = gl::createBufferWith<std::uint32_t>(mesh.indices);
    indexCount_ = mesh.indices.size();
    byteSize_ = interleaved.size() * sizeof(Vertex) + mesh.indices.size() * sizeof(std::uint32_t);

    vertexArray_ = gl::createVertexArray();
    const GLuint vao = vertexArray_.id();
    glVertexArrayVertexBuffer(vao, 0, vertices_.id(), 0, sizeof(Vertex));
    glVertexArrayElementBuffer(vao, indices_.id());
    auto attribute = [vao](GLuint location, GLint components, std::size_t offset) {
        glEnableVertexArrayAttrib(vao, location);
        glVertexArrayAttribFormat(vao, location, components, GL_FLOAT, GL_FALSE, GLuint(offset));
        glVertexArrayAttribBinding(vao, location, 0);
    };
    attribute(kPosition, 3, offsetof(Vertex, position));
    attribute(kNormal, 3, offsetof(Vertex, normal));
    attribute(kTangent, 4, offsetof(Vertex, tangent));
    attribute(kUv0, 2, offsetof(Vertex, uv0));
    attribute(kUv1, 2, offsetof(Vertex, uv1));
}

void GpuMesh::draw() const
{
    glBindVertexArray(vertexArray_.id());
    glDrawElements(GL_TRIANGLES, GLsizei(indexCount_), GL_UNSIGNED_INT, nullptr);
}

} // namespace iblab
