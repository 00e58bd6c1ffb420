#include "io/image_codec.hpp"

#include <cstdlib>
#include <filesystem>
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
        return direct ? std::move(direct) : openImageIoCodec().openFile(path, error);
    }

    std::unique_ptr<ImageReader> openMemory(std::span<const std::uint8_t> bytes, const std::string& nameHint,
                                            std::string& error) const override
    {
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
