#pragma once
// PRIVATE to iblab_scene (includes tinygltf): reading accessors out of a parsed glTF with
// bounds checks of our own, and the vertex and index budgets the reads are charged to.
// The glTF library maps JSON to structs but does not check that an accessor's elements lie
// inside its bufferView; AccessorReader does, before every read (offset + stride *
// (count - 1) + element size <= byteLength, in arithmetic that cannot overflow), for dense
// data and sparse substitutions alike, and converts float, normalized and plain integer
// components to numbers as the glTF spec defines them.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include "scene/gltf_model.hpp"

namespace iblab::scene_detail {

// ModelLoadOptions::maxVertices and maxIndices, counted over the flattened model (a mesh
// used by n nodes counts n times). Checked before anything is allocated for the elements.
class GeometryBudget {
public:
    GeometryBudget(const std::string& path, const ModelLoadOptions& options) : path_(path), options_(options) {}
    // Throw iblab::Error naming `what` when `count` more would not fit.
    void requireVertices(std::uint64_t count, const std::string& what) const;
    void requireIndices(std::uint64_t count, const std::string& what) const;
    // Charges an instance that has been added to the model.
    void take(std::uint64_t vertices, std::uint64_t indices);

private:
    const std::string& path_;
    const ModelLoadOptions& options_;
    std::uint64_t verticesUsed_ = 0;
    std::uint64_t indicesUsed_ = 0;
};

class AccessorReader {
public:
    AccessorReader(const std::string& path, const tinygltf::Model& gltf) : path_(path), gltf_(gltf) {}

    // accessors[index], or an Error naming `what` when there is no such accessor.
    const tinygltf::Accessor& accessor(int index, const std::string& what) const;

    // A float vector attribute (POSITION, NORMAL, TANGENT, TEXCOORD_n; N = 2, 3 or 4): the
    // accessor must have the matching type, `expectedCount` elements, and float or 8/16-bit
    // integer components (integers as KHR_mesh_quantization and normalized texcoords allow).
    template <int N>
    std::vector<glm::vec<N, float>> readVectors(int index, std::size_t expectedCount, const std::string& what) const;

    // Unsigned byte, short or int SCALAR indices, their count checked against `budget`
    // before they are read. Values are not checked against the vertex count here.
    std::vector<std::uint32_t> readIndices(int index, const std::string& what, const GeometryBudget& budget) const;

private:
    [[noreturn]] void fail(const std::string& problem) const;
    std::pair<const std::uint8_t*, std::size_t> locate(int viewIndex, std::size_t byteOffset, std::size_t count,
                                                       std::size_t elementSize, bool allowStride,
                                                       const std::string& what) const;
    template <class Sink>
    void visitAccessor(int index, int components, const std::string& what, Sink&& sink) const;

    const std::string& path_;
    const tinygltf::Model& gltf_;
};

} // namespace iblab::scene_detail
