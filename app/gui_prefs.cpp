#include "gui_prefs.hpp"

#include <cstdlib>
#include <fstream>

#include <nlohmann/json.hpp>

#include "io/atomic_file.hpp"
#include "io/error.hpp"

namespace iblab::app {
namespace {

std::string environmentValue(const char* name)
{
    const char* value = std::getenv(name);
    return value ? value : "";
}

std::filesystem::path configHome()
{
    if (const std::string xdg = environmentValue("XDG_CONFIG_HOME"); !xdg.empty()) return xdg;
    if (const std::string home = environmentValue("HOME"); !home.empty()) return std::filesystem::path(home) / ".config";
    return {};
}

// XDG_PICTURES_DIR="$HOME/Pictures" in user-dirs.dirs: the only forms the spec allows are
// an absolute path or one starting with $HOME/.
std::optional<std::filesystem::path> userDirsEntry(const std::string& key)
{
    const std::filesystem::path file = configHome() / "user-dirs.dirs";
    std::ifstream in(file);
    std::string line;
    while (std::getline(in, line)) {
        if (line.compare(0, key.size() + 1, key + "=") != 0) continue;
        std::string value = line.substr(key.size() + 1);
        if (value.size() >= 2 && value.front() == '"' && value.back() == '"') value = value.substr(1, value.size() - 2);
        if (value.compare(0, 5, "$HOME") == 0) value = environmentValue("HOME") + value.substr(5);
        if (!value.empty() && value.front() == '/') return std::filesystem::path(value);
    }
    return std::nullopt;
}

std::string stringOr(const nlohmann::json& object, const char* key)
{
    return object.contains(key) && object[key].is_string() ? object[key].get<std::string>() : "";
}

} // namespace

std::filesystem::path guiPrefsPath()
{
    const std::filesystem::path home = configHome();
    return home.empty() ? home : home / "iblab" / "gui.json";
}

std::optional<GuiPrefs> loadGuiPrefs(const std::filesystem::path& path, std::string& warning)
{
    std::error_code error;
    if (path.empty() || !std::filesystem::exists(path, error)) return std::nullopt;
    GuiPrefs prefs;
    try {
        const nlohmann::json json = nlohmann::json::parse(readTextFile(path.string()));
        if (!json.is_object()) throw Error(path.string(), "expected a JSON object");
        if (json.contains("sections") && json["sections"].is_object())
            for (const auto& [label, open] : json["sections"].items())
                if (open.is_boolean()) prefs.sections[label] = open.get<bool>();
        prefs.environmentPath = stringOr(json, "environment_path");
        prefs.modelPath = stringOr(json, "model_path");
        prefs.presetPath = stringOr(json, "preset_path");
        prefs.exportPath = stringOr(json, "export_path");
        prefs.captureFolder = stringOr(json, "capture_folder");
        prefs.bakeExportPath = stringOr(json, "bake_export_path");
        // A file from before the key was saved comes from a user who has run the lab already.
        prefs.hintDismissed = !json.contains("hint_dismissed") || json["hint_dismissed"] == true;
        if (json.contains("window") && json["window"].is_array() && json["window"].size() == 2 && json["window"][0].is_number_integer() &&
            json["window"][1].is_number_integer()) {
            prefs.width = json["window"][0].get<int>();
            prefs.height = json["window"][1].get<int>();
        }
    } catch (const Error& e) {
        warning = e.what();
        return GuiPrefs{};
    } catch (const nlohmann::json::exception& e) {
        warning = path.string() + ": not valid JSON (" + e.what() + "); the GUI starts with its defaults";
        return GuiPrefs{};
    }
    return prefs;
}

void saveGuiPrefs(const std::filesystem::path& path, const GuiPrefs& prefs)
{
    if (path.empty()) return;
    std::error_code error;
    std::filesystem::create_directories(path.parent_path(), error);
    if (error) throw Error(path.parent_path().string(), "cannot create the folder: " + error.message());
    nlohmann::json json = {{"sections", prefs.sections},         {"environment_path", prefs.environmentPath}, {"model_path", prefs.modelPath},
                           {"preset_path", prefs.presetPath},    {"export_path", prefs.exportPath},           {"capture_folder", prefs.captureFolder},
                           {"window", {prefs.width, prefs.height}},  {"bake_export_path", prefs.bakeExportPath},   {"hint_dismissed", prefs.hintDismissed}};
    writeTextFileAtomic(path.string(), json.dump(2) + "\n");
}

std::filesystem::path userDirectory(const std::string& name)
{
    const std::string key = "XDG_" + name + "_DIR";
    if (const std::string direct = environmentValue(key.c_str()); !direct.empty()) return direct;
    if (const std::optional<std::filesystem::path> listed = userDirsEntry(key)) return *listed;
    std::error_code error;
    if (const std::string home = environmentValue("HOME"); !home.empty()) {
        const std::string conventional = name == "PICTURES" ? "Pictures" : name == "DOCUMENTS" ? "Documents" : "";
        if (!conventional.empty() && std::filesystem::is_directory(std::filesystem::path(home) / conventional, error))
            return std::filesystem::path(home) / conventional;
        return home;
    }
    return std::filesystem::current_path(error);
}

} // namespace iblab::app
