#include "ui/widgets.hpp"

#include <imgui_internal.h>

#include "ibl/tonemap.hpp"
#include "io/environment.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

namespace iblab::ui {

std::string visibleLabel(std::string_view label)
{
    const std::size_t hashes = label.find("##");
    if (hashes == std::string_view::npos) return std::string(label);
    if (hashes > 0) return std::string(label.substr(0, hashes));
    return std::string(label.substr(2));
}

void ItemRegistry::beginFrame()
{
    building_.clear();
    scope_.clear();
}

void ItemRegistry::endFrame() { shown_ = std::exchange(building_, {}); }

void ItemRegistry::pushScope(std::string_view name) { scope_.push_back(visibleLabel(name)); }

void ItemRegistry::popScope()
{
    if (!scope_.empty()) scope_.pop_back();
}

void ItemRegistry::recordLastItem(std::string_view label, std::string_view kind)
{
    recordRect(label, kind, ImGui::GetItemRectMin(), ImGui::GetItemRectMax());
    if (ImGui::IsItemActivated() || ImGui::IsItemClicked() || ImGui::IsItemEdited()) interacted_.insert(building_.back().path);
}

void ItemRegistry::recordRect(std::string_view label, std::string_view kind, ImVec2 min, ImVec2 max)
{
    std::string path;
    for (const std::string& part : scope_) path += part + "/";
    path += visibleLabel(label);
    // Two controls of one scope with the same visible text (two "Load" buttons) stay apart.
    const std::string base = path;
    for (int n = 2; std::any_of(building_.begin(), building_.end(), [&](const TrackedItem& item) { return item.path == path; }); ++n)
        path = base + "#" + std::to_string(n);
    building_.push_back({.path = path, .kind = std::string(kind), .min = min, .max = max});
    everShown_.emplace(path, std::string(kind));
}

void ItemRegistry::noteLastField(std::string_view field, double min, double max, std::string_view kind)
{
    for (auto item = building_.rbegin(); item != building_.rend(); ++item)
        if (kind.empty() || item->kind == kind) {
            item->field = std::string(field);
            item->fieldMin = min;
            item->fieldMax = max;
            return;
        }
}

const TrackedItem* ItemRegistry::find(std::string_view path) const
{
    const TrackedItem* suffixMatch = nullptr;
    int suffixMatches = 0;
    const std::string suffix = "/" + std::string(path);
    for (const TrackedItem& item : shown_) {
        if (item.path == path) return &item;
        if (item.path.size() > suffix.size() && item.path.compare(item.path.size() - suffix.size(), suffix.size(), suffix) == 0) {
            suffixMatch = &item;
            ++suffixMatches;
        }
    }
    return suffixMatches == 1 ? suffixMatch : nullptr;
}

ItemRegistry& itemRegistry()
{
    static ItemRegistry registry;
    return registry;
}

namespace {

template <typename Result>
Result recorded(Result result, const char* label, std::string_view kind)
{
    itemRegistry().recordLastItem(label, kind);
    return result;
}

} // namespace

std::map<std::string, bool>& sectionStates()
{
    static std::map<std::string, bool> states;
    return states;
}

namespace {

bool collapsingHeader(const char* label, bool defaultOpen)
{
    std::map<std::string, bool>& states = sectionStates();
    if (const auto remembered = states.find(label); remembered != states.end()) ImGui::SetNextItemOpen(remembered->second, ImGuiCond_Once);
    const bool open = ImGui::CollapsingHeader(label, defaultOpen ? ImGuiTreeNodeFlags_DefaultOpen : 0);
    states[label] = open;
    return open;
}

} // namespace

Section::Section(const char* label, bool defaultOpen) : open_(recorded(collapsingHeader(label, defaultOpen), label, "header"))
{
    if (!open_) return;
    ImGui::PushID(label);
    itemRegistry().pushScope(label);
}

Section::~Section()
{
    if (!open_) return;
    itemRegistry().popScope();
    ImGui::PopID();
}

Combo::Combo(const char* label, const char* preview, ImGuiComboFlags flags)
    : open_(recorded(ImGui::BeginCombo(label, preview, flags), label, "combo"))
{
    if (open_) itemRegistry().pushScope(label);
}

Combo::~Combo()
{
    if (!open_) return;
    itemRegistry().popScope();
    ImGui::EndCombo();
}

bool Combo::entry(const char* label, bool selected)
{
    const bool chosen = recorded(ImGui::Selectable(label, selected), label, "entry");
    if (selected) ImGui::SetItemDefaultFocus();
    return chosen;
}

bool button(const char* label, ImVec2 size) { return recorded(ImGui::Button(label, size), label, "button"); }
bool smallButton(const char* label) { return recorded(ImGui::SmallButton(label), label, "button"); }
bool checkbox(const char* label, bool* value) { return recorded(ImGui::Checkbox(label, value), label, "checkbox"); }
bool radioButton(const char* label, bool active) { return recorded(ImGui::RadioButton(label, active), label, "radio"); }

bool sliderFloat(const char* label, float* value, float min, float max, const char* format, ImGuiSliderFlags flags)
{
    return recorded(ImGui::SliderFloat(label, value, min, max, format, flags), label, "slider");
}

bool sliderInt(const char* label, int* value, int min, int max, const char* format, ImGuiSliderFlags flags)
{
    return recorded(ImGui::SliderInt(label, value, min, max, format, flags), label, "slider");
}

bool inputInt(const char* label, int* value, int step, int stepFast)
{
    return recorded(ImGui::InputInt(label, value, step, stepFast), label, "input");
}

bool inputText(const char* label, char* buffer, std::size_t size, ImGuiInputTextFlags flags)
{
    return recorded(ImGui::InputText(label, buffer, size, flags), label, "input");
}

bool inputTextWithHint(const char* label, const char* hint, char* buffer, std::size_t size, ImGuiInputTextFlags flags)
{
    return recorded(ImGui::InputTextWithHint(label, hint, buffer, size, flags), label, "input");
}

bool tooltipWanted()
{
    constexpr float kRestSeconds = 0.5f;
    static ImGuiID used = 0;
    const ImGuiID id = ImGui::GetItemID();
    const bool hovered = ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled);
    if (id != 0 && ImGui::IsItemActive()) used = id;
    if (!hovered) {
        if (id != 0 && used == id) used = 0;
        return false;
    }
    if (used == id && id != 0) return false;
    // Text has no id, a disabled control is never the hovered id: nothing to drag there.
    const ImGuiContext& g = *ImGui::GetCurrentContext();
    if (id == 0 || g.HoveredId != id) return true;
    return g.HoveredIdNotActiveTimer >= kRestSeconds;
}

