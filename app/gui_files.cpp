#include "gui_files.hpp"

#include <cctype>
#include <ctime>

#include "io/builtin_environments.hpp"
#include "io/error.hpp"
#include "io/atomic_file.hpp"

namespace iblab::app {

ui::StatusLine savePreset(const std::string& path, const FrameSettings& settings)
{
    try {
        writeTextFileAtomic(path, toJsonText(settings) + "\n");
        return {"saved " + path, false};
    } catch (const Error& e) {
        return {e.what(), true};
    }
}

// A preset replaces every setting; its environment and model load like a user's choice.
ui::StatusLine loadPreset(const std::string& path, FrameSettings& settings, LabSession& session)
{
    FrameSettings loaded;
    try {
        loaded = frameSettingsFromJsonText(readTextFile(path));
    } catch (const Error& e) {
        return {e.what(), true};
    } catch (const std::exception& e) {
        return {path + ": " + e.what(), true};
    }
    const std::string environment = loaded.environment.source;
    loaded.environment.source = settings.environment.source; // until the new one has loaded
    settings = loaded;
    if (!environment.empty()) session.requestEnvironment(environment);
    if (settings.scene.kind == SceneKind::Model && !settings.scene.modelPath.empty()) {
        const ui::StatusLine model = session.loadModel(settings.scene.modelPath, settings);
        if (model.isError) return model;
    }
    return {"loaded " + path, false};
}

// A screenshot name nobody has used: iblab-<environment>-<date>-<time>[-n].<ext> in
// `directory`, or `requested` (made unique the same way) when the user typed one. A capture
// never overwrites a file.
std::filesystem::path captureName(const std::filesystem::path& directory, const std::string& requested, const std::string& environment,
                                  const std::string& extension)
{
    std::filesystem::path base;
    if (!requested.empty()) {
        base = std::filesystem::path(requested);
        if (base.is_relative()) base = directory / base;
    } else {
        const std::time_t now = std::time(nullptr);
        char stamp[32];
        std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", std::localtime(&now));
        const std::string stem = isBuiltinSpec(environment) ? environment.substr(environment.find(':') + 1, std::string::npos)
                                                            : std::filesystem::path(environment).stem().string();
        std::string safe;
        for (char c : stem.substr(0, stem.find('?'))) safe += std::isalnum(static_cast<unsigned char>(c)) || c == '-' ? c : '_';
        base = directory / ("iblab-" + safe + "-" + stamp + extension);
    }
    std::filesystem::path candidate = base;
    for (int n = 2; std::filesystem::exists(candidate); ++n)
        candidate = base.parent_path() / (base.stem().string() + "-" + std::to_string(n) + base.extension().string());
    return candidate;
}

} // namespace iblab::app
