#include "io/image_codec.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
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
    if (!ec)
        candidates.push_back(executable.parent_path() / kModuleFileName);
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

std::string pngFileProblem(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::error_code ec;
    const std::uintmax_t size = fs::file_size(path, ec);
    if (!in || ec) return ""; // the decoder reports what cannot be opened
    return pngChunkProblem(size, [&](std::uintmax_t offset, std::size_t count, std::uint8_t* out) {
        in.clear();
        return bool(in.seekg(std::streamoff(offset)).read(reinterpret_cast<char*>(out), std::streamsize(count)));
    });
}

std::string pngMemoryProblem(std::span<const std::uint8_t> bytes)
{
    return pngChunkProblem(bytes.size(), [&](std::uintmax_t offset, std::size_t count, std::uint8_t* out) {
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
        std::unique_ptr<ImageReader> direct;
        switch (sniffImageFile(path)) {
        case ImageFileKind::OpenExr: direct = openExrDirect(path); break;
        case ImageFileKind::RadianceHdr: direct = openHdrDirect(path); break;
        case ImageFileKind::Other: break;
        }
        if (direct) return direct;
        if (error = pngFileProblem(path); !error.empty()) return nullptr;
        return openImageIoCodec().openFile(path, error);
    }

    std::unique_ptr<ImageReader> openMemory(std::span<const std::uint8_t> bytes, const std::string& nameHint,
                                            std::string& error) const override
    {
        if (error = pngMemoryProblem(bytes); !error.empty()) return nullptr;
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
