#pragma once
// Panel controls bound to a setting by member pointer: fieldSlider<&CameraSettings::fovDegrees>(camera)
// edits that member, and its table row (io/settings_fields.hpp, frame/settings.cpp) gives
// the control's label (and so its script path), its tooltip (the row's help), the slider's
// span and format (the row's range and ui), an enum's names for a combo. A member that is
// not a setting does not compile (no such member) or has no row, which the first draw
// reports. A panel adds only layout and enabling rules. Each control records its row in the
// item registry (ui/widgets.hpp), so tests/cpu/panel_fields_test.cpp can hold every
// control to its row.
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>

#include <imgui.h>

#include "frame/settings.hpp"
#include "io/settings_fields.hpp"
#include "ui/widgets.hpp"

namespace iblab::ui {

// Where a panel's settings struct is described: the table of the struct it sits in
// (`Root`), and the way from a Root to it.
template <typename Sub>
struct FieldHome;
template <>
struct FieldHome<MaterialSettings> {
    using Root = MaterialSettings;
    static const FieldTable<Root>& table() { return materialSettingsFields(); }
    static const MaterialSettings& in(const Root& root) { return root; }
};
template <>
struct FieldHome<SamplingSettings> { // the frame's own and the split view's B alike
    using Root = SamplingSettings;
    static const FieldTable<Root>& table() { return samplingSettingsFields(); }
    static const SamplingSettings& in(const Root& root) { return root; }
};
template <typename Sub, Sub FrameSettings::*Member>
struct FrameFieldHome {
    using Root = FrameSettings;
    static const FieldTable<Root>& table() { return frameSettingsFields(); }
    static const Sub& in(const Root& root) { return root.*Member; }
};
template <>
struct FieldHome<EnvironmentSettings> : FrameFieldHome<EnvironmentSettings, &FrameSettings::environment> {};
template <>
struct FieldHome<ToneMapSettings> : FrameFieldHome<ToneMapSettings, &FrameSettings::toneMap> {};
template <>
struct FieldHome<CameraSettings> : FrameFieldHome<CameraSettings, &FrameSettings::camera> {};
template <>
struct FieldHome<SceneSettings> : FrameFieldHome<SceneSettings, &FrameSettings::scene> {};
template <>
struct FieldHome<ViewSettings> : FrameFieldHome<ViewSettings, &FrameSettings::view> {};

template <typename MemberPointer>
struct MemberOf;
template <typename Class, typename T>
struct MemberOf<T Class::*> {
    using Struct = Class;
    using Type = T;
};

// The table row of the setting `Member` points to, looked up once: the row whose reference
// reaches the same member of a default-made settings struct.
template <auto Member>
const auto& settingRow()
{
    using Sub = typename MemberOf<decltype(Member)>::Struct;
    using Home = FieldHome<Sub>;
    using Root = typename Home::Root;
    static const auto& row = []() -> const Field<Root>& {
        static const Root probe{};
        const Field<Root>* field = findFieldAt(Home::table(), probe, &(Home::in(probe).*Member));
        if (!field) throw std::logic_error("a panel control's member has no row in the settings table");
        return *field;
    }();
    return row;
}

inline void fieldTooltip(std::string_view help)
{
    if (!help.empty() && tooltipWanted()) ImGui::SetTooltip("%.*s", int(help.size()), help.data());
}

// Records the row that the control of `kind` just drawn edits, and its span (sliders, and a
// combo of numbers). A combo's entries are recorded after it, hence the kind.
template <typename Root>
void noteField(const Field<Root>& row, std::string_view kind, double min = std::numeric_limits<double>::quiet_NaN(),
               double max = std::numeric_limits<double>::quiet_NaN())
{
    itemRegistry().noteLastField(row.key, min, max, kind);
}

// The row's label as a widget label; hidden ("##N") where the panel writes its own text.
template <typename Root>
std::string fieldLabel(const Field<Root>& row, bool hidden = false)
{
    return (hidden ? "##" : "") + std::string(row.label);
}

template <auto Member, typename Sub>
bool fieldCheckbox(Sub& settings)
{
    static_assert(std::is_same_v<Sub, typename MemberOf<decltype(Member)>::Struct>);
    const auto& row = settingRow<Member>();
    const bool changed = checkbox(fieldLabel(row).c_str(), &(settings.*Member));
    noteField(row, "checkbox");
    fieldTooltip(row.help);
    return changed;
}

// A slider over the row's span, float or int as the member is. extraFlags adds to the row's
// (ImGuiSliderFlags_AlwaysClamp where a panel's buttons step the value).
template <auto Member, typename Sub>
bool fieldSlider(Sub& settings, ImGuiSliderFlags extraFlags = 0, bool hideLabel = false)
{
    using T = typename MemberOf<decltype(Member)>::Type;
    static_assert(std::is_same_v<Sub, typename MemberOf<decltype(Member)>::Struct>);
    static_assert(std::is_same_v<T, float> || std::is_same_v<T, int>);
    const auto& row = settingRow<Member>();
    const double min = sliderMin(row.range), max = sliderMax(row.range);
    const ImGuiSliderFlags flags = extraFlags | (row.range.ui.logarithmic ? ImGuiSliderFlags_Logarithmic : 0);
    const std::string label = fieldLabel(row, hideLabel);
    const std::string format(row.range.ui.format.empty() ? (std::is_same_v<T, int> ? "%d" : "%.3f") : row.range.ui.format);
    bool changed = false;
    if constexpr (std::is_same_v<T, float>)
        changed = sliderFloat(label.c_str(), &(settings.*Member), float(min), float(max), format.c_str(), flags);
    else
        changed = sliderInt(label.c_str(), &(settings.*Member), int(min), int(max), format.c_str(), flags);
    noteField(row, "slider", min, max);
    fieldTooltip(row.help);
    return changed;
}

// A combo over the enum's names, or over `values` in that order, each shown as `entryLabel`
// gives it (the tone-map operators' display names).
template <auto Member, typename Sub, typename Enum = typename MemberOf<decltype(Member)>::Type, std::size_t N = 0>
bool fieldCombo(Sub& settings, const std::array<Enum, N>& values = {}, const char* (*entryLabel)(Enum) = nullptr)
{
    static_assert(std::is_same_v<Sub, typename MemberOf<decltype(Member)>::Struct> && std::is_enum_v<Enum>);
    const auto& row = settingRow<Member>();
    Enum& value = settings.*Member;
    auto shown = [entryLabel](Enum v) { return entryLabel ? std::string(entryLabel(v)) : std::string(enumName(v)); };
    bool changed = false;
    if (Combo combo(fieldLabel(row).c_str(), shown(value).c_str()); combo) {
        auto entry = [&](Enum v) {
            if (combo.entry(shown(v).c_str(), v == value)) {
                changed = v != value;
                value = v;
            }
        };
        if constexpr (N > 0)
            for (Enum v : values) entry(v);
        else
            for (std::string_view name : enumChoices<Enum>()) entry(*parseEnum<Enum>(name));
    }
    noteField(row, "combo");
    fieldTooltip(row.help);
    return changed;
}

// Linear r, g, b fields and an sRGB swatch (colourEdit3) for a colour setting.
template <auto Member, typename Sub>
bool fieldColour(Sub& settings)
{
    static_assert(std::is_same_v<Sub, typename MemberOf<decltype(Member)>::Struct>);
    const auto& row = settingRow<Member>();
    const bool changed = colourEdit3(fieldLabel(row).c_str(), &(settings.*Member).x);
    noteField(row, "colour");
    fieldTooltip(row.help);
    return changed;
}

} // namespace iblab::ui
