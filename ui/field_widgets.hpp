#pragma once
// Panel controls drawn from a setting's table row (io/settings_fields.hpp): the row's label
// names the control (and its script path), its help is the tooltip, its range bounds the
// slider, an enum's names fill the combo. A panel adds layout, formats and enabling rules.
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>

#include <imgui.h>

#include "io/settings_fields.hpp"
#include "ui/widgets.hpp"

namespace iblab::ui {

template <typename Settings>
const Field<Settings>& fieldRow(const FieldTable<Settings>& table, std::string_view key)
{
    const Field<Settings>* field = findField(table, key);
    if (!field) throw std::logic_error("no setting " + std::string(key));
    return *field;
}

inline void fieldTooltip(std::string_view help)
{
    if (!help.empty() && tooltipWanted()) ImGui::SetTooltip("%.*s", int(help.size()), help.data());
}

template <typename Settings>
bool fieldCheckbox(const FieldTable<Settings>& table, std::string_view key, Settings& settings)
{
    const Field<Settings>& field = fieldRow(table, key);
    bool& value = std::get<std::function<bool&(Settings&)>>(field.ref)(settings);
    const bool changed = checkbox(std::string(field.label).c_str(), &value);
    fieldTooltip(field.help);
    return changed;
}

template <typename Settings>
bool fieldSlider(const FieldTable<Settings>& table, std::string_view key, Settings& settings, const char* format = "%.3f",
                 ImGuiSliderFlags flags = 0)
{
    const Field<Settings>& field = fieldRow(table, key);
    float& value = std::get<std::function<float&(Settings&)>>(field.ref)(settings);
    const bool changed = sliderFloat(std::string(field.label).c_str(), &value, float(field.range.min), float(field.range.max), format, flags);
    fieldTooltip(field.help);
    return changed;
}

template <typename Settings>
bool fieldCombo(const FieldTable<Settings>& table, std::string_view key, Settings& settings)
{
    const Field<Settings>& field = fieldRow(table, key);
    const auto& names = std::get<EnumFieldRef<Settings>>(field.ref);
    const std::string current(names.get(settings));
    bool changed = false;
    if (Combo combo(std::string(field.label).c_str(), current.c_str()); combo)
        for (std::string_view choice : names.choices)
            if (combo.entry(std::string(choice).c_str(), choice == current)) {
                changed = choice != current;
                names.set(settings, choice);
            }
    fieldTooltip(field.help);
    return changed;
}

} // namespace iblab::ui
