#include "io/image_codec.hpp"

#include <cstdlib>
#include <filesystem>
#include <thread>
#include <vector>

#include <dlfcn.h>

#include "io/error.hpp"

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

} // namespace

const ImageCodec& imageCodec()
{
    // A failed load throws out of the initialiser, so the next call tries again.
    static const ImageCodec& codec = *loadCodec();
    return codec;
}

void preloadImageCodec()
{
    // A function-local static: joined when the program exits, before the module's own
    // statics could be torn down under a thread still loading it.
    static std::jthread loader([] {
        try {
            imageCodec();
        } catch (const Error&) {
        }
    });
}

} // namespace iblab