std::string srgbHex(const float linear[3])
{
    char text[8];
    int bytes[3];
    for (int c = 0; c < 3; ++c) bytes[c] = int(std::lround(255.0f * std::clamp(srgbOetf(std::clamp(linear[c], 0.0f, 1.0f)), 0.0f, 1.0f)));
    std::snprintf(text, sizeof text, "#%02X%02X%02X", bytes[0], bytes[1], bytes[2]);
    return text;
}

bool colourEdit3(const char* label, float colour[3])
{
    // The fields edit the linear values the settings hold (as --base-color r,g,b reads them).
    // The swatch and its picker show the colour as the display does, sRGB-encoded, so that the
    // picker's hex is what --base-color #rrggbb reads: ImGui's own swatch drew the linear
    // values as display colours, and its picker wrote their hex.
    const ImGuiStyle& style = ImGui::GetStyle();
    const float square = ImGui::GetFrameHeight();
    const float inputsWidth = ImGui::CalcItemWidth() - (square + style.ItemInnerSpacing.x);
    const float componentWidth = std::max(1.0f, float(int((inputsWidth - 2.0f * style.ItemInnerSpacing.x) / 3.0f)));
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    ImGui::SetNextItemWidth(inputsWidth);
    bool changed = recorded(ImGui::ColorEdit3(label, colour, ImGuiColorEditFlags_Float | ImGuiColorEditFlags_NoSmallPreview | ImGuiColorEditFlags_NoLabel),
                            label, "colour");
    ItemRegistry& registry = itemRegistry();
    registry.pushScope(label);
    const char* names[] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) {
        const float x = origin.x + float(c) * (componentWidth + style.ItemInnerSpacing.x);
        registry.recordRect(names[c], "part", ImVec2(x, origin.y), ImVec2(x + componentWidth, origin.y + ImGui::GetFrameHeight()));
    }
    ImGui::PushID(label);
    float display[3];
    for (int c = 0; c < 3; ++c) display[c] = srgbOetf(std::clamp(colour[c], 0.0f, 1.0f));
    ImGui::SameLine(0.0f, style.ItemInnerSpacing.x);
    if (recorded(ImGui::ColorButton("swatch", ImVec4(display[0], display[1], display[2], 1.0f), ImGuiColorEditFlags_NoTooltip, ImVec2(square, square)),
                 "swatch", "button"))
        ImGui::OpenPopup("picker");
    if (tooltipWanted()) ImGui::SetTooltip("%s in sRGB (as --base-color #rrggbb reads it); the fields are linear", srgbHex(colour).c_str());
    if (ImGui::BeginPopup("picker")) {
        if (ImGui::ColorPicker3("##sRGB", display, ImGuiColorEditFlags_DisplayRGB | ImGuiColorEditFlags_DisplayHex)) {
            for (int c = 0; c < 3; ++c) colour[c] = srgbToLinear(display[c]);
            changed = true;
        }
        ImGui::EndPopup();
    }
    ImGui::PopID();
    registry.popScope();
    const std::string visible = visibleLabel(label);
    if (!visible.empty()) {
        ImGui::SameLine(0.0f, style.ItemInnerSpacing.x);
        ImGui::TextUnformatted(visible.c_str());
    }
    return changed;
}

bool canvas(const char* label, ImVec2 size, std::string_view kind) { return recorded(ImGui::InvisibleButton(label, size), label, kind); }

void progressBar(const char* label, float fraction, const char* overlay)
{
    ImGui::ProgressBar(fraction, ImVec2(-1.0f, 0.0f), overlay);
    itemRegistry().recordLastItem(label, "progress");
}

} // namespace iblab::ui
