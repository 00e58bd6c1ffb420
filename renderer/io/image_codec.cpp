#include "io/image_codec.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include <dlfcn.h>

#include "io/error.hpp"
#include "io/image_codec_direct.hpp"

namespace iblab {
namespace {

namespace fs = std::filesystem;

constexpr const char* kModuleFileName = "libiblab_oiio.so";

// Where the module may be, most specific first (see image_codec.hpp).
std::vector<fs::path> moduleCandidates()
{
    std::vector<fs::path> candidates;
    if (const char* path = std::getenv("IBLAB_IMAGE_MODULE"); path && *path)
        candidates.emplace_back(path);
    std::error_code ec;
    const fs::path executable = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        candidates.push_back(executable.parent_path() / kModuleFileName);
        candidates.push_back(executable.parent_path().parent_path() / IBLAB_INSTALL_MODULE_DIR / kModuleFileName);
    }
    candidates.emplace_back(IBLAB_IMAGE_MODULE_BUILD_PATH);
    return candidates;
}

const ImageCodec* loadCodec()
{
    std::string tried;
    for (const fs::path& candidate : moduleCandidates()) {
        std::error_code ec;
        if (!fs::exists(candidate, ec)) {
            tried += (tried.empty() ? "" : ", ") + candidate.string() + " (absent)";
            continue;
        }
        // Never closed: the codec and the readers it made live as long as the process.
        void* module = ::dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!module) {
            const char* why = ::dlerror();
            tried += (tried.empty() ? "" : ", ") + candidate.string() + " (" + (why ? why : "dlopen failed") + ")";
            continue;
        }
        auto* entry = reinterpret_cast<ImageCodecEntry*>(::dlsym(module, kImageCodecEntryName));
        if (!entry) {
            tried += (tried.empty() ? "" : ", ") + candidate.string() + " (no " + kImageCodecEntryName + ")";
            continue;
        }
        return entry();
    }
    throw Error(kModuleFileName, "cannot load the image module, needed to read and write image files; tried " + tried);
}

// Reads `count` bytes at `offset` of a file or a buffer; false past its end.
using ByteReader = std::function<bool(std::uintmax_t offset, std::size_t count, std::uint8_t* out)>;

