#pragma once
// Command-line options made from setting descriptions (io/settings_fields.hpp): the option's
// name, form, help, default and range check all come from the field's table row.
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "io/settings_fields.hpp"

namespace iblab::app {

// Range text for --help, "[1..4096]", or empty.
inline std::string rangeHint(const FieldRange& range)
{
    if (!std::isfinite(range.min) || !std::isfinite(range.max)) return {};
    return " [" + rangeText(range).substr(std::string("must be ").size()) + "]";
}

// Applies `text` to the field of `target`, turning a bad value or one outside the field's
// range into CLI11's validation error, which names the option once ("--metallic:
// material.metallic: must be 0..1, got -1.0"; the range's own error named it again).
template <typename Settings>
void applyFieldText(const Field<Settings>& field, Settings& target, const std::string& text)
{
    Settings candidate = target;
    try {
        setFieldFromText(field, candidate, text);
    } catch (const std::exception& e) {
        throw CLI::ValidationError(field.cli, e.what());
    }
    if (const std::optional<std::string> problem = rangeProblem(field, candidate)) throw CLI::ValidationError(field.cli, *problem);
    target = std::move(candidate);
}

// Binds the field's option (Value, Flag or NegatedFlag) to `target`, whose current value is
// shown as the default.
template <typename Settings>
CLI::Option* addFieldOption(CLI::App& command, const Field<Settings>& field, Settings& target)
{
    std::string help = std::string(field.help) + rangeHint(field.range);
    if (const auto* names = std::get_if<EnumFieldRef<Settings>>(&field.ref); names && help.find('|') == std::string::npos) {
        help += ":";
        for (std::size_t i = 0; i < names->choices.size(); ++i) help += (i == 0 ? " " : "|") + std::string(names->choices[i]);
    }
    switch (field.cliForm) {
    case CliForm::Value:
        return command
            .add_option_function<std::string>(
                field.cli, [&field, &target](const std::string& text) { applyFieldText(field, target, text); }, help)
            ->default_str(fieldText(field, target));
    case CliForm::Flag:
    case CliForm::NegatedFlag: {
        const std::string value = field.cliForm == CliForm::Flag ? "on" : "off";
        return command.add_flag_callback(field.cli, [&field, &target, value] { applyFieldText(field, target, value); }, help);
    }
    case CliForm::None: break;
    }
    return nullptr;
}

// Every Value/Flag option of the table bound to `target` (fields with CliForm::None are
// left to the caller, which gives them their special forms).
template <typename Settings>
void addFieldOptions(CLI::App& command, const FieldTable<Settings>& table, Settings& target)
{
    for (const auto& field : table) addFieldOption(command, field, target);
}

// Options recorded as text, for settings that start from something chosen later on the same
// command line (a preset): apply them with applyRecorded once it is known.
template <typename Settings>
class RecordedFieldOptions {
public:
    void add(CLI::App& command, const FieldTable<Settings>& table)
    {
        for (const auto& field : table) {
            if (field.cliForm != CliForm::Value) continue;
            command.add_option_function<std::string>(
                field.cli, [this, &field](const std::string& text) { given_.emplace_back(&field, text); },
                std::string(field.help) + rangeHint(field.range));
        }
    }
    // Throws iblab::Error naming the option and the problem.
    void applyTo(Settings& settings) const
    {
        for (const auto& [field, text] : given_) {
            try {
                setFieldFromText(*field, settings, text);
            } catch (const std::exception& e) {
                throw Error(field->cli, e.what());
            }
        }
    }

private:
    std::vector<std::pair<const Field<Settings>*, std::string>> given_;
};

} // namespace iblab::app
