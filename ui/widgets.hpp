#pragma once
// The controls the panels are made of, each one Dear ImGui's widget plus a record of where
// it was drawn this frame under a readable path ("Scene/Scene", "Material/Roughness",
// "Scene/Scene/grid" for a combo's entry). Scripted input (app/gui_script.hpp) aims at a
// control by that path, as a user aims at what a control says, instead of at pixel
// coordinates that move whenever a panel changes; Dear ImGui's own test engine does the same
// through hooks that Debian's prebuilt library leaves out.
//
// A Section (collapsing header) also scopes the IDs of what it holds, so a header and a
// control inside it may share a label ("Scene" > "Scene") without sharing an ImGui ID.
#include <cstddef>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <imgui.h>

namespace iblab::ui {

struct TrackedItem {
    std::string path;
    // "header", "button", "checkbox", "slider", "input", "combo", "radio", "colour", "canvas";
    // "entry" for a combo's entries and "part" for a colour's component fields, which are
    // choices inside a control rather than controls of their own; "progress" for a progress
    // bar, which shows and is not used.
    std::string kind;
    ImVec2 min{0.0f, 0.0f}, max{0.0f, 0.0f}; // window pixels, y down
    // The settings table row the control edits ("camera.fov_degrees"; ui/field_widgets.hpp),
    // empty for a control that edits no setting; a slider's span (NaN for other controls).
    std::string field = {};
    double fieldMin = std::numeric_limits<double>::quiet_NaN(), fieldMax = std::numeric_limits<double>::quiet_NaN();
    ImVec2 centre() const { return {0.5f * (min.x + max.x), 0.5f * (min.y + max.y)}; }
};

// Where every tracked control was in the last complete frame, and which ones the user has
// ever clicked, edited or focused (the GUI tests' coverage of the panels).
class ItemRegistry {
public:
    // Brackets a frame's drawing: what was recorded between them is what find() sees
    // until the next endFrame.
    void beginFrame();
    void endFrame();
    void pushScope(std::string_view name);
    void popScope();
    // Records ImGui's last item as `label` (the part before "##", or after it when the
    // visible part is empty) under the current scope.
    void recordLastItem(std::string_view label, std::string_view kind);
    // Records a part of a composite widget (a colour's component field) by its rectangle.
    void recordRect(std::string_view label, std::string_view kind, ImVec2 min, ImVec2 max);
    // Notes the settings row that the last recorded item of `kind` (any kind when empty)
    // edits, and a slider's span.
    void noteLastField(std::string_view field, double min, double max, std::string_view kind = {});

    // In the last complete frame: the exact path, else the one item whose path ends with
    // "/" + path.
    const TrackedItem* find(std::string_view path) const;
    const std::vector<TrackedItem>& items() const { return shown_; }
    // Every path recorded in any frame (kind by path), and those that were interacted with.
    const std::map<std::string, std::string>& everShown() const { return everShown_; }
    const std::set<std::string>& interacted() const { return interacted_; }

private:
    std::vector<std::string> scope_;
    std::vector<TrackedItem> building_, shown_;
    std::map<std::string, std::string> everShown_;
    std::set<std::string> interacted_;
};

// The registry of the current ImGui context's panels (one GUI per process).
ItemRegistry& itemRegistry();

// "Yaw##camera" -> "Yaw"; "##envpath" -> "envpath".
std::string visibleLabel(std::string_view label);

// Which sections are open, by label: read when a section is first drawn (the GUI remembers
// them between sessions, gui_prefs.hpp), then kept up to date as the user opens and closes them.
std::map<std::string, bool>& sectionStates();

// A collapsing header whose contents are scoped under its label, for IDs and paths alike.
class Section {
public:
    explicit Section(const char* label, bool defaultOpen = false);
    ~Section();
    Section(const Section&) = delete;
    Section& operator=(const Section&) = delete;
    explicit operator bool() const { return open_; }

private:
    bool open_ = false;
};

// A combo box: entries are tracked under "<combo path>/<entry>". Use as
//   if (ui::Combo combo("Scene", preview)) for (...) if (combo.entry(name, selected)) ...
class Combo {
public:
    Combo(const char* label, const char* preview, ImGuiComboFlags flags = 0);
    ~Combo();
    Combo(const Combo&) = delete;
    Combo& operator=(const Combo&) = delete;
    explicit operator bool() const { return open_; }
    bool entry(const char* label, bool selected);

private:
    bool open_ = false;
};

// Each calls the ImGui widget of the same name and records it.
bool button(const char* label, ImVec2 size = ImVec2(0.0f, 0.0f));
bool smallButton(const char* label);
bool checkbox(const char* label, bool* value);
bool radioButton(const char* label, bool active);
bool sliderFloat(const char* label, float* value, float min, float max, const char* format = "%.3f", ImGuiSliderFlags flags = 0);
bool sliderInt(const char* label, int* value, int min, int max, const char* format = "%d", ImGuiSliderFlags flags = 0);
bool inputInt(const char* label, int* value, int step = 1, int stepFast = 10);
bool inputText(const char* label, char* buffer, std::size_t size, ImGuiInputTextFlags flags = 0);
bool inputTextWithHint(const char* label, const char* hint, char* buffer, std::size_t size, ImGuiInputTextFlags flags = 0);
// Whether the item just drawn should show its tooltip: once the mouse has rested on it for
// half a second, never while it is dragged or typed into (the tooltip covered the value),
// and not again after it was used until the mouse has left it.
bool tooltipWanted();
// Linear r, g, b fields, and a swatch whose picker edits the colour in sRGB (its hex is what
// --base-color #rrggbb reads); the swatch is the part "swatch".
bool colourEdit3(const char* label, float colour[3]);
// The linear colour's sRGB hex, "#F9D1C2".
std::string srgbHex(const float linear[3]);
// An invisible button of `size` (a chart or a curve), tracked as `kind`.
bool canvas(const char* label, ImVec2 size, std::string_view kind);
// A full-width progress bar showing `overlay`, tracked as `label` of kind "progress" (shown,
// not a control to use).
void progressBar(const char* label, float fraction, const char* overlay);

} // namespace iblab::ui
