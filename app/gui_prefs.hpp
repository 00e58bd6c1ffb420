#pragma once
// What the GUI remembers between sessions, in $XDG_CONFIG_HOME/iblab/gui.json
// (~/.config/iblab/gui.json when XDG_CONFIG_HOME is unset): the open sections, the paths
// typed into the panel, the window's size. And where files go by default: screenshots to the
// user's pictures folder, presets to the documents folder (XDG user directories).
#include <filesystem>
#include <map>
#include <optional>
#include <string>

namespace iblab::app {

struct GuiPrefs {
    std::map<std::string, bool> sections; // a collapsing section's label -> open
    std::string environmentPath, modelPath, presetPath, exportPath, captureFolder;
    int width = 0, height = 0; // 0: not remembered
    std::string bakeExportPath = {};
    bool hintDismissed = false; // the first-run hint went (the user did something); a first run: false
    bool operator==(const GuiPrefs&) const = default;
};

// The file, or empty when neither XDG_CONFIG_HOME nor HOME is set.
std::filesystem::path guiPrefsPath();

// nullopt when there is no file yet (the first run). A file that cannot be read or parsed
// gives the defaults and `warning` naming the file and the problem.
std::optional<GuiPrefs> loadGuiPrefs(const std::filesystem::path& path, std::string& warning);
// Writes atomically, creating the folder. Throws iblab::Error naming the file on failure.
void saveGuiPrefs(const std::filesystem::path& path, const GuiPrefs& prefs);

// An XDG user directory ("PICTURES", "DOCUMENTS"): $XDG_<NAME>_DIR, else its line in
// $XDG_CONFIG_HOME/user-dirs.dirs (what xdg-user-dir reads), else ~/Pictures or ~/Documents
// when it exists, else the home folder, else the working directory.
std::filesystem::path userDirectory(const std::string& name);

} // namespace iblab::app
