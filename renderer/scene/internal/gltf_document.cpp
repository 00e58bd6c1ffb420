// The canonical document: the JSON checked (nesting depth before any parser recurses, the
// asset version, required extensions) and every buffer merged into one, bufferView ranges
// checked and rebased onto it, each image's encoded bytes gathered; plus the small writers
// the exporter and the test-model generator build documents with.
#include "scene/internal/gltf_document.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <optional>
#include <string_view>

#include "io/error.hpp"
#include "scene/internal/glb_container.hpp"
#include "scene/internal/gltf_resources.hpp"

namespace iblab::scene_detail {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// True when arrays/objects nest deeper than maxDepth. A plain scan with no recursion and
// no allocation, run before any JSON parser: parsers (and the glTF library's conversion
// of "extras") recurse once per level, and 100000 '[' would overflow the stack.
bool nestsDeeperThan(std::string_view text, int maxDepth)
{
    int depth = 0;
    bool inString = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (inString) {
            if (c == '\\')
                ++i;
            else if (c == '"')
                inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            if (++depth > maxDepth)
                return true;
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
    return false;
}

// The first bytes of a file, for "this is not glTF" messages: text when printable, hex
// otherwise.
std::string describeStart(const std::vector<std::uint8_t>& bytes)
{
    const std::size_t n = std::min<std::size_t>(bytes.size(), 8);
    const bool printable = std::all_of(bytes.begin(), bytes.begin() + std::ptrdiff_t(n),
                                       [](std::uint8_t b) { return b >= 0x20 && b < 0x7F; });
    std::string out;
    if (printable) {
        out = "'" + std::string(bytes.begin(), bytes.begin() + std::ptrdiff_t(n)) + "'";
    } else {
        static const char* digits = "0123456789ABCDEF";
        for (std::size_t i = 0; i < n; ++i) {
            out += i ? " " : "bytes ";
            out += digits[bytes[i] >> 4];
            out += digits[bytes[i] & 15];
        }
    }
    return out;
}

// Typed access to JSON members, with errors that say where in the document they are.
class Members {
public:
    explicit Members(const std::string& path) : path_(path) {}

    [[noreturn]] void fail(const std::string& problem) const { throw Error(path_, problem); }

    // root[key] when it is an array; an empty array when absent.
    const json& array(const json& object, const char* key, const std::string& where) const
    {
        static const json empty = json::array();
        const auto it = object.find(key);
        if (it == object.end())
            return empty;
        if (!it->is_array())
            fail(where + key + " is not an array");
        return *it;
    }

    const json& object(const json& array, std::size_t index, const std::string& where) const
    {
        if (!array[index].is_object())
            fail(where + " is not an object");
        return array[index];
    }

    // A non-negative integer member; `fallback` when absent (nullopt: required).
    std::uint64_t count(const json& object, const char* key, const std::string& where,
                        std::optional<std::uint64_t> fallback) const
    {
        const auto it = object.find(key);
        if (it == object.end()) {
            if (!fallback)
                fail(where + "." + key + " is missing");
            return *fallback;
        }
        if (it->is_number_unsigned())
            return it->get<std::uint64_t>();
        // Some writers emit integral values as 1024.0.
        if (it->is_number_float()) {
            const double v = it->get<double>();
            if (v >= 0.0 && v <= 9007199254740992.0 && v == double(std::uint64_t(v)))
                return std::uint64_t(v);
        }
        fail(where + "." + key + " is not a non-negative integer");
    }

    const std::string* string(const json& object, const char* key, const std::string& where) const
    {
        const auto it = object.find(key);
        if (it == object.end())
            return nullptr;
        if (!it->is_string())
            fail(where + "." + key + " is not a string");
        return it->get_ptr<const std::string*>();
    }

private:
    const std::string& path_;
};

// Extensions whose absence breaks geometry or textures outright; when a file REQUIRES
// one of these, loading fails with a clear reason rather than showing garbage.
bool isUndecodableExtension(const std::string& name)
{
    static const char* const names[] = {"KHR_draco_mesh_compression", "EXT_meshopt_compression", "KHR_meshopt_compression",
                                        "KHR_texture_basisu", "EXT_texture_webp", "EXT_texture_avif"};
    return std::find(std::begin(names), std::end(names), name) != std::end(names);
}

void checkAssetAndExtensions(const Members& m, const json& root, std::vector<std::string>& warnings)
{
    const auto asset = root.find("asset");
    if (asset == root.end() || !asset->is_object())
        m.fail("the \"asset\" object is missing: not a glTF 2.0 document");
    const std::string* version = m.string(*asset, "version", "asset");
    if (!version)
        m.fail("asset.version is missing: not a glTF 2.0 document");
    if (version->rfind("2.", 0) != 0)
        m.fail("glTF version '" + *version + "' is not supported (only 2.x)");

    static const char* const handled[] = {"KHR_mesh_quantization", "KHR_materials_emissive_strength"};
    std::string ignored;
    for (const char* key : {"extensionsRequired", "extensionsUsed"}) {
        const json& list = m.array(root, key, "");
        for (const json& e : list) {
            if (!e.is_string())
                continue;
            const std::string name = e.get<std::string>();
            if (std::find(std::begin(handled), std::end(handled), name) != std::end(handled))
                continue;
            if (std::string_view(key) == "extensionsRequired" && isUndecodableExtension(name))
                m.fail("requires the extension " + name + ", which iblab cannot decode");
            if (ignored.find(name) == std::string::npos)
                ignored += (ignored.empty() ? "" : ", ") + name;
        }
    }
    if (!ignored.empty())
        warnings.push_back("ignores the extensions " + ignored + "; the model may look different elsewhere");
}

// Reads every buffer into one contiguous `bin` (4-byte aligned pieces) and returns where
// each source buffer starts in it.
std::vector<std::uint64_t> mergeBuffers(const Members& m, GltfDocument& doc, const fs::path& folder, const GlbChunks* glb,
                                        InputBudget& budget)
{
    const json& buffers = m.array(doc.json, "buffers", "");
    std::vector<std::uint64_t> lengths(buffers.size()), offsets(buffers.size());
    std::uint64_t total = 0;
    for (std::size_t i = 0; i < buffers.size(); ++i) {
        const json& b = m.object(buffers, i, indexed("buffers", i));
        lengths[i] = m.count(b, "byteLength", indexed("buffers", i), std::nullopt);
        // Declared sizes are checked first, so that a buffer claiming 1 GB fails here,
        // before a single byte of it is read or decoded.
        if (lengths[i] > budget.limit())
            m.fail(indexed("buffers", i) + " declares " + bytesText(lengths[i]) + ", more than the " +
                   bytesText(budget.limit()) + " input budget (ModelLoadOptions::maxInputBytes)");
        offsets[i] = total;
        total += (lengths[i] + 3) / 4 * 4;
        if (total > kMaxGlbBytes)
            m.fail("the buffers add up to more than 4 GiB");
    }
    doc.bin.reserve(std::size_t(total));

    for (std::size_t i = 0; i < buffers.size(); ++i) {
        const std::string where = indexed("buffers", i);
        const json& b = buffers[i];
        const std::string* uri = m.string(b, "uri", where);
        std::vector<std::uint8_t> bytes;
        if (!uri) {
            if (!glb || i != 0)
                m.fail(where + " has no uri (only the first buffer of a .glb may omit it)");
            if (!glb->hasBin)
                m.fail(where + " refers to the GLB's BIN chunk, but the file has none");
            if (lengths[i] > glb->binSize)
                m.fail(where + " declares " + bytesText(lengths[i]) + " but the GLB BIN chunk holds " +
                       bytesText(glb->binSize));
            doc.bin.insert(doc.bin.end(), glb->bin, glb->bin + lengths[i]);
        } else if (const auto data = parseDataUri(*uri)) {
            bytes = decodeDataUri(*data, doc.path, where, budget);
            if (bytes.size() < lengths[i])
                m.fail(where + "'s data URI holds " + bytesText(bytes.size()) + ", its byteLength says " +
                       std::to_string(lengths[i]));
            bytes.resize(std::size_t(lengths[i]));
        } else {
            std::string problem;
            const auto file = resolveInsideFolder(folder, *uri, problem);
            if (!file)
                m.fail(where + ".uri " + quoteUri(*uri) + " " + problem);
            const std::uint64_t onDisk = fileSize(*file);
            budget.take(doc.path, where + " " + quoteUri(*uri), std::min(onDisk, lengths[i]));
            auto read = readFilePrefix(*file, lengths[i], problem);
            if (!read)
                m.fail(where + ": the file " + quoteUri(*uri) + " " + problem);
            if (read->size() < lengths[i])
                m.fail(where + ": the file " + quoteUri(*uri) + " has " + bytesText(read->size()) +
                       ", its byteLength says " + std::to_string(lengths[i]));
            bytes = std::move(*read);
        }
        doc.bin.insert(doc.bin.end(), bytes.begin(), bytes.end());
        doc.bin.resize(std::size_t(offsets[i] + (lengths[i] + 3) / 4 * 4), 0);
    }
    // The offsets of the pieces, followed by their lengths, for rebasing bufferViews.
    offsets.insert(offsets.end(), lengths.begin(), lengths.end());
    return offsets;
}

// Checks every bufferView's range against its buffer and rebases it onto the merged
// buffer 0.
void rebaseBufferViews(const Members& m, json& root, const std::vector<std::uint64_t>& offsetsThenLengths)
{
    const std::size_t bufferCount = offsetsThenLengths.size() / 2;
    if (!root.contains("bufferViews"))
        return;
    json& views = root["bufferViews"];
    if (!views.is_array())
        m.fail("bufferViews is not an array");
    for (std::size_t i = 0; i < views.size(); ++i) {
        const std::string where = indexed("bufferViews", i);
        json& v = views[i];
        if (!v.is_object())
            m.fail(where + " is not an object");
        const std::uint64_t buffer = m.count(v, "buffer", where, std::nullopt);
        if (buffer >= bufferCount)
            m.fail(where + ".buffer " + std::to_string(buffer) + " does not exist (there are " +
                   std::to_string(bufferCount) + " buffers)");
        const std::uint64_t offset = m.count(v, "byteOffset", where, 0);
        const std::uint64_t length = m.count(v, "byteLength", where, std::nullopt);
        const std::uint64_t bufferLength = offsetsThenLengths[bufferCount + buffer];
        if (offset > bufferLength || length > bufferLength - offset)
            m.fail(where + " (bytes " + std::to_string(offset) + ".." + std::to_string(offset + length) +
                   ") runs past the end of " + indexed("buffers", buffer) + " (" + bytesText(bufferLength) + ")");
        const std::uint64_t stride = m.count(v, "byteStride", where, 0);
        if (v.contains("byteStride") && (stride < 4 || stride > 252 || stride % 4 != 0))
            m.fail(where + ".byteStride " + std::to_string(stride) + " is not a multiple of 4 in 4..252");
        v["buffer"] = 0;
        v["byteOffset"] = offsetsThenLengths[buffer] + offset;
    }
}

void readImages(const Members& m, GltfDocument& doc, const fs::path& folder, InputBudget& budget)
{
    const json& images = m.array(doc.json, "images", "");
    const json& views = m.array(doc.json, "bufferViews", "");
    doc.images.resize(images.size());
    for (std::size_t i = 0; i < images.size(); ++i) {
        const std::string where = indexed("images", i);
        const json& image = m.object(images, i, where);
        ImageSource& source = doc.images[i];
        const std::string* uri = m.string(image, "uri", where);
        const std::string* name = m.string(image, "name", where);
        const std::string* mime = m.string(image, "mimeType", where);
        if (mime)
            source.mimeType = *mime;
        const bool isData = uri && parseDataUri(*uri).has_value();
        if (uri && !isData) {
            source.uri = *uri;
            source.name = percentDecode(*uri);
        } else {
            source.name = name && !name->empty() ? *name : where;
        }
        source.label = source.name == where ? where : quoteUri(source.name) + " (" + where + ")";

        if (image.contains("bufferView")) {
            const std::uint64_t view = m.count(image, "bufferView", where, std::nullopt);
            if (view >= views.size())
                m.fail(where + ".bufferView " + std::to_string(view) + " does not exist");
            const std::uint64_t offset = views[view].at("byteOffset").get<std::uint64_t>(); // rebased and checked
            const std::uint64_t length = views[view].at("byteLength").get<std::uint64_t>();
            source.encoded.assign(doc.bin.begin() + std::ptrdiff_t(offset), doc.bin.begin() + std::ptrdiff_t(offset + length));
        } else if (isData) {
            source.encoded = decodeDataUri(*parseDataUri(*uri), doc.path, where, budget);
            if (source.mimeType.empty())
                source.mimeType = parseDataUri(*uri)->mimeType;
        } else if (uri) {
            std::string problem;
            if (const auto file = resolveInsideFolder(folder, *uri, problem)) {
                const std::uint64_t size = fileSize(*file);
                budget.take(doc.path, where + " " + quoteUri(*uri), size);
                if (auto read = readFilePrefix(*file, size, problem))
                    source.encoded = std::move(*read);
            }
            source.problem = problem;
        } else {
            source.problem = "has neither a uri nor a bufferView";
        }
        if (source.encoded.empty() && source.problem.empty())
            source.problem = "is empty";
        if (source.mimeType.empty())
            source.mimeType = sniffImageMimeType(source.encoded);
    }
}

} // namespace

GltfDocument readGltfDocument(const std::string& path, const DocumentLimits& limits)
{
    GltfDocument doc;
    doc.path = path;
    InputBudget budget(limits.maxInputBytes);
    const Members m(doc.path);

    fs::path folder = fs::path(path).parent_path();
    if (folder.empty())
        folder = ".";
    std::string problem;
    const std::uint64_t size = fileSize(path);
    budget.take(path, "the file", size);
    auto file = readFilePrefix(path, size, problem);
    if (!file)
        throw Error(path, problem == "not found" ? "no such file" : problem);
    if (file->empty())
        throw Error(path, "empty file");

    std::optional<GlbChunks> glb;
    std::string_view text;
    if (startsWithGlbMagic(*file)) {
        glb = parseGlb(path, *file, doc.warnings);
        text = glb->jsonText;
    } else {
        text = std::string_view(reinterpret_cast<const char*>(file->data()), file->size());
        if (text.substr(0, 3) == "\xEF\xBB\xBF")
            text.remove_prefix(3); // UTF-8 byte order mark, written by some Windows tools
        const std::size_t first = text.find_first_not_of(" \t\r\n");
        if (first == std::string_view::npos || text[first] != '{')
            throw Error(path, lowerExtension(path) == ".glb"
                                  ? "not a binary glTF: no 'glTF' magic, starts with " + describeStart(*file)
                                  : "not a glTF file: starts with " + describeStart(*file) +
                                        ", neither a JSON object nor the GLB magic 'glTF'");
    }
    // GLB writers pad the JSON chunk with spaces, some with NULs, which JSON forbids.
    while (!text.empty() && (text.back() == '\0' || text.back() == ' '))
        text.remove_suffix(1);

    if (nestsDeeperThan(text, limits.maxJsonDepth))
        throw Error(path, "JSON nests deeper than " + std::to_string(limits.maxJsonDepth) + " levels");
    try {
        doc.json = json::parse(text.begin(), text.end());
    } catch (const json::parse_error& e) {
        std::string what = e.what();
        // "[json.exception.parse_error.101] parse error at line 1, ...": the bracketed
        // id means nothing to an artist.
        if (const std::size_t close = what.find("] "); what.rfind("[json.exception", 0) == 0 && close != std::string::npos)
            what.erase(0, close + 2);
        throw Error(path, "malformed JSON: " + what);
    }
    if (!doc.json.is_object())
        throw Error(path, "the JSON document is not an object");
    checkAssetAndExtensions(m, doc.json, doc.warnings);

    const std::vector<std::uint64_t> offsets = mergeBuffers(m, doc, folder, glb ? &*glb : nullptr, budget);
    file.reset(); // the BIN chunk has been copied; the raw file is no longer needed
    rebaseBufferViews(m, doc.json, offsets);
    setSingleBuffer(doc.json, doc.bin, false);
    readImages(m, doc, folder, budget);
    return doc;
}

int appendBufferView(json& root, std::vector<std::uint8_t>& bin, const std::uint8_t* data, std::size_t size, int target,
                     int byteStride)
{
    bin.resize((bin.size() + 3) / 4 * 4, 0);
    json view = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", size}};
    if (target)
        view["target"] = target;
    if (byteStride)
        view["byteStride"] = byteStride;
    bin.insert(bin.end(), data, data + size);
    json& views = root["bufferViews"];
    if (!views.is_array())
        views = json::array();
    views.push_back(std::move(view));
    return int(views.size() - 1);
}

void setSingleBuffer(json& root, const std::vector<std::uint8_t>& bin, bool embedAsDataUri)
{
    if (bin.empty()) {
        root.erase("buffers");
        return;
    }
    json buffer = {{"byteLength", bin.size()}};
    if (embedAsDataUri)
        buffer["uri"] = "data:application/octet-stream;base64," + encodeBase64(bin);
    root["buffers"] = json::array({std::move(buffer)});
}

std::string bytesText(std::uint64_t n) { return std::to_string(n) + (n == 1 ? " byte" : " bytes"); }

std::string indexed(const char* array, std::size_t index) { return std::string(array) + "[" + std::to_string(index) + "]"; }

std::string lowerExtension(const std::string& path)
{
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

std::string sniffImageMimeType(const std::vector<std::uint8_t>& b)
{
    const auto starts = [&](std::initializer_list<int> sig, std::size_t at = 0) {
        if (b.size() < at + sig.size())
            return false;
        std::size_t i = at;
        for (int s : sig)
            if (b[i++] != std::uint8_t(s))
                return false;
        return true;
    };
    if (starts({0x89, 'P', 'N', 'G'}))
        return "image/png";
    if (starts({0xFF, 0xD8, 0xFF}))
        return "image/jpeg";
    if (starts({'R', 'I', 'F', 'F'}) && starts({'W', 'E', 'B', 'P'}, 8))
        return "image/webp";
    if (starts({0xAB, 'K', 'T', 'X', ' ', '2', '0'}))
        return "image/ktx2";
    return "";
}

} // namespace iblab::scene_detail
