// glTF -> ModelData. readGltfDocument() has already checked the container, the JSON and
// every byte range down to bufferViews; the glTF library then maps the JSON to structs
// (from memory, with no file system access), and this file reads accessors with its own
// bounds checks, flattens the node tree and converts materials and textures.
#include "scene/gltf_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>
#include <set>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <tiny_gltf.h>

#include "io/error.hpp"
#include "scene/internal/gltf_document.hpp"
#include "scene/internal/image_codec.hpp"

namespace iblab {
namespace {

namespace sd = scene_detail;

using sd::indexed;

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

bool finiteVec(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

float clamp01(double v, float fallback) { return std::isfinite(v) ? float(std::clamp(v, 0.0, 1.0)) : fallback; }

// A primitive read once in its mesh's local space; instances copy and transform it.
struct LocalPrimitive {
    std::optional<MeshData> mesh; // nullopt: skipped (a warning said why)
    int material = -1;
};

class ModelBuilder {
public:
    ModelBuilder(const std::string& path, const ModelLoadOptions& options, const tinygltf::Model& gltf,
                 const std::vector<sd::ImageSource>& images, ModelData& out)
        : path_(path), options_(options), gltf_(gltf), images_(images), out_(out), meshCache_(gltf.meshes.size())
    {
    }

    void build()
    {
        for (std::size_t i = 0; i < gltf_.materials.size(); ++i) out_.materials.push_back(convertMaterial(i));
        for (const auto& [node, world] : sceneRoots()) flatten(node, world);
        for (const MeshInstance& instance : out_.instances) out_.bounds.extend(computeBounds(instance.mesh));
    }

private:
    [[noreturn]] void fail(const std::string& problem) const { throw Error(path_, problem); }
    void warn(const std::string& text) { out_.warnings.push_back(text); }

    // ---- accessors -------------------------------------------------------------------

    // Start and stride of `count` elements of `elementSize` bytes at `byteOffset` in a
    // bufferView, after checking that all of them lie inside it:
    //   byteOffset + stride * (count - 1) + elementSize <= byteLength.
    std::pair<const std::uint8_t*, std::size_t> locate(int viewIndex, std::size_t byteOffset, std::size_t count,
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

    const tinygltf::Accessor& accessor(int index, const std::string& what) const
    {
        if (index < 0 || std::size_t(index) >= gltf_.accessors.size())
            fail(what + " refers to accessors[" + std::to_string(index) + "], which does not exist");
        return gltf_.accessors[std::size_t(index)];
    }

    // Calls sink(element, component, value) for every component of an accessor of
    // `components` components, dense part first, then sparse substitutions.
    template <class Sink>
    void visitAccessor(int index, int components, const std::string& what, Sink&& sink) const
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

    // A float vector attribute (POSITION, NORMAL, TANGENT, TEXCOORD_n): the accessor must
    // have the given type, `expectedCount` elements, and float or 8/16-bit integer
    // components (integers as KHR_mesh_quantization and normalized texcoords allow).
    template <int N>
    std::vector<glm::vec<N, float>> readVectors(int index, std::size_t expectedCount, const std::string& what) const
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

    std::vector<std::uint32_t> readIndices(int index, const std::string& what) const
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
        requireIndexBudget(a.count, where);
        std::vector<std::uint32_t> out(a.count, 0);
        visitAccessor(index, 1, where, [&](std::size_t e, int, double v) { out[e] = std::uint32_t(v); });
        return out;
    }

    void requireVertexBudget(std::uint64_t count, const std::string& what) const
    {
        if (count > options_.maxVertices - std::min(verticesUsed_, options_.maxVertices))
            fail(what + " brings the model past the " + std::to_string(options_.maxVertices) +
                 "-vertex budget (ModelLoadOptions::maxVertices)");
    }
    void requireIndexBudget(std::uint64_t count, const std::string& what) const
    {
        if (count > options_.maxIndices - std::min(indicesUsed_, options_.maxIndices))
            fail(what + " brings the model past the " + std::to_string(options_.maxIndices) +
                 "-index budget (ModelLoadOptions::maxIndices)");
    }

    // ---- primitives ------------------------------------------------------------------

    // Triangle-list indices for a primitive of `mode` over `source` (vertex indices, or
    // 0..n-1 for non-indexed primitives). Strips and fans become lists with the spec's
    // vertex order (which keeps every triangle's orientation); their degenerate
    // triangles, used as restarts, are dropped.
    std::optional<std::vector<std::uint32_t>> triangulate(int mode, std::vector<std::uint32_t> source,
                                                          const std::string& what)
    {
        const std::size_t n = source.size();
        if (mode == TINYGLTF_MODE_TRIANGLES) {
            if (n % 3 != 0) {
                warn(what + ": " + std::to_string(n) + " indices is not a whole number of triangles; the last " +
                     std::to_string(n % 3) + " ignored");
                source.resize(n - n % 3);
            }
            return source;
        }
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN) {
            std::vector<std::uint32_t> list;
            if (n < 3)
                return list;
            requireIndexBudget(3 * (n - 2), what);
            list.reserve(3 * (n - 2));
            for (std::size_t i = 0; i + 2 < n; ++i) {
                std::uint32_t t[3];
                if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
                    t[0] = source[i];
                    t[1] = source[i + 1 + i % 2];
                    t[2] = source[i + 2 - i % 2];
                } else {
                    t[0] = source[i + 1];
                    t[1] = source[i + 2];
                    t[2] = source[0];
                }
                if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
                    list.insert(list.end(), t, t + 3);
            }
            return list;
        }
        static const char* const names[] = {"POINTS", "LINES", "LINE_LOOP", "LINE_STRIP"};
        warn(what + ": mode " + (mode >= 0 && mode < 4 ? std::string(names[mode]) : std::to_string(mode)) +
             " is not triangles; skipped");
        return std::nullopt;
    }

