#pragma once
// A MeshData uploaded once into immutable GL buffers: one interleaved vertex buffer, one
// index buffer and the vertex array that describes them (DSA, so no bind-to-edit).
#include <cstdint>

#include "gl/handles.hpp"
#include "scene/mesh.hpp"

namespace iblab {

// Attribute locations every mesh shader declares (assets/shaders/mesh.vert).
enum MeshAttribute : GLuint { kPosition = 0, kNormal = 1, kTangent = 2, kUv0 = 3, kUv1 = 4 };

class GpuMesh {
public:
    explicit GpuMesh(const MeshData& mesh);
    void draw() const;
    std::size_t indexCount() const { return indexCount_; }
    std::size_t byteSize() const { return byteSize_; }

private:
    gl::Buffer vertices_;
    gl::Buffer indices_;
    gl::VertexArray vertexArray_;
    std::size_t indexCount_ = 0;
    std::size_t byteSize_ = 0;
};

} // namespace iblab
