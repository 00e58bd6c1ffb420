#pragma once
// PRIVATE to iblab_scene (includes nlohmann/json): the container layer shared by the
// loader, the exporter and the test-model generator.
//
// readGltfDocument() turns any .gltf (+ its files) or .glb into one canonical,
// self-contained, validated form:
//   - json: the parsed document, with ALL buffers merged into a single buffer 0 whose
//     bytes are `bin` (each source buffer 4-byte aligned in it) and every bufferView
//     rebased onto it (buffer 0, byteOffset shifted) after checking its range; images
//     are left exactly as written (uri or bufferView);
//   - images: each image's encoded bytes (from its file, data URI or bufferView), or the
//     reason they are unavailable.
// Everything a hostile file could use to crash a parser, escape the model's folder or
// exhaust memory is checked here, before the glTF library sees the document: the container
// by glb_container.hpp, the files and data URIs by gltf_resources.hpp, the JSON and the
// byte ranges by gltf_document.cpp.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace iblab::scene_detail {

struct DocumentLimits {
    std::uint64_t maxInputBytes = 0;
    int maxJsonDepth = 0;
};

struct ImageSource {
    std::string name;                  // the file name as written (percent-decoded), the image's name, or "images[2]"
    std::string label;                 // "'wood.png' (images[2])", for messages
    std::string uri;                   // the external file's URI as written; empty otherwise
    std::vector<std::uint8_t> encoded; // PNG/JPEG/... bytes; empty when unavailable
    std::string mimeType;              // as declared, or sniffed from the bytes
    std::string problem;               // why `encoded` is empty
};

struct GltfDocument {
    std::string path; // as given: the subject of every Error
    nlohmann::json json;
    std::vector<std::uint8_t> bin;
    std::vector<ImageSource> images; // parallel to json["images"]
    std::vector<std::string> warnings;
};

GltfDocument readGltfDocument(const std::string& path, const DocumentLimits& limits);

// Appends bytes to `bin` (4-byte aligned, as accessors need) as a new bufferView of
// buffer 0 and returns its index. target: 0 (none), 34962 (vertices), 34963 (indices).
int appendBufferView(nlohmann::json& json, std::vector<std::uint8_t>& bin, const std::uint8_t* data, std::size_t size,
                     int target = 0, int byteStride = 0);

// Points the document's single buffer at `bin`: buffers = [{byteLength}] (with a base64
// data URI when `embedAsDataUri`), or no buffers at all when bin is empty.
void setSingleBuffer(nlohmann::json& json, const std::vector<std::uint8_t>& bin, bool embedAsDataUri);

// "1 byte", "12 bytes": how messages count bytes.
std::string bytesText(std::uint64_t n);

// "buffers[3]": how messages name an element of a top-level array.
std::string indexed(const char* array, std::size_t index);

// ".glb" for "Model.GLB": the extension, lower-cased.
std::string lowerExtension(const std::string& path);

// "image/png", "image/jpeg", "image/webp", "image/ktx2" from magic bytes; "" otherwise.
std::string sniffImageMimeType(const std::vector<std::uint8_t>& bytes);

} // namespace iblab::scene_detail
