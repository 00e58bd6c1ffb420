// Accessor reads with bounds checks of our own: component types and values, bufferView
// ranges, sparse substitutions, and the vertex and index budgets.
#include "scene/internal/gltf_accessors.hpp"

#include <algorithm>
#include <cstring>

#include "io/error.hpp"
#include "scene/internal/gltf_document.hpp"

namespace iblab::scene_detail {
namespace {

const char* typeName(int type)
{
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    }
    return "an unknown type";
}

int componentSize(int componentType)
{
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    }
    return 0;
}

// One component as a number; normalized integers map to [0, 1] (unsigned) or [-1, 1]
// (signed, with the most negative value clamped as the glTF spec says).
double componentValue(const std::uint8_t* p, int componentType, bool normalized)
{
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
        std::int8_t v;
        std::memcpy(&v, p, 1);
        return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? p[0] / 255.0 : p[0];
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        std::int16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        std::uint16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        std::uint32_t v;
        std::memcpy(&v, p, 4);
        return v;
    }
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        float v;
        std::memcpy(&v, p, 4);
        return v;
    }
    }
    return 0.0;
}

} // namespace

void GeometryBudget::requireVertices(std::uint64_t count, const std::string& what) const
{
    if (count > options_.maxVertices - std::min(verticesUsed_, options_.maxVertices))
        throw Error(path_, what + " brings the model past the " + std::to_string(options_.maxVertices) +
                               "-vertex budget (ModelLoadOptions::maxVertices)");
}

void GeometryBudget::requireIndices(std::uint64_t count, const std::string& what) const
{
    if (count > options_.maxIndices - std::min(indicesUsed_, options_.maxIndices))
        throw Error(path_, what + " brings the model past the " + std::to_string(options_.maxIndices) +
                               "-index budget (ModelLoadOptions::maxIndices)");
}

void GeometryBudget::take(std::uint64_t vertices, std::uint64_t indices)
{
    verticesUsed_ += vertices;
    indicesUsed_ += indices;
}

void AccessorReader::fail(const std::string& problem) const { throw Error(path_, problem); }

// Start and stride of `count` elements of `elementSize` bytes at `byteOffset` in a
// bufferView, after checking that all of them lie inside it:
//   byteOffset + stride * (count - 1) + elementSize <= byteLength.
std::pair<const std::uint8_t*, std::size_t> AccessorReader::locate(int viewIndex, std::size_t byteOffset, std::size_t count,
                                                                   std::size_t elementSize, bool allowStride,
                                                                   const std::string& what) const
{
    if (viewIndex < 0 || std::size_t(viewIndex) >= gltf_.bufferViews.size())
        fail(what + " refers to bufferViews[" + std::to_string(viewIndex) + "], which does not exist");
    const tinygltf::BufferView& view = gltf_.bufferViews[std::size_t(viewIndex)];
    // Re-checked although readGltfDocument() validated views: this is what guards
    // the raw pointer arithmetic below.
    if (view.buffer < 0 || std::size_t(view.buffer) >= gltf_.buffers.size() ||
        view.byteOffset > gltf_.buffers[std::size_t(view.buffer)].data.size() ||
        view.byteLength > gltf_.buffers[std::size_t(view.buffer)].data.size() - view.byteOffset)
        fail(indexed("bufferViews", std::size_t(viewIndex)) + " lies outside its buffer");
    const std::size_t stride = allowStride && view.byteStride ? view.byteStride : elementSize;
    if (stride < elementSize)
        fail(what + ": the byteStride " + std::to_string(stride) + " of " + indexed("bufferViews", std::size_t(viewIndex)) +
             " is smaller than the " + std::to_string(elementSize) + "-byte element");
    if (count > 0) {
        // Division first, so that a huge count cannot overflow the multiplication.
        const bool fits = byteOffset <= view.byteLength && elementSize <= view.byteLength - byteOffset &&
                          (count - 1) <= (view.byteLength - byteOffset - elementSize) / stride;
        if (!fits)
            fail(what + " needs " + std::to_string(count) + " elements of " + std::to_string(elementSize) +
                 " bytes, stride " + std::to_string(stride) + ", from byte " + std::to_string(byteOffset) + " of " +
                 indexed("bufferViews", std::size_t(viewIndex)) + ", which has only " +
                 std::to_string(view.byteLength) + " bytes: the accessor is out of range");
    }
    return {gltf_.buffers[std::size_t(view.buffer)].data.data() + view.byteOffset + byteOffset, stride};
}

const tinygltf::Accessor& AccessorReader::accessor(int index, const std::string& what) const
{
    if (index < 0 || std::size_t(index) >= gltf_.accessors.size())
        fail(what + " refers to accessors[" + std::to_string(index) + "], which does not exist");
    return gltf_.accessors[std::size_t(index)];
}

// Calls sink(element, component, value) for every component of an accessor of
// `components` components, dense part first, then sparse substitutions.
template <class Sink>
void AccessorReader::visitAccessor(int index, int components, const std::string& what, Sink&& sink) const
{
    const tinygltf::Accessor& a = accessor(index, what);
    const std::size_t size = std::size_t(componentSize(a.componentType));
    const std::size_t elementSize = size * std::size_t(components);
    if (a.bufferView >= 0) {
        const auto [data, stride] = locate(a.bufferView, a.byteOffset, a.count, elementSize, true, what);
        for (std::size_t e = 0; e < a.count; ++e)
            for (int c = 0; c < components; ++c)
                sink(e, c, componentValue(data + e * stride + std::size_t(c) * size, a.componentType, a.normalized));
    } // else: all zeros, the caller's initial values
    if (!a.sparse.isSparse)
        return;
    const std::string sparseWhat = what + " (sparse)";
    const int indexType = a.sparse.indices.componentType;
    if (a.sparse.count < 0 || std::size_t(a.sparse.count) > a.count)
        fail(sparseWhat + ": sparse.count " + std::to_string(a.sparse.count) + " is not in 0.." + std::to_string(a.count));
    if (indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        fail(sparseWhat + ": sparse indices have component type " + std::to_string(indexType));
    const std::size_t n = std::size_t(a.sparse.count);
    const auto [indices, indexStride] = locate(a.sparse.indices.bufferView, std::size_t(std::max(0, a.sparse.indices.byteOffset)),
                                               n, std::size_t(componentSize(indexType)), false, sparseWhat);
    const auto [values, valueStride] = locate(a.sparse.values.bufferView, std::size_t(std::max(0, a.sparse.values.byteOffset)),
                                              n, elementSize, false, sparseWhat);
    for (std::size_t s = 0; s < n; ++s) {
        const double target = componentValue(indices + s * indexStride, indexType, false);
        if (target >= double(a.count))
            fail(sparseWhat + ": sparse index " + std::to_string(std::uint64_t(target)) + " is past the " +
                 std::to_string(a.count) + " elements");
        for (int c = 0; c < components; ++c)
            sink(std::size_t(target), c,
                 componentValue(values + s * valueStride + std::size_t(c) * size, a.componentType, a.normalized));
    }
}

template <int N>
std::vector<glm::vec<N, float>> AccessorReader::readVectors(int index, std::size_t expectedCount, const std::string& what) const
{
    static constexpr int kTypes[] = {0, TINYGLTF_TYPE_SCALAR, TINYGLTF_TYPE_VEC2, TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4};
    const tinygltf::Accessor& a = accessor(index, what);
    const std::string where = what + " (" + indexed("accessors", std::size_t(index)) + ")";
    if (a.type != kTypes[N])
        fail(where + " is " + typeName(a.type) + ", expected " + typeName(kTypes[N]));
    if (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT || componentSize(a.componentType) == 0)
        fail(where + " has component type " + std::to_string(a.componentType) +
             ", expected FLOAT or a (normalized) byte or short");
    if (a.count != expectedCount)
        fail(where + " has " + std::to_string(a.count) + " elements, POSITION has " + std::to_string(expectedCount));
    std::vector<glm::vec<N, float>> out(a.count, glm::vec<N, float>(0.0f));
    visitAccessor(index, N, where, [&](std::size_t e, int c, double v) { out[e][c] = float(v); });
    return out;
}

std::vector<std::uint32_t> AccessorReader::readIndices(int index, const std::string& what, const GeometryBudget& budget) const
{
    const tinygltf::Accessor& a = accessor(index, what);
    const std::string where = what + " (" + indexed("accessors", std::size_t(index)) + ")";
    if (a.type != TINYGLTF_TYPE_SCALAR)
        fail(where + " is " + typeName(a.type) + ", indices must be SCALAR");
    if (a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        fail(where + " has component type " + std::to_string(a.componentType) +
             ", indices must be unsigned byte, short or int");
    budget.requireIndices(a.count, where);
    std::vector<std::uint32_t> out(a.count, 0);
    visitAccessor(index, 1, where, [&](std::size_t e, int, double v) { out[e] = std::uint32_t(v); });
    return out;
}

template std::vector<glm::vec2> AccessorReader::readVectors<2>(int, std::size_t, const std::string&) const;
template std::vector<glm::vec3> AccessorReader::readVectors<3>(int, std::size_t, const std::string&) const;
template std::vector<glm::vec4> AccessorReader::readVectors<4>(int, std::size_t, const std::string&) const;

} // namespace iblab::scene_detail
