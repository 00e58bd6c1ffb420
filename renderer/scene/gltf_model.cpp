// glTF -> ModelData. readGltfDocument() has already checked the container, the JSON and
// every byte range down to bufferViews; the glTF library then maps the JSON to structs
// (from memory, with no file system access). This file reads each primitive through
// AccessorReader (gltf_accessors.hpp), completes its normals and tangents, flattens the
// node tree into world-space instances, and leaves materials and textures to
// convertMaterials (gltf_materials.hpp).
#include "scene/gltf_model.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <tiny_gltf.h>

#include "io/error.hpp"
#include "scene/internal/glb_container.hpp"
#include "scene/internal/gltf_accessors.hpp"
#include "scene/internal/gltf_document.hpp"
#include "scene/internal/gltf_materials.hpp"

namespace iblab {
namespace {

namespace sd = scene_detail;

using sd::indexed;

bool finiteVec(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// A primitive read once in its mesh's local space; instances copy and transform it.
struct LocalPrimitive {
    std::optional<MeshData> mesh; // nullopt: skipped (a warning said why)
    int material = -1;
};

class ModelBuilder {
public:
    ModelBuilder(const std::string& path, const ModelLoadOptions& options, const tinygltf::Model& gltf,
                 const std::vector<sd::ImageSource>& images, ModelData& out)
        : path_(path), options_(options), gltf_(gltf), images_(images), out_(out), reader_(path, gltf), budget_(path, options),
          meshCache_(gltf.meshes.size())
    {
    }

    void build()
    {
        sd::convertMaterials(options_, gltf_, images_, out_);
        for (const auto& [node, world] : sceneRoots()) flatten(node, world);
        for (const MeshInstance& instance : out_.instances) out_.bounds.extend(computeBounds(instance.mesh));
    }

private:
    [[noreturn]] void fail(const std::string& problem) const { throw Error(path_, problem); }
    void warn(const std::string& text) { out_.warnings.push_back(text); }


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
            budget_.requireIndices(3 * (n - 2), what);
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
        const std::size_t count = reader_.accessor(positionIndex, what + " POSITION").count;
        budget_.requireVertices(count, what);

        MeshData mesh;
        mesh.positions = reader_.readVectors<3>(positionIndex, count, what + " POSITION");
        if (!std::all_of(mesh.positions.begin(), mesh.positions.end(), finiteVec)) {
            warn(what + " has non-finite positions; skipped");
            return result;
        }
        std::vector<std::uint32_t> source;
        if (p.indices >= 0) {
            source = reader_.readIndices(p.indices, what + " indices", budget_);
            for (std::size_t i = 0; i < source.size(); ++i)
                if (source[i] >= count)
                    fail(what + " indices: index " + std::to_string(source[i]) + " (at position " + std::to_string(i) +
                         ") is past the " + std::to_string(count) + " vertices");
        } else {
            budget_.requireIndices(count, what);
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
            mesh.normals = reader_.readVectors<3>(normalIndex, count, what + " NORMAL");
        if (uv0 >= 0)
            mesh.uvs = reader_.readVectors<2>(uv0, count, what + " TEXCOORD_0");
        if (uv1 >= 0)
            mesh.uvs1 = reader_.readVectors<2>(uv1, count, what + " TEXCOORD_1");
        // The spec: without normals, the file's tangents must be ignored.
        if (tangentIndex >= 0 && normalIndex >= 0)
            mesh.tangents = reader_.readVectors<4>(tangentIndex, count, what + " TANGENT");
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
            budget_.requireVertices(local.mesh->vertexCount(), name);
            budget_.requireIndices(local.mesh->indices.size(), name);
            MeshInstance instance;
            instance.name = name;
            instance.mesh = *local.mesh;
            instance.materialIndex = local.material;
            instance.worldMatrix = glm::mat4(world);
            if (!transformMesh(instance.mesh, instance.worldMatrix)) {
                warn(nodeWhat + " has a singular or non-finite world transform; " + name + " skipped");
                continue;
            }
            budget_.take(instance.mesh.vertexCount(), instance.mesh.indices.size());
            out_.instances.push_back(std::move(instance));
        }
    }

    const std::string& path_;
    const ModelLoadOptions& options_;
    const tinygltf::Model& gltf_;
    const std::vector<sd::ImageSource>& images_;
    ModelData& out_;
    sd::AccessorReader reader_;
    sd::GeometryBudget budget_;
    std::vector<std::optional<std::vector<LocalPrimitive>>> meshCache_;
    std::vector<char> visited_;
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

ModelData loadDrawableGltfModel(const std::string& path, const ModelLoadOptions& options)
{
    ModelData model = loadGltfModel(path, options);
    if (model.instances.empty()) {
        std::string problem = "nothing to draw";
        for (const std::string& warning : model.warnings) problem += "; " + warning;
        throw Error(path, problem);
    }
    return model;
}

} // namespace iblab