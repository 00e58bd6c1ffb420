#include "gui_files.hpp"

#include <cctype>
#include <ctime>

#include "asset_paths.hpp"
#include "io/builtin_environments.hpp"
#include "io/error.hpp"
#include "io/atomic_file.hpp"
#include "preset_json.hpp"

namespace iblab::app {

ui::EnvironmentCatalog environmentCatalog()
{
    ui::EnvironmentCatalog catalog;
    catalog.gallery = galleryEnvironments(assetDirectory().string());
    for (const auto& name : builtinEnvironmentNames()) catalog.builtins.push_back("builtin:" + name);
    return catalog;
}

ui::StatusLine savePreset(const std::string& path, const FrameSettings& settings, const bake::BakeSettings& bake)
{
    try {
        writeTextFileAtomic(path, presetJsonText(settings, bake, path) + "\n");
        return {"saved " + path, false};
    } catch (const Error& e) {
        return {e.what(), true};
    }
}

// A preset replaces every setting; its environment and model load like a user's choice, and
// bake settings other than the session's bake the environment again with them.
ui::StatusLine loadPreset(const std::string& path, FrameSettings& settings, FrameSettings& saved, LabSession& session, LoadedModel& model,
                          std::string& convention)
{
    Preset loaded;
    try {
        loaded = readPreset(path);
    } catch (const Error& e) {
        return {e.what(), true};
    } catch (const std::exception& e) {
        return {path + ": " + e.what(), true};
    }
    const std::string environment = loaded.settings.environment.source;
    loaded.settings.environment.source = settings.environment.source; // until the new one has loaded
    settings = loaded.settings;
    ui::StatusLine status{"loaded " + path, false};
    if (loaded.bake && toJsonText(*loaded.bake) != toJsonText(session.bakeSettings())) {
        session.setBakeSettings(*loaded.bake);
        status.text += "; its bake settings differ from the current ones: baking again";
    }
    convention = matchingConvention(session.bakeSettings(), settings.sampling);
    if (!environment.empty()) session.requestEnvironment(environment);
    if (settings.scene.kind == SceneKind::Model && !settings.scene.modelPath.empty()) {
        const StatusReport loadedModel = model.load(settings.scene.modelPath, /*modelShown=*/true);
        if (loadedModel.isError) return toStatusLine(loadedModel);
    }
    // The preset's environment counts as saved while it loads: the GUI names it in the
    // settings once shown, which made a preset look edited as soon as its map arrived.
    saved = settings;
    if (!environment.empty()) saved.environment.source = environment;
    return status;
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