    // Unit normals where the file's are usable; where they are not (zero, NaN), or where
    // the file has none, smooth computed ones.
    void completeNormals(MeshData& mesh, bool fromFile)
    {
        if (!fromFile) {
            computeSmoothNormals(mesh);
            return;
        }
        std::optional<MeshData> computed;
        for (std::size_t i = 0; i < mesh.normals.size(); ++i) {
            const float len = glm::length(mesh.normals[i]);
            if (len > 1e-12f && std::isfinite(len)) {
                mesh.normals[i] /= len;
                continue;
            }
            if (!computed) {
                computed = MeshData{mesh.positions, {}, {}, {}, {}, mesh.indices};
                computeSmoothNormals(*computed);
            }
            mesh.normals[i] = computed->normals[i];
        }
    }

    // The file's tangents, orthonormalised against the normals, when every one of them is
    // usable; otherwise (or when there are none) generated ones.
    void completeTangents(MeshData& mesh)
    {
        bool usable = mesh.tangents.size() == mesh.positions.size();
        for (std::size_t i = 0; usable && i < mesh.tangents.size(); ++i) {
            const glm::vec3 n = mesh.normals[i];
            glm::vec3 t = glm::vec3(mesh.tangents[i]);
            t -= n * glm::dot(n, t);
            const float len = glm::length(t);
            usable = len > 1e-6f && std::isfinite(len);
            mesh.tangents[i] = glm::vec4(t / len, mesh.tangents[i].w < 0.0f ? -1.0f : 1.0f);
        }
        if (!usable)
            generateTangents(mesh);
    }

    LocalPrimitive loadPrimitive(const tinygltf::Primitive& p, const std::string& what)
    {
        LocalPrimitive result;
        result.material = p.material;
        if (p.material < -1 || p.material >= int(gltf_.materials.size())) {
            warn(what + ": materials[" + std::to_string(p.material) + "] does not exist; the default material is used");
            result.material = -1;
        }
        const auto attribute = [&](const char* name) {
            const auto it = p.attributes.find(name);
            return it == p.attributes.end() ? -1 : it->second;
        };
        const int positionIndex = attribute("POSITION");
        if (positionIndex < 0) {
            warn(what + " has no POSITION; skipped");
            return result;
        }
        const std::size_t count = accessor(positionIndex, what + " POSITION").count;
        requireVertexBudget(count, what);

        MeshData mesh;
        mesh.positions = readVectors<3>(positionIndex, count, what + " POSITION");
        if (!std::all_of(mesh.positions.begin(), mesh.positions.end(), finiteVec)) {
            warn(what + " has non-finite positions; skipped");
            return result;
        }
        std::vector<std::uint32_t> source;
        if (p.indices >= 0) {
            source = readIndices(p.indices, what + " indices");
            for (std::size_t i = 0; i < source.size(); ++i)
                if (source[i] >= count)
                    fail(what + " indices: index " + std::to_string(source[i]) + " (at position " + std::to_string(i) +
                         ") is past the " + std::to_string(count) + " vertices");
        } else {
            requireIndexBudget(count, what);
            source.resize(count);
            for (std::size_t i = 0; i < count; ++i) source[i] = std::uint32_t(i);
        }
        auto triangles = triangulate(p.mode, std::move(source), what);
        if (!triangles)
            return result;
        mesh.indices = std::move(*triangles);

        const int normalIndex = attribute("NORMAL");
        const int tangentIndex = attribute("TANGENT");
        const int uv0 = attribute("TEXCOORD_0");
        const int uv1 = attribute("TEXCOORD_1");
        if (normalIndex >= 0)
            mesh.normals = readVectors<3>(normalIndex, count, what + " NORMAL");
        if (uv0 >= 0)
            mesh.uvs = readVectors<2>(uv0, count, what + " TEXCOORD_0");
        if (uv1 >= 0)
            mesh.uvs1 = readVectors<2>(uv1, count, what + " TEXCOORD_1");
        // The spec: without normals, the file's tangents must be ignored.
        if (tangentIndex >= 0 && normalIndex >= 0)
            mesh.tangents = readVectors<4>(tangentIndex, count, what + " TANGENT");
        completeNormals(mesh, normalIndex >= 0);
        completeTangents(mesh);
        result.mesh = std::move(mesh);
        return result;
    }

    // ---- node hierarchy --------------------------------------------------------------

    glm::dmat4 localMatrix(const tinygltf::Node& node, const std::string& what)
    {
        if (!node.matrix.empty()) {
            if (node.matrix.size() == 16) {
                glm::dmat4 m;
                for (int c = 0; c < 4; ++c)
                    for (int r = 0; r < 4; ++r) m[c][r] = node.matrix[std::size_t(c * 4 + r)];
                return m;
            }
            warn(what + ".matrix has " + std::to_string(node.matrix.size()) + " numbers, not 16; ignored");
        }
        glm::dmat4 m(1.0);
        if (node.translation.size() == 3)
            m[3] = glm::dvec4(node.translation[0], node.translation[1], node.translation[2], 1.0);
        if (node.rotation.size() == 4) {
            glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]); // glTF stores x, y, z, w
            const double len = glm::length(q);
            if (len > 0.0 && std::isfinite(len))
                m *= glm::mat4_cast(q / len);
            else
                warn(what + ".rotation is not a usable quaternion; ignored");
        }
        if (node.scale.size() == 3)
            m = glm::scale(m, glm::dvec3(node.scale[0], node.scale[1], node.scale[2]));
        return m;
    }

    // The default scene's root nodes: "scene", else scenes[0], else every node that is
    // nobody's child.
    std::vector<std::pair<int, glm::dmat4>> sceneRoots()
    {
        std::vector<int> roots;
        if (!gltf_.scenes.empty()) {
            std::size_t scene = 0;
            if (gltf_.defaultScene >= 0 && std::size_t(gltf_.defaultScene) < gltf_.scenes.size())
                scene = std::size_t(gltf_.defaultScene);
            else if (gltf_.defaultScene >= 0)
                warn("scene " + std::to_string(gltf_.defaultScene) + " does not exist; showing scenes[0]");
            roots = gltf_.scenes[scene].nodes;
        } else {
            std::vector<char> isChild(gltf_.nodes.size(), 0);
            for (const tinygltf::Node& n : gltf_.nodes)
                for (int c : n.children)
                    if (c >= 0 && std::size_t(c) < isChild.size())
                        isChild[std::size_t(c)] = 1;
            for (std::size_t i = 0; i < gltf_.nodes.size(); ++i)
                if (!isChild[i])
                    roots.push_back(int(i));
        }
        std::vector<std::pair<int, glm::dmat4>> result;
        for (int r : roots) result.emplace_back(r, glm::dmat4(1.0));
        return result;
    }

    // Depth-first over the node tree with an explicit stack: a chain of a million nodes
    // must not overflow the call stack. glTF requires a forest; a node reached a second
    // time (a cycle, or a node with two parents) is skipped, so a hostile graph can
    // neither loop forever nor multiply itself exponentially.
    void flatten(int rootNode, const glm::dmat4& rootMatrix)
    {
        std::vector<std::pair<int, glm::dmat4>> stack{{rootNode, rootMatrix}};
        while (!stack.empty()) {
            auto [index, parent] = stack.back();
            stack.pop_back();
            if (index < 0 || std::size_t(index) >= gltf_.nodes.size())
                fail("the node hierarchy refers to nodes[" + std::to_string(index) + "], which does not exist");
            const std::string what = indexed("nodes", std::size_t(index));
            if (visited_.empty())
                visited_.assign(gltf_.nodes.size(), 0);
            if (visited_[std::size_t(index)]) {
                warn(what + " is reached a second time (the node graph must be a tree); skipped there");
                continue;
            }
            visited_[std::size_t(index)] = 1;
            const tinygltf::Node& node = gltf_.nodes[std::size_t(index)];
            const glm::dmat4 world = parent * localMatrix(node, what);
            if (node.mesh >= 0)
                instantiate(node, what, world);
            for (auto c = node.children.rbegin(); c != node.children.rend(); ++c) stack.emplace_back(*c, world);
        }
    }

    void instantiate(const tinygltf::Node& node, const std::string& nodeWhat, const glm::dmat4& world)
    {
        const std::size_t meshIndex = std::size_t(node.mesh);
        if (meshIndex >= gltf_.meshes.size())
            fail(nodeWhat + ".mesh " + std::to_string(node.mesh) + " does not exist");
        const tinygltf::Mesh& mesh = gltf_.meshes[meshIndex];
        if (!meshCache_[meshIndex]) {
            std::vector<LocalPrimitive> primitives;
            for (std::size_t p = 0; p < mesh.primitives.size(); ++p)
                primitives.push_back(
                    loadPrimitive(mesh.primitives[p], indexed("meshes", meshIndex) + "." + indexed("primitives", p)));
            meshCache_[meshIndex] = std::move(primitives);
        }
        const std::string nodeName = node.name.empty() ? nodeWhat : node.name;
        const std::string meshName = mesh.name.empty() ? indexed("meshes", meshIndex) : mesh.name;
        for (std::size_t p = 0; p < meshCache_[meshIndex]->size(); ++p) {
            const LocalPrimitive& local = (*meshCache_[meshIndex])[p];
            if (!local.mesh)
                continue;
            const std::string name = nodeName + "/" + meshName + "#" + std::to_string(p);
            requireVertexBudget(local.mesh->vertexCount(), name);
            requireIndexBudget(local.mesh->indices.size(), name);
            MeshInstance instance;
            instance.name = name;
            instance.mesh = *local.mesh;
            instance.materialIndex = local.material;
            instance.worldMatrix = glm::mat4(world);
            if (!transformMesh(instance.mesh, instance.worldMatrix)) {
                warn(nodeWhat + " has a singular or non-finite world transform; " + name + " skipped");
                continue;
            }
            verticesUsed_ += instance.mesh.vertexCount();
            indicesUsed_ += instance.mesh.indices.size();
            out_.instances.push_back(std::move(instance));
        }
    }

    // ---- materials and textures ------------------------------------------------------

    // The ModelData texture for image `source` read as sRGB or linear, decoded on first
    // use; -1 (with one warning per image) when it cannot be had.
    int decodedTexture(std::size_t source, bool srgb)
    {
        const auto key = std::make_pair(source, srgb);
        if (const auto it = textureSlots_.find(key); it != textureSlots_.end())
            return it->second;
        int& slot = textureSlots_[key];
        slot = -1;
        const sd::ImageSource& image = images_[source];
        if (failedImages_.count(source))
            return slot;
        const auto fallBack = [&](const std::string& problem) {
            warn("texture image " + image.label + " " + problem + "; textures using it fall back to their factors");
            failedImages_.insert(source);
            return slot;
        };
        if (image.encoded.empty())
            return fallBack(image.problem);

        std::optional<TextureImage> decoded;
        if (const auto other = textureSlots_.find(std::make_pair(source, !srgb));
            other != textureSlots_.end() && other->second >= 0) {
            decoded = out_.textures[std::size_t(other->second)]; // same pixels, other interpretation
        } else {
            std::string problem, note;
            decoded = sd::decodeImage(image.encoded, options_.maxTextureDimension, problem, note);
            if (!decoded)
                return fallBack(problem);
            if (!note.empty())
                warn("texture image " + image.label + " " + note);
        }
        const std::uint64_t bytes = decoded->rgba8.size();
        if (bytes > options_.maxTextureBytes - std::min(textureBytesUsed_, options_.maxTextureBytes))
            return fallBack("would exceed the " + std::to_string(options_.maxTextureBytes) +
                            "-byte texture budget (ModelLoadOptions::maxTextureBytes); dropped");
        textureBytesUsed_ += bytes;
        decoded->name = image.name;
        decoded->srgb = srgb;
        out_.textures.push_back(std::move(*decoded));
        slot = int(out_.textures.size() - 1);
        return slot;
    }

    TextureRef textureRef(int textureIndex, int texCoord, bool srgb, const std::string& what)
    {
        if (textureIndex < 0)
            return {};
        if (std::size_t(textureIndex) >= gltf_.textures.size()) {
            warn(what + " refers to textures[" + std::to_string(textureIndex) + "], which does not exist; ignored");
            return {};
        }
        const int source = gltf_.textures[std::size_t(textureIndex)].source;
        if (source < 0 || std::size_t(source) >= images_.size()) {
            warn(what + ": textures[" + std::to_string(textureIndex) + "] has no image iblab can read; ignored");
            return {};
        }
        if (texCoord != 0 && texCoord != 1) {
            warn(what + " uses TEXCOORD_" + std::to_string(texCoord) + "; iblab reads sets 0 and 1, using 0");
            texCoord = 0;
        }
        TextureRef ref;
        ref.index = decodedTexture(std::size_t(source), srgb);
        ref.texCoord = texCoord;
        return ref;
    }

    PbrMaterial convertMaterial(std::size_t index)
    {
        const tinygltf::Material& m = gltf_.materials[index];
        const std::string what = indexed("materials", index);
        const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
        PbrMaterial p;
        p.name = m.name.empty() ? what : m.name;
        if (pbr.baseColorFactor.size() == 4)
            for (int c = 0; c < 4; ++c) p.baseColorFactor[c] = clamp01(pbr.baseColorFactor[std::size_t(c)], 1.0f);
        p.metallicFactor = clamp01(pbr.metallicFactor, 1.0f);
        p.roughnessFactor = clamp01(pbr.roughnessFactor, 1.0f);
        if (m.emissiveFactor.size() == 3)
            for (int c = 0; c < 3; ++c) p.emissiveFactor[c] = clamp01(m.emissiveFactor[std::size_t(c)], 0.0f);
        if (const auto ext = m.extensions.find("KHR_materials_emissive_strength"); ext != m.extensions.end()) {
            const tinygltf::Value& strength = ext->second.Get("emissiveStrength");
            const double s = strength.IsNumber() ? strength.GetNumberAsDouble() : 1.0;
            if (std::isfinite(s) && s >= 0.0)
                p.emissiveFactor *= float(s);
        }
        p.occlusionStrength = clamp01(m.occlusionTexture.strength, 1.0f);
        p.normalScale = std::isfinite(m.normalTexture.scale) ? float(m.normalTexture.scale) : 1.0f;
        if (m.alphaMode == "MASK")
            p.alphaMode = AlphaMode::Mask;
        else if (m.alphaMode == "BLEND")
            p.alphaMode = AlphaMode::Blend;
        else if (m.alphaMode != "OPAQUE")
            warn(what + ".alphaMode '" + m.alphaMode + "' is not OPAQUE, MASK or BLEND; OPAQUE used");
        p.alphaCutoff = std::isfinite(m.alphaCutoff) && m.alphaCutoff >= 0.0 ? float(m.alphaCutoff) : 0.5f;
        p.doubleSided = m.doubleSided;

        p.baseColorTexture = textureRef(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, true,
                                        what + ".baseColorTexture");
        p.metallicRoughnessTexture = textureRef(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                                                false, what + ".metallicRoughnessTexture");
        p.normalTexture = textureRef(m.normalTexture.index, m.normalTexture.texCoord, false, what + ".normalTexture");
        p.occlusionTexture = textureRef(m.occlusionTexture.index, m.occlusionTexture.texCoord, false,
                                        what + ".occlusionTexture");
        p.emissiveTexture = textureRef(m.emissiveTexture.index, m.emissiveTexture.texCoord, true, what + ".emissiveTexture");
        return p;
    }

    const std::string& path_;
    const ModelLoadOptions& options_;
    const tinygltf::Model& gltf_;
    const std::vector<sd::ImageSource>& images_;
    ModelData& out_;
    std::vector<std::optional<std::vector<LocalPrimitive>>> meshCache_;
    std::vector<char> visited_;
    std::map<std::pair<std::size_t, bool>, int> textureSlots_;
    std::set<std::size_t> failedImages_;
    std::uint64_t verticesUsed_ = 0;
    std::uint64_t indicesUsed_ = 0;
    std::uint64_t textureBytesUsed_ = 0;
};

// The glTF library must never touch the file system or decode images on its own: the
// document it gets is self-contained, and these callbacks make sure of it.
bool noFileExists(const std::string&, void*) { return false; }
std::string noExpand(const std::string& path, void*) { return path; }
bool noReadFile(std::vector<unsigned char>*, std::string* err, const std::string&, void*)
{
    if (err)
        *err += "iblab resolves files itself";
    return false;
}
bool noWriteFile(std::string*, const std::string&, const std::vector<unsigned char>&, void*) { return false; }
bool noImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*)
{
    return false;
}

// Maps the canonical document to tinygltf structs. The images are taken out of the JSON
// first: decoding them is ModelBuilder's job (non-fatal, budgeted), and the library
// would fail the whole load on an undecodable one. Releases doc.bin on the way (the
// library keeps its own copy), so memory peaks at two copies of the buffers, not three.
tinygltf::Model parseStructure(sd::GltfDocument& doc, std::vector<std::string>& warnings)
{
    nlohmann::json structure = doc.json;
    structure.erase("images");
    const std::string glb = sd::serializeGlb(structure, doc.bin);
    structure = nullptr;
    std::vector<std::uint8_t>().swap(doc.bin);

    tinygltf::TinyGLTF loader;
    loader.SetFsCallbacks(tinygltf::FsCallbacks{&noFileExists, &noExpand, &noReadFile, &noWriteFile, nullptr});
    loader.SetImageLoader(&noImage, nullptr);
    tinygltf::Model model;
    std::string err, warn;
    const bool ok = loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(glb.data()),
                                                static_cast<unsigned int>(glb.size()), "", tinygltf::REQUIRE_VERSION);
    if (!ok)
        throw Error(doc.path, "invalid glTF: " + oneLine(err.empty() ? "rejected by the glTF parser" : err));
    for (std::size_t start = 0; start < warn.size();) {
        const std::size_t end = std::min(warn.find('\n', start), warn.size());
        if (end > start)
            warnings.push_back(warn.substr(start, end - start));
        start = end + 1;
    }
    return model;
}

} // namespace

const PbrMaterial& ModelData::material(int index) const
{
    static const PbrMaterial defaultMaterial = [] {
        PbrMaterial m;
        m.name = "default";
        return m;
    }();
    return index >= 0 && std::size_t(index) < materials.size() ? materials[std::size_t(index)] : defaultMaterial;
}

ModelData loadGltfModel(const std::string& path, const ModelLoadOptions& options)
{
    // Anything else (a JSON type surprise deep in a library) still ends as one clean line
    // naming the file rather than escaping as an unknown exception.
    return rethrowAsError(path, "loading; lower the ModelLoadOptions budgets", "cannot be loaded", [&] {
        sd::GltfDocument doc = sd::readGltfDocument(path, {options.maxInputBytes, options.maxJsonDepth});
        ModelData model;
        model.warnings = std::move(doc.warnings);
        const tinygltf::Model gltf = parseStructure(doc, model.warnings);
        ModelBuilder(path, options, gltf, doc.images, model).build();
        if (model.instances.empty())
            model.warnings.push_back("the default scene has no triangles to show");
        return model;
    });
}

} // namespace iblab
