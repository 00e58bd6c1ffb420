#pragma once
// glTF 2.0 models (.gltf with its files, or .glb): loading into flat, world-space
// MeshData + PbrMaterial + decoded textures, and exporting a copy with tuned materials.
//
// Artists drop whatever files they have, so the loader treats every file as hostile:
// it never crashes, hangs or allocates beyond ModelLoadOptions' budgets, and fails with
// iblab::Error carrying ONE line that names the file and the problem, e.g.
//   "model.gltf: meshes[0].primitives[0] POSITION (accessors[0]) needs 1000 elements of
//    12 bytes, stride 12, from byte 0 of bufferViews[0], which has only 36 bytes: the
//    accessor is out of range"   (one line in reality)
// What it checks itself, rather than trusting the glTF library: the GLB container
// (magic, version, declared and chunk lengths), JSON nesting depth (before any parser
// recurses), that every external URI stays inside the model's folder (no "..", no
// absolute paths, no schemes), buffer and data-URI sizes against the byte budget before
// decoding or reading, bufferView and accessor ranges (offset + stride * (count - 1) +
// element size), index values against the vertex count, node graph cycles.
// Problems that leave the model usable are warnings instead: a texture image that is
// missing or cannot be decoded (its slot falls back to the factor; the warning names the
// file), unsupported primitive modes (points, lines: skipped), ignored extensions,
// oversized textures (downsampled).
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/material.hpp"
#include "scene/mesh.hpp"

namespace iblab {

struct ModelLoadOptions {
    // Vertices after flattening the node hierarchy (a mesh used by n nodes counts n
    // times). 4M vertices of MeshData is about 250 MB. Over budget: Error.
    std::uint64_t maxVertices = 4'000'000;
    // Triangle-list indices after flattening (8M triangles, 96 MB). Over budget: Error.
    std::uint64_t maxIndices = 24'000'000;
    // Bytes read from disk or decoded from data URIs, all together: the .gltf/.glb
    // itself, buffers and encoded image files. Checked against declared sizes and file
    // sizes BEFORE reading or decoding anything. Over budget: Error. At most 4 GiB - 1
    // is honoured (the GLB format's own limit).
    std::uint64_t maxInputBytes = 512ull << 20;
    // Textures wider or taller than this are box-filtered down by a power of two while
    // they are read (scanline by scanline, so the full-size image is never held), with a
    // warning. Images claiming more than 8x this (65536 by default) in either dimension
    // are not decoded at all: warning, the slot falls back to its factor.
    int maxTextureDimension = 8192;
    // Decoded RGBA8 bytes of all textures together. Textures that would exceed it are
    // dropped with a warning (their slots fall back to the factors), not an Error: the
    // model stays viewable.
    std::uint64_t maxTextureBytes = 512ull << 20;
    // JSON nesting depth; deeper documents fail before any parser sees them (parsers
    // and the glTF library's "extras" conversion recurse per level).
    int maxJsonDepth = 64;
};

struct MeshInstance {
    std::string name;      // "node/mesh#primitive", for UI and messages
    MeshData mesh;         // WORLD space: worldMatrix has already been applied
    int materialIndex = -1; // into ModelData::materials; -1 = glTF's default material
    glm::mat4 worldMatrix{1.0f}; // the node's world transform, recorded for reference only
};

struct ModelData {
    std::vector<MeshInstance> instances; // one per (node, primitive) of the default scene
    std::vector<PbrMaterial> materials;  // index-compatible with the file's "materials"
    std::vector<TextureImage> textures;  // decoded textures the materials reference
    Bounds bounds;                       // of all instances, world space
    std::vector<std::string> warnings;   // one line each

    // materials[index], or the glTF default material for -1 (and any other bad index).
    const PbrMaterial& material(int index) const;
};

// Loads the default scene (the file's "scene", else scenes[0], else all root nodes) of
// a .gltf or .glb; the container type is detected from the content, not the extension.
// Triangles only: TRIANGLES as is, TRIANGLE_STRIP and TRIANGLE_FAN converted, points
// and lines skipped with a warning. Missing normals are computed (smooth, see
// computeSmoothNormals; zero or NaN normals in the file are patched the same way);
// missing or unusable tangents are generated (generateTangents) for every primitive,
// normal map or not, so all instances share one vertex layout. TEXCOORD_1 is kept as
// uvs1 when present. Texcoords may be float or (normalized) 8/16-bit integers, and so
// may positions, normals and tangents (KHR_mesh_quantization). Primitives with
// non-finite positions, and instances whose world transform is singular, are skipped
// with a warning. Failures: iblab::Error (see above); nothing is returned half-built.
ModelData loadGltfModel(const std::string& path, const ModelLoadOptions& options = {});
// loadGltfModel for a caller that draws it (the GUI, render, bench): a model whose scene has
// no triangles (every primitive skipped, or only empty nodes) is an iblab::Error naming the
// file, "nothing to draw", and the warnings that say why.
ModelData loadDrawableGltfModel(const std::string& path, const ModelLoadOptions& options = {});

struct MaterialEdit {
    // Index into the source's "materials"; -1 adds a material for the primitives that
    // have none (they rendered with the default material).
    int materialIndex = -1;
    PbrMaterial material;
};

// Writes a copy of the model at sourcePath to outPath with the edited materials' factors
// replaced: baseColorFactor, metallicFactor, roughnessFactor, emissiveFactor (> 1 via
// KHR_materials_emissive_strength), occlusion strength and normal scale (where the
// material has those textures), alphaMode, alphaCutoff, doubleSided. Texture slots,
// names and everything else in the file (extensions, extras, animations, skins,
// cameras) are kept as they are.
// The copy is self-contained: ".glb" gets all buffers merged into its BIN chunk and
// every image embedded; ".gltf" gets the same single buffer as a base64 data URI and
// the images as buffer views of it. A texture image that is missing from the source
// keeps its URI (a warning says so). The file is written atomically (temporary file +
// rename): a failure leaves any existing outPath untouched. The source is read with the
// same checks and budgets as loadGltfModel(); sourcePath == outPath is fine.
// Returns warnings (one line each); throws iblab::Error for a bad source, a material
// index out of range, an extension other than .glb/.gltf, or a failed write.
std::vector<std::string> exportGltfWithMaterials(const std::string& sourcePath, const std::string& outPath,
                                                 const std::vector<MaterialEdit>& edits,
                                                 const ModelLoadOptions& options = {});

// The single-material case of exportGltfWithMaterials().
std::vector<std::string> exportGltfWithMaterial(const std::string& sourcePath, const std::string& outPath,
                                                int materialIndex, const PbrMaterial& tuned);

} // namespace iblab
