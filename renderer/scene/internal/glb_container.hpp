#pragma once
// PRIVATE to iblab_scene: the binary glTF container (GLB) in both directions. Reading walks
// the header and chunks of a file already in memory with every declared length checked
// against what the file really holds, and hands back views into it; writing lays out a
// complete .glb from a document and its single buffer. What the JSON says is not looked at
// here (gltf_document.hpp does that).
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace iblab::scene_detail {

// The GLB header stores lengths in 32 bits, and the glTF library takes a 32-bit size: no
// model, and no input budget, may be larger.
inline constexpr std::uint64_t kMaxGlbBytes = 0xFFFFFFFFull;

// True when the bytes start with the GLB magic "glTF" (the container type is told from the
// content, never from the file's extension).
bool startsWithGlbMagic(const std::vector<std::uint8_t>& file);

// The chunks of a GLB: views into the file's bytes, valid while those live.
struct GlbChunks {
    std::string_view jsonText;
    const std::uint8_t* bin = nullptr;
    std::size_t binSize = 0;
    bool hasBin = false;
};

// Walks the container (https://registry.khronos.org/glTF/specs/2.0/glTF-2.0.html#binary-gltf-layout).
// Throws iblab::Error naming `path` for a truncated or malformed one; bytes after the
// declared end, unpadded chunks and the like are `warnings`.
GlbChunks parseGlb(const std::string& path, const std::vector<std::uint8_t>& file, std::vector<std::string>& warnings);

// A complete .glb: header, JSON chunk (space-padded), BIN chunk (zero-padded; omitted
// when bin is empty). The json's buffer 0, if any, must describe `bin`.
std::string serializeGlb(const nlohmann::json& json, const std::vector<std::uint8_t>& bin);

} // namespace iblab::scene_detail