// OpenEXR 3.1 allocates each header attribute at the size the bytes claim before reading
// it, so a 41-byte file claiming a 1.8 GB string attribute makes it allocate 1.8 GB (found
// by scripts/fuzz.sh; tests/fuzz/corpus/environment/exr-attribute-claims-gigabytes). So the
// attribute list (name, type, int32 size, payload; an empty name ends a header) is walked
// first, and a size that the rest of the bytes cannot hold is the problem returned ("" if
// none, or if the bytes are not an EXR). Multi-part files list several headers, each ended
// by an empty name, and the list by one more.
// The walk must step through the header exactly as OpenEXR does, or a later attribute it
// reads is one this walk never saw (tests/fuzz/corpus/environment/exr-channel-list-overruns-
// its-size): OpenEXR reads the types it knows by their content and ignores the declared
// size. So a fixed-size type must declare its own size, a channel list must end where its
// size says, and so must a preview image and a string vector.
std::string exrHeaderProblem(std::uintmax_t size, const ByteReader& read)
{
    std::uint8_t magic[4] = {};
    if (!read(0, 4, magic) || std::memcmp(magic, kExrMagic, 4) != 0)
        return ""; // not an EXR: nothing to check
    struct Truncated {};
    struct Corrupt {
        std::string problem;
    };
    std::uintmax_t position = 4;
    auto readInt = [&] {
        std::uint8_t bytes[4];
        if (!read(position, 4, bytes)) throw Truncated{};
        position += 4;
        return std::int32_t(std::uint32_t(bytes[0]) | std::uint32_t(bytes[1]) << 8 | std::uint32_t(bytes[2]) << 16 |
                            std::uint32_t(bytes[3]) << 24);
    };
    auto readName = [&] {
        std::string name;
        for (std::uint8_t c; read(position, 1, &c);) {
            ++position;
            if (c == 0) return name;
            if (name.size() >= 255) throw Corrupt{"corrupt EXR header: a name longer than 255 bytes"};
            name += char(c);
        }
        throw Truncated{};
    };
    // The bytes OpenEXR reads for a value of a type it knows, where that is fixed.
    static const std::map<std::string, std::int32_t, std::less<>> kFixedSizes = {
        {"box2i", 16},   {"box2f", 16}, {"chromaticities", 32}, {"compression", 1}, {"deepImageState", 1},
        {"double", 8},   {"envmap", 1}, {"float", 4},           {"int", 4},          {"keycode", 28},
        {"lineOrder", 1}, {"m33f", 36}, {"m33d", 72},           {"m44f", 64},        {"m44d", 128},
        {"rational", 8}, {"tiledesc", 9}, {"timecode", 8},      {"v2i", 8},          {"v2f", 8},
        {"v2d", 16},     {"v3i", 12},   {"v3f", 12},            {"v3d", 24}};
    try {
        const bool multiPart = (std::uint32_t(readInt()) & 0x1000u) != 0;
        for (;;) {
            const std::string name = readName();
            if (name.empty()) {
                // The end of a header. A single-part file has one; a multi-part list ends
                // with an empty header, i.e. a second empty name in a row.
                std::uint8_t next = 1;
                if (!multiPart || (read(position, 1, &next) && next == 0)) return "";
                continue;
            }
            const std::string type = readName();
            const std::int32_t declared = readInt();
            const std::uintmax_t left = size - std::min(size, position);
            if (declared < 0 || std::uintmax_t(declared) > left)
                return "corrupt EXR header: attribute '" + name + "' claims " + std::to_string(declared) + " bytes, more than the " +
                       std::to_string(left) + " left";
            const std::uintmax_t end = position + std::uintmax_t(declared);
            auto mismatch = [&](const std::string& what) {
                return Corrupt{"corrupt EXR header: attribute '" + name + "' (" + type + ") declares " + std::to_string(declared) +
                               " bytes but " + what};
            };
            if (const auto fixed = kFixedSizes.find(type); fixed != kFixedSizes.end()) {
                if (declared != fixed->second) throw mismatch("its type has " + std::to_string(fixed->second));
            } else if (type == "chlist") {
                // Channels until an empty name: each a name and 16 bytes (type, linear,
                // reserved, x and y sampling).
                while (!readName().empty()) {
                    position += 16;
                    if (position > end) throw mismatch("its channel list runs past them");
                }
                if (position != end) throw mismatch("its channel list ends before them");
            } else if (type == "preview") {
                // Width and height (unsigned 32-bit each, so their product fits 64 bits),
                // then 4 bytes a pixel.
                if (declared < 8) throw mismatch("a preview starts with 8 bytes of width and height");
                const std::uint64_t width = std::uint32_t(readInt());
                const std::uint64_t height = std::uint32_t(readInt());
                if (width * height != std::uint64_t(declared - 8) / 4 || (declared - 8) % 4 != 0)
                    throw mismatch("a " + std::to_string(width) + "x" + std::to_string(height) + " preview holds " +
                                   std::to_string(width * height) + " pixels of 4 bytes after them");
            } else if (type == "stringvector") {
                // Length-prefixed strings until the size is used up.
                while (position < end) {
                    const std::int32_t length = readInt();
                    if (length < 0 || position + std::uintmax_t(length) > end)
                        throw mismatch("holds a string of " + std::to_string(length) + " bytes that does not fit");
                    position += std::uintmax_t(length);
                }
                if (position != end) throw mismatch("its last string length runs past them");
            } else if (type == "floatvector" && declared % 4 != 0) {
                throw mismatch("a float vector is a multiple of 4 bytes");
            } else if (type == "idmanifest" && declared < 8) {
                throw mismatch("an ID manifest starts with its uncompressed size"); // OpenEXR allocates size - 4 or - 8
            }
            // Strings, float vectors and types OpenEXR does not know are read at their size.
            position = end;
        }
    } catch (const Truncated&) {
        return "truncated EXR header";
    } catch (const Corrupt& corrupt) {
        return corrupt.problem;
    }
}

// libpng allocates (and zeroes) the whole of an ancillary chunk (tEXt, iCCP, ...) at the
// length the bytes claim, up to 2^31 - 1, before it reads any of it: a 357-byte PNG cost
// 2 GB and 5 s before its error (found by scripts/fuzz.sh;
// tests/fuzz/corpus/environment/png-text-chunk-claims-gigabytes), and a glTF texture is
// decoded the same way. So the chunk list (length, type, data, CRC) is walked first, and a
// length that the rest of the bytes cannot hold is the problem returned ("" if none, or if
// the bytes are not a PNG). Image data is streamed, not allocated: an IDAT that runs past
// the end is a truncated file, left to the pixel read to report.
std::string pngChunkProblem(std::uintmax_t size, const ByteReader& read)
{
    std::uint8_t signature[8] = {};
    if (!read(0, 8, signature) || std::memcmp(signature, "\x89PNG\r\n\x1a\n", 8) != 0)
        return "";
    for (std::uintmax_t position = 8;;) {
        std::uint8_t header[8];
        if (!read(position, 8, header))
            return ""; // truncated between chunks: libpng reports it
        const std::uint32_t length = std::uint32_t(header[0]) << 24 | std::uint32_t(header[1]) << 16 |
                                     std::uint32_t(header[2]) << 8 | std::uint32_t(header[3]);
        std::string type(reinterpret_cast<const char*>(header) + 4, 4);
        for (char& c : type)
            if (c < 0x20 || c > 0x7e) c = '?'; // a corrupt type is any four bytes
        position += 8;
        const std::uintmax_t left = size - std::min(size, position);
        if (length > left)
            return type == "IDAT" ? "" : "corrupt PNG: chunk '" + type + "' claims " + std::to_string(length) + " bytes, more than the " +
                                             std::to_string(left) + " left";
        if (type == "IEND") return "";
        position += std::uintmax_t(length) + 4; // data and CRC
    }
}

