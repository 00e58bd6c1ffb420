#include "asset_paths.hpp"

#include <cstdlib>
#include <string_view>
#include <system_error>
#include <vector>

namespace iblab::app {
namespace {

namespace fs = std::filesystem;

// An asset directory is one with the shaders in it: the rest is optional for a user's own
// environment and model, the shaders are not.
bool holdsAssets(const fs::path& directory)
{
    std::error_code ec;
    return fs::is_directory(directory / "shaders", ec);
}

std::vector<fs::path> candidates()
{
    std::vector<fs::path> out;
    std::error_code ec;
    const fs::path executable = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) out.push_back(executable.parent_path().parent_path() / IBLAB_INSTALL_DATA_DIR);
    out.emplace_back(IBLAB_ASSET_DIR);
    const char* dataDirs = std::getenv("XDG_DATA_DIRS");
    std::string_view dirs = dataDirs && *dataDirs ? dataDirs : "/usr/local/share:/usr/share";
    while (!dirs.empty()) {
        const std::size_t colon = dirs.find(':');
        const std::string_view dir = dirs.substr(0, colon);
        if (!dir.empty()) out.push_back(fs::path(dir) / "iblab");
        dirs = colon == std::string_view::npos ? std::string_view() : dirs.substr(colon + 1);
    }
    return out;
}

} // namespace

std::filesystem::path assetDirectory()
{
    if (const char* overridden = std::getenv("IBLAB_ASSET_DIR"); overridden && *overridden) return overridden;
    static const fs::path found = [] {
        for (const fs::path& candidate : candidates())
            if (holdsAssets(candidate)) return candidate.lexically_normal();
        // None has them: the build-time path, so that the error about a missing shader names
        // the place a build would have them.
        return fs::path(IBLAB_ASSET_DIR);
    }();
    return found;
}
}
