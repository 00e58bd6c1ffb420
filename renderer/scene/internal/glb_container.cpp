// The GLB container: parsing a file's header and chunks, and serialising a document and
// its buffer as a .glb. Byte order is little-endian throughout, as the format says.
#include "scene/internal/glb_container.hpp"

#include "io/error.hpp"
#include "scene/internal/gltf_document.hpp"

namespace iblab::scene_detail {
namespace {

constexpr std::uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr std::uint32_t kChunkJson = 0x4E4F534A; // "JSON"
constexpr std::uint32_t kChunkBin = 0x004E4942;  // "BIN\0"

std::uint32_t readU32(const std::uint8_t* p)
{
    return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24;
}

void appendU32(std::string& out, std::uint32_t v)
{
    for (int i = 0; i < 4; ++i) out += char((v >> (8 * i)) & 0xFF);
}

} // namespace

bool startsWithGlbMagic(const std::vector<std::uint8_t>& file)
{
    return file.size() >= 4 && readU32(file.data()) == kGlbMagic;
}

GlbChunks parseGlb(const std::string& path, const std::vector<std::uint8_t>& file, std::vector<std::string>& warnings)
{
    if (file.size() < 12)
        throw Error(path, "truncated GLB: " + bytesText(file.size()) + ", the GLB header alone needs 12");
    const std::uint32_t version = readU32(&file[4]);
    if (version != 2)
        throw Error(path, "GLB version " + std::to_string(version) + " is not supported (only glTF 2.0)");
    const std::uint64_t declared = readU32(&file[8]);
    if (declared > file.size())
        throw Error(path, "truncated GLB: the header declares " + bytesText(declared) + " but the file has " +
                              bytesText(file.size()));
    if (declared < file.size())
        warnings.push_back(bytesText(file.size() - declared) + " after the end of the GLB data, ignored");

    GlbChunks chunks;
    bool haveJson = false;
    std::uint64_t offset = 12;
    for (int index = 0; offset < declared; ++index) {
        if (offset + 8 > declared)
            throw Error(path, "truncated GLB: chunk " + std::to_string(index) + "'s header at byte " + std::to_string(offset) +
                                  " runs past the end of the " + bytesText(declared) + " GLB");
        const std::uint64_t length = readU32(&file[offset]);
        const std::uint32_t type = readU32(&file[offset + 4]);
        const std::uint64_t dataStart = offset + 8;
        if (length > declared - dataStart)
            throw Error(path, "GLB chunk " + std::to_string(index) + " declares a length of " + bytesText(length) +
                                  " but only " + bytesText(declared - dataStart) + " follow its header");
        if (length % 4 != 0)
            warnings.push_back("GLB chunk " + std::to_string(index) + "'s length " + std::to_string(length) +
                               " is not a multiple of 4 (the GLB spec requires padding)");
        if (index == 0) {
            if (type != kChunkJson)
                throw Error(path, "the first GLB chunk is not JSON");
            chunks.jsonText = std::string_view(reinterpret_cast<const char*>(&file[dataStart]), std::size_t(length));
            haveJson = true;
        } else if (type == kChunkBin && !chunks.hasBin) {
            chunks.bin = &file[dataStart];
            chunks.binSize = std::size_t(length);
            chunks.hasBin = true;
        } // Other chunk types are to be ignored, says the spec.
        offset = dataStart + length;
    }
    if (!haveJson)
        throw Error(path, "the GLB has no JSON chunk");
    return chunks;
}

std::string serializeGlb(const nlohmann::json& root, const std::vector<std::uint8_t>& bin)
{
    std::string text = root.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    text.resize((text.size() + 3) / 4 * 4, ' ');
    const std::size_t binPadded = (bin.size() + 3) / 4 * 4;
    const std::size_t total = 12 + 8 + text.size() + (bin.empty() ? 0 : 8 + binPadded);
    if (total > kMaxGlbBytes)
        throw Error("GLB", "the model needs " + bytesText(total) + ", more than a GLB can hold (4 GiB)");
    std::string out;
    out.reserve(total);
    appendU32(out, kGlbMagic);
    appendU32(out, 2);
    appendU32(out, std::uint32_t(total));
    appendU32(out, std::uint32_t(text.size()));
    appendU32(out, kChunkJson);
    out += text;
    if (!bin.empty()) {
        appendU32(out, std::uint32_t(binPadded));
        appendU32(out, kChunkBin);
        out.append(reinterpret_cast<const char*>(bin.data()), bin.size());
        out.append(binPadded - bin.size(), '\0');
    }
    return out;
}

} // namespace iblab::scene_detail
