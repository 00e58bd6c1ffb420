#pragma once
// Command-line options made from setting descriptions (io/settings_fields.hpp): the option's
// name, form, help, default and range check all come from the field's table row.
#include <cstdint>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "io/settings_fields.hpp"

namespace iblab::app {

// Range text for --help, "[1..4096]", or empty. A bound past 1e15 stands for "no bound"
// (the bake's step size), which --help does not spell out in 19 digits.
inline std::string rangeHint(FieldRange range)
{
    if (std::abs(range.max) >= 1e15) range.max = std::numeric_limits<double>::infinity();
    if (!std::isfinite(range.min) && !std::isfinite(range.max)) return {};
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

// The value's form in --help: FLOAT, INT, on|off, NAME (the choices follow in the help), R,G,B,
// LIST (numbers separated by commas) or TEXT.
template <typename Settings>
std::string fieldTypeName(const Field<Settings>& field)
{
    return std::visit(
        [](const auto& ref) -> std::string {
            using Ref = std::decay_t<decltype(ref)>;
            if constexpr (std::is_same_v<Ref, EnumFieldRef<Settings>>) {
                return "NAME";
            } else {
                using T = std::decay_t<decltype(ref(std::declval<Settings&>()))>;
                if constexpr (std::is_same_v<T, bool>) return "on|off";
                else if constexpr (std::is_same_v<T, float> || std::is_same_v<T, double>) return "FLOAT";
                else if constexpr (std::is_integral_v<T>) return "INT";
                else if constexpr (std::is_same_v<T, glm::vec3>) return "R,G,B";
                else if constexpr (std::is_same_v<T, NumberList>) return "LIST";
                else return "TEXT";
            }
        },
        field.ref);
}

// A number as --help shows a default: at most 6 significant digits, so that a float's 0.3
// reads 0.3 and not its double expansion 0.30000001192092896.
inline std::string shortNumber(double value)
{
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", value);
    return text;
}

// The field's current value as --help shows it.
template <typename Settings>
std::string fieldDefaultText(const Field<Settings>& field, const Settings& settings)
{
    if (std::holds_alternative<std::function<NumberList&(Settings&)>>(field.ref)) return fieldText(field, settings);
    const nlohmann::ordered_json value = fieldJson(field, settings);
    if (value.is_number()) return shortNumber(value.get<double>());
    if (value.is_array()) return shortNumber(value[0].get<double>()) + "," + shortNumber(value[1].get<double>()) + "," + shortNumber(value[2].get<double>());
    return fieldText(field, settings);
}

// The help sentence: the table's text, the range and, for names, the choices.
template <typename Settings>
std::string fieldHelp(const Field<Settings>& field)
{
    std::string help = std::string(field.help) + rangeHint(field.range);
    if (const auto* names = std::get_if<EnumFieldRef<Settings>>(&field.ref); names && help.find('|') == std::string::npos) {
        help += ":";
        for (std::size_t i = 0; i < names->choices.size(); ++i) help += (i == 0 ? " " : "|") + std::string(names->choices[i]);
    }
    return help;
}

// The other form of a flag: "--multiscatter" <-> "--no-multiscatter", and within a prefix
// ("--b-no-pdf-filtering" <-> "--b-pdf-filtering") when `prefix` is "b-".
inline std::string oppositeFlag(const std::string& cli, std::string_view prefix = {})
{
    const std::string head = "--" + std::string(prefix);
    const std::string rest = cli.substr(head.size());
    return rest.starts_with("no-") ? head + rest.substr(3) : head + "no-" + rest;
}

// Binds the field's option (Value, Flag or NegatedFlag) to `target`, whose current value is
// shown as the default. A flag comes with its opposite ("--multiscatter,--no-multiscatter",
// "--no-pdf-filtering,--pdf-filtering"), so that either state can be asked for whatever the
// default, and a boolean value option with its "--no-" form ("--prefilter-mirror-copy off").
template <typename Settings>
CLI::Option* addFieldOption(CLI::App& command, const Field<Settings>& field, Settings& target)
{
    const std::string help = fieldHelp(field);
    switch (field.cliForm) {
    case CliForm::Value: {
        CLI::Option* option = command
                                  .add_option_function<std::string>(
                                      field.cli, [&field, &target](const std::string& text) { applyFieldText(field, target, text); }, help)
                                  ->type_name(fieldTypeName(field))
                                  ->default_str(fieldDefaultText(field, target));
        if (fieldTypeName(field) == "on|off")
            command.add_flag_callback(
                oppositeFlag(field.cli, field.cliPrefix), [&field, &target] { applyFieldText(field, target, "off"); },
                "Same as " + field.cli + " off");
        return option;
    }
    case CliForm::Flag:
    case CliForm::NegatedFlag: {
        // The flag's own name sets the state its form says; the opposite name the other one.
        const bool named = field.cliForm == CliForm::Flag;
        const std::string opposite = oppositeFlag(field.cli, field.cliPrefix);
        const bool namedIsDefault = (fieldText(field, target) == "on") == named;
        return command.add_flag_function(
            field.cli + ",!" + opposite,
            [&field, &target, named](std::int64_t count) { applyFieldText(field, target, (count > 0) == named ? "on" : "off"); },
            help + " (default: " + (namedIsDefault ? field.cli : opposite) + ")")
            // The last of "--multiscatter --no-multiscatter" wins, as for any other option
            // (CLI11 would add them up to 0).
            ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
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
            command
                .add_option_function<std::string>(
                    field.cli, [this, &field](const std::string& text) { given_.emplace_back(&field, text); }, fieldHelp(field))
                ->type_name(fieldTypeName(field));
            if (fieldTypeName(field) == "on|off")
                command.add_flag_callback(
                    oppositeFlag(field.cli, field.cliPrefix), [this, &field] { given_.emplace_back(&field, "off"); },
                    "Same as " + field.cli + " off");
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