// What the walks above find in a file or a buffer ("" if nothing).
std::string headerProblem(std::uintmax_t size, const ByteReader& read)
{
    std::string problem = exrHeaderProblem(size, read);
    return problem.empty() ? pngChunkProblem(size, read) : problem;
}

std::string fileHeaderProblem(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::error_code ec;
    const std::uintmax_t size = fs::file_size(path, ec);
    if (!in || ec) return ""; // the decoder reports what cannot be opened
    // The walks read names a byte at a time: served from one block (a header is a few KB; a
    // PNG's chunk heads are a block's read apart), so that opening a file costs a read or
    // two, not a system call per byte (the bake cache opens a dozen files per hit).
    std::vector<std::uint8_t> block;
    std::uintmax_t blockStart = 0;
    return headerProblem(size, [&](std::uintmax_t offset, std::size_t count, std::uint8_t* out) {
        if (offset < blockStart || offset + count > blockStart + block.size()) {
            constexpr std::size_t kBlockBytes = 64 * 1024;
            if (offset >= size) return false;
            blockStart = offset;
            block.resize(std::size_t(std::min<std::uintmax_t>(std::max(kBlockBytes, count), size - offset)));
            in.clear();
            if (!in.seekg(std::streamoff(offset)).read(reinterpret_cast<char*>(block.data()), std::streamsize(block.size()))) return false;
            if (count > block.size()) return false;
        }
        std::memcpy(out, block.data() + (offset - blockStart), count);
        return true;
    });
}

std::string memoryHeaderProblem(std::span<const std::uint8_t> bytes)
{
    return headerProblem(bytes.size(), [&](std::uintmax_t offset, std::size_t count, std::uint8_t* out) {
        if (offset > bytes.size() || count > bytes.size() - offset) return false;
        std::memcpy(out, bytes.data() + offset, count);
        return true;
    });
}

// OpenEXR and Radiance files that image_codec_direct.hpp takes are read and written
// without OpenImageIO; everything else, and whatever those readers leave, goes to the module.
class DispatchingCodec final : public ImageCodec {
public:
    std::unique_ptr<ImageReader> openFile(const std::string& path, std::string& error) const override
    {
        if (error = fileHeaderProblem(path); !error.empty()) return nullptr;
        std::unique_ptr<ImageReader> direct;
        switch (sniffImageFile(path)) {
        case ImageFileKind::OpenExr: direct = openExrDirect(path); break;
        case ImageFileKind::RadianceHdr: direct = openHdrDirect(path); break;
        case ImageFileKind::Other: break;
        }
        return direct ? std::move(direct) : openImageIoCodec().openFile(path, error);
    }

    std::unique_ptr<ImageReader> openMemory(std::span<const std::uint8_t> bytes, const std::string& nameHint,
                                            std::string& error) const override
    {
        if (error = memoryHeaderProblem(bytes); !error.empty()) return nullptr;
        return openImageIoCodec().openMemory(bytes, nameHint, error);
    }

    void writeFile(const std::string& subject, const std::string& file, const ImageWrite& image) const override
    {
        if (!writeExrDirect(subject, file, image))
            openImageIoCodec().writeFile(subject, file, image);
    }

    std::vector<std::uint8_t> encode(const std::string& subject, const ImageWrite& image) const override
    {
        return openImageIoCodec().encode(subject, image);
    }
};

} // namespace

const ImageCodec& openImageIoCodec()
{
    // A failed load throws out of the initialiser, so the next call tries again.
    static const ImageCodec& codec = *loadCodec();
    return codec;
}

const ImageCodec& imageCodec()
{
    static const DispatchingCodec codec;
    return codec;
}

void preloadImageCodec()
{
    // A function-local static: joined when the program exits, before the module's own
    // statics could be torn down under a thread still loading it.
    static std::jthread loader([] {
        try {
            openImageIoCodec();
        } catch (const Error&) {
        }
    });
}

} // namespace iblab
