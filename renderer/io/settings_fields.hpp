#pragma once
// One description per setting: its JSON key, command-line option, label, help and valid
// range, with a reference into the settings struct. JSON (presets, sidecars, the bake cache
// key), the command line (app/field_options.hpp), validation and the UI's tooltips and
// ranges, labels and slider formats all read the same description, so a setting is added in
// one table row; its default stays where it belongs, in the struct's member initialiser.
#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "ibl/enum_names.hpp"
#include "io/error.hpp"

namespace iblab {

// How a field appears on the command line.
enum class CliForm {
    None,        // not an option (set through JSON or the UI only)
    Value,       // --name VALUE (booleans take on/off, true/false, 1/0)
    Flag,        // --name alone sets a boolean true
    NegatedFlag, // --name alone sets a boolean false ("--no-pdf-filtering")
};

template <typename Settings>
struct EnumFieldRef {
    std::function<std::string_view(const Settings&)> get;
    std::function<bool(Settings&, std::string_view)> set; // false for an unknown name
    std::vector<std::string_view> choices;
    std::function<const void*(const Settings&)> address; // the member itself (fieldAddress)
};

// A list of numbers: a JSON array, "a,b,c" on the command line (mip sample factors).
using NumberList = std::vector<double>;

template <typename Settings>
using FieldRef = std::variant<std::function<bool&(Settings&)>, std::function<int&(Settings&)>, std::function<float&(Settings&)>,
                              std::function<double&(Settings&)>, std::function<std::int64_t&(Settings&)>,
                              std::function<std::string&(Settings&)>, std::function<glm::vec3&(Settings&)>,
                              std::function<NumberList&(Settings&)>, EnumFieldRef<Settings>>;

// How a panel shows a number. The slider spans the valid range unless the row names a
// narrower span: where the whole range would leave a slider useless (an angle valid at any
// value, a distance of 1e-5..1e6) or a documented part of it is the useful one.
struct FieldUi {
    std::string_view format = {}; // printf format of the slider ("%.1f deg"); empty: ImGui's default
    double min = std::numeric_limits<double>::quiet_NaN(); // NaN: the valid range's end
    double max = std::numeric_limits<double>::quiet_NaN();
    bool logarithmic = false;
};

struct FieldRange {
    double min = -std::numeric_limits<double>::infinity();
    double max = std::numeric_limits<double>::infinity();
    // A value outside [min, max] that is also valid, with its meaning: "0 = from the source".
    std::optional<double> special = std::nullopt;
    std::string_view specialMeaning = {};
    bool powerOfTwo = false; // face sizes, sample counts of MSAA
    FieldUi ui = {};         // a list's range is each element's
};

// The span of a number's slider: the row's ui span where it has one, else its valid range.
inline double sliderMin(const FieldRange& range) { return std::isnan(range.ui.min) ? range.min : range.ui.min; }
inline double sliderMax(const FieldRange& range) { return std::isnan(range.ui.max) ? range.max : range.ui.max; }

template <typename Settings>
struct Field {
    std::string key;        // JSON path, "prefilter.face_size"
    std::string_view label; // what the UI shows
    std::string_view help;  // the CLI's help text and the UI's tooltip
    FieldRef<Settings> ref;
    FieldRange range = {};
    std::string cli = {};   // "--prefilter-size"
    CliForm cliForm = CliForm::None;
    std::string cliPrefix = {}; // "b-" for a nested table's "--b-samples" (appendNested)
};

template <typename Settings>
using FieldTable = std::vector<Field<Settings>>;

// A reference to a member, as a captureless lambda: [](S& s) -> auto& { return s.a.b; }.
// Enums become name-based references through their EnumNames.
template <typename Settings, typename Access>
FieldRef<Settings> fieldRef(Access access)
{
    using T = std::remove_reference_t<decltype(access(std::declval<Settings&>()))>;
    if constexpr (std::is_enum_v<T>) {
        return EnumFieldRef<Settings>{
            [access](const Settings& s) { return enumName(access(const_cast<Settings&>(s))); },
            [access](Settings& s, std::string_view name) {
                const std::optional<T> value = parseEnum<T>(name);
                if (value) access(s) = *value;
                return value.has_value();
            },
            enumChoices<T>(), [access](const Settings& s) -> const void* { return &access(const_cast<Settings&>(s)); }};
    } else {
        return std::function<T&(Settings&)>(access);
    }
}

// The fields of a nested struct (the frame's sampling block, also its compare block) as
// fields of the outer one, under a key prefix ("view.compare.") and an option prefix.
template <typename Outer, typename Inner, typename Access>
void appendNested(FieldTable<Outer>& out, const FieldTable<Inner>& inner, Access access, std::string_view keyPrefix,
                  std::string_view cliPrefix)
{
    for (const Field<Inner>& field : inner) {
        Field<Outer> nested{.key = std::string(keyPrefix) + field.key, .label = field.label, .help = field.help, .ref = {},
                            .range = field.range, .cli = field.cli, .cliForm = field.cliForm, .cliPrefix = {}};
        // "--samples" -> "--b-samples"
        if (!field.cli.empty() && !cliPrefix.empty()) {
            nested.cli = "--" + std::string(cliPrefix) + field.cli.substr(2);
            nested.cliPrefix = std::string(cliPrefix) + field.cliPrefix;
        }
        nested.ref = std::visit(
            [&](const auto& ref) -> FieldRef<Outer> {
                using Ref = std::decay_t<decltype(ref)>;
                if constexpr (std::is_same_v<Ref, EnumFieldRef<Inner>>) {
                    return EnumFieldRef<Outer>{[ref, access](const Outer& o) { return ref.get(access(const_cast<Outer&>(o))); },
                                               [ref, access](Outer& o, std::string_view name) { return ref.set(access(o), name); },
                                               ref.choices,
                                               [ref, access](const Outer& o) { return ref.address(access(const_cast<Outer&>(o))); }};
                } else {
                    using T = std::remove_reference_t<decltype(ref(std::declval<Inner&>()))>;
                    return std::function<T&(Outer&)>([ref, access](Outer& o) -> T& { return ref(access(o)); });
                }
            },
            field.ref);
        out.push_back(std::move(nested));
    }
}

template <typename Settings>
const Field<Settings>* findField(const FieldTable<Settings>& table, std::string_view key)
{
    for (const auto& field : table)
        if (field.key == key) return &field;
    return nullptr;
}

// The address of the member the field describes, in `settings`.
template <typename Settings>
const void* fieldAddress(const Field<Settings>& field, const Settings& settings)
{
    return std::visit(
        [&](const auto& ref) -> const void* {
            if constexpr (std::is_same_v<std::decay_t<decltype(ref)>, EnumFieldRef<Settings>>)
                return ref.address(settings);
            else
                return &ref(const_cast<Settings&>(settings));
        },
        field.ref);
}

// The row that describes the member at `address` inside `settings`, null for none: how a
// member pointer finds its row (ui/field_widgets.hpp), since a row reaches its member
// through a function rather than naming it.
template <typename Settings>
const Field<Settings>* findFieldAt(const FieldTable<Settings>& table, const Settings& settings, const void* address)
{
    for (const auto& field : table)
        if (fieldAddress(field, settings) == address) return &field;
    return nullptr;
}

// "1,1,2": the shortest text that reads back as each number.
inline std::string numberListText(const NumberList& list)
{
    std::string text;
    for (std::size_t i = 0; i < list.size(); ++i) {
        char buffer[32];
        const auto end = std::to_chars(buffer, buffer + sizeof buffer, list[i]).ptr;
        text += (i == 0 ? "" : ",") + std::string(buffer, end);
    }
    return text;
}

// Numbers separated by commas ("" is the empty list); throws std::runtime_error otherwise.
inline NumberList parseNumberList(std::string_view text)
{
    NumberList list;
    if (text.empty()) return list;
    for (std::size_t begin = 0;;) {
        const std::size_t comma = std::min(text.find(',', begin), text.size());
        const std::string_view item = text.substr(begin, comma - begin);
        double value = 0.0;
        const auto [end, error] = std::from_chars(item.data(), item.data() + item.size(), value);
        if (item.empty() || error != std::errc() || end != item.data() + item.size())
            throw std::runtime_error("expected numbers separated by commas, got \"" + std::string(text) + "\"");
        list.push_back(value);
        if (comma == text.size()) return list;
        begin = comma + 1;
    }
}

// The field's value as JSON.
template <typename Settings>
nlohmann::ordered_json fieldJson(const Field<Settings>& field, const Settings& settings)
{
    Settings& s = const_cast<Settings&>(settings); // the references only read here
    return std::visit(
        [&](const auto& ref) -> nlohmann::ordered_json {
            using Ref = std::decay_t<decltype(ref)>;
            if constexpr (std::is_same_v<Ref, EnumFieldRef<Settings>>) {
                return std::string(ref.get(settings));
            } else {
                const auto& value = ref(s);
                if constexpr (std::is_same_v<std::decay_t<decltype(value)>, glm::vec3>)
                    return nlohmann::ordered_json::array({value.x, value.y, value.z});
                else
                    return value;
            }
        },
        field.ref);
}

// Every field, nested by the dots of its key, in table order.
template <typename Settings>
nlohmann::ordered_json toJson(const FieldTable<Settings>& table, const Settings& settings)
{
    nlohmann::ordered_json root = nlohmann::ordered_json::object();
    for (const auto& field : table) {
        nlohmann::ordered_json* node = &root;
        std::string_view key = field.key;
        for (std::size_t dot = key.find('.'); dot != std::string_view::npos; dot = key.find('.')) {
            node = &(*node)[std::string(key.substr(0, dot))];
            key.remove_prefix(dot + 1);
        }
        (*node)[std::string(key)] = fieldJson(field, settings);
    }
    return root;
}

// Sets the field from JSON; throws std::runtime_error saying what was expected.
template <typename Settings>
void setFieldFromJson(const Field<Settings>& field, Settings& settings, const nlohmann::json& value)
{
    std::visit(
        [&](const auto& ref) {
            using Ref = std::decay_t<decltype(ref)>;
            if constexpr (std::is_same_v<Ref, EnumFieldRef<Settings>>) {
                const std::string name = value.get<std::string>();
                if (!ref.set(settings, name)) {
                    std::string expected;
                    for (std::size_t i = 0; i < ref.choices.size(); ++i)
                        expected += (i == 0 ? "" : i + 1 == ref.choices.size() ? " or " : ", ") + std::string(ref.choices[i]);
                    throw std::runtime_error("unknown value \"" + name + "\" (expected " + expected + ")");
                }
            } else {
                auto& target = ref(settings);
                using T = std::decay_t<decltype(target)>;
                if constexpr (std::is_same_v<T, glm::vec3>) {
                    if (!value.is_array() || value.size() != 3) throw std::runtime_error("expected [r, g, b]");
                    target = glm::vec3(value[0].get<float>(), value[1].get<float>(), value[2].get<float>());
                } else if constexpr (std::is_same_v<T, NumberList>) {
                    // Presets and caches written before lists were arrays hold the text "1,1,2".
                    if (value.is_string()) {
                        target = parseNumberList(value.get<std::string>());
                        return;
                    }
                    if (!value.is_array()) throw std::runtime_error("expected an array of numbers");
                    NumberList list;
                    for (const auto& item : value) {
                        if (!item.is_number()) throw std::runtime_error("expected an array of numbers");
                        list.push_back(item.get<double>());
                    }
                    target = std::move(list);
                } else if constexpr (std::is_same_v<T, bool>) {
                    if (!value.is_boolean()) throw std::runtime_error("expected true or false");
                    target = value.get<bool>();
                } else {
                    target = value.get<T>();
                }
            }
        },
        field.ref);
}

// Reads every field present in `json` (missing ones keep their values). Throws
// std::runtime_error naming "<what>.<key>" on a value of the wrong type or name.
template <typename Settings>
void fromJson(const FieldTable<Settings>& table, const nlohmann::json& json, Settings& settings, std::string_view what)
{
    for (const auto& field : table) {
        const nlohmann::json* node = &json;
        std::string_view key = field.key;
        bool present = true;
        for (std::size_t dot = key.find('.'); present; dot = key.find('.')) {
            const std::string part(dot == std::string_view::npos ? key : key.substr(0, dot));
            present = node->is_object() && node->contains(part);
            if (present) node = &node->at(part);
            if (dot == std::string_view::npos) break;
            key.remove_prefix(dot + 1);
        }
        if (!present) continue;
        try {
            setFieldFromJson(field, settings, *node);
        } catch (const std::exception& e) {
            throw std::runtime_error(std::string(what) + "." + field.key + ": " + e.what());
        }
    }
}

// Parses command-line text into the field: numbers, on/off for booleans, enum names,
// "r,g,b" for colours, "a,b,c" for lists. Throws std::runtime_error saying what was expected.
template <typename Settings>
void setFieldFromText(const Field<Settings>& field, Settings& settings, std::string_view text)
{
    auto number = [&](auto& target) {
        using T = std::decay_t<decltype(target)>;
        T value{};
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (error != std::errc() || end != text.data() + text.size())
            throw std::runtime_error("expected a " + std::string(std::is_integral_v<T> ? "whole number" : "number") + ", got \"" +
                                     std::string(text) + "\"");
        target = value;
    };
    std::visit(
        [&](const auto& ref) {
            using Ref = std::decay_t<decltype(ref)>;
            if constexpr (std::is_same_v<Ref, EnumFieldRef<Settings>>) {
                setFieldFromJson(field, settings, nlohmann::json(std::string(text)));
            } else {
                auto& target = ref(settings);
                using T = std::decay_t<decltype(target)>;
                if constexpr (std::is_same_v<T, bool>) {
                    if (text == "on" || text == "true" || text == "1" || text == "yes") target = true;
                    else if (text == "off" || text == "false" || text == "0" || text == "no") target = false;
                    else throw std::runtime_error("expected on or off, got \"" + std::string(text) + "\"");
                } else if constexpr (std::is_same_v<T, std::string>) {
                    target = std::string(text);
                } else if constexpr (std::is_same_v<T, NumberList>) {
                    target = parseNumberList(text);
                } else if constexpr (std::is_same_v<T, glm::vec3>) {
                    glm::vec3 v;
                    std::string_view rest = text;
                    for (int i = 0; i < 3; ++i) {
                        const std::size_t comma = rest.find(',');
                        if ((comma == std::string_view::npos) != (i == 2)) throw std::runtime_error("expected r,g,b, got \"" + std::string(text) + "\"");
                        const std::string_view part = rest.substr(0, comma);
                        const auto [end, error] = std::from_chars(part.data(), part.data() + part.size(), v[i]);
                        if (error != std::errc() || end != part.data() + part.size())
                            throw std::runtime_error("expected r,g,b, got \"" + std::string(text) + "\"");
                        if (comma != std::string_view::npos) rest.remove_prefix(comma + 1);
                    }
                    target = v;
                } else {
                    number(target);
                }
            }
        },
        field.ref);
}

// The field's value as the text setFieldFromText reads (CLI defaults, UI).
template <typename Settings>
std::string fieldText(const Field<Settings>& field, const Settings& settings)
{
    if (const auto* list = std::get_if<std::function<NumberList&(Settings&)>>(&field.ref))
        return numberListText((*list)(const_cast<Settings&>(settings)));
    const nlohmann::ordered_json j = fieldJson(field, settings);
    if (j.is_string()) return j.get<std::string>();
    if (j.is_boolean()) return j.get<bool>() ? "on" : "off";
    if (j.is_array()) return j[0].dump() + "," + j[1].dump() + "," + j[2].dump();
    return j.dump();
}

// The numeric value of a number field, nullopt for the others.
template <typename Settings>
std::optional<double> fieldNumber(const Field<Settings>& field, const Settings& settings)
{
    const nlohmann::ordered_json j = fieldJson(field, settings);
    if (j.is_number()) return j.get<double>();
    return std::nullopt;
}

// "must be 1..4096" (and ", or 0 = from the source").
inline std::string rangeText(const FieldRange& range)
{
    auto num = [](double v) { return nlohmann::json(v == std::floor(v) && std::abs(v) < 1e15 ? nlohmann::json(std::int64_t(v)) : nlohmann::json(v)).dump(); };
    std::string text;
    const bool lower = std::isfinite(range.min), upper = std::isfinite(range.max);
    if (lower && upper) text = "must be " + num(range.min) + ".." + num(range.max);
    else if (lower) text = "must be >= " + num(range.min);
    else if (upper) text = "must be <= " + num(range.max);
    else text = "must be finite";
    if (range.powerOfTwo) text = (lower && upper ? "must be a power of two in " + text.substr(std::string("must be ").size()) : text + " and a power of two");
    if (range.special) text += ", or " + num(*range.special) + " (" + std::string(range.specialMeaning) + ")";
    return text;
}

// "<key>: must be 1..4096, got 0" when the field is a number outside its range (NaN and
// infinities are outside every range), nullopt otherwise.
template <typename Settings>
std::optional<std::string> rangeProblem(const Field<Settings>& field, const Settings& settings)
{
    if (const auto* list = std::get_if<std::function<NumberList&(Settings&)>>(&field.ref)) {
        for (const double item : (*list)(const_cast<Settings&>(settings)))
            if (!std::isfinite(item) || item < field.range.min || item > field.range.max)
                return field.key + ": each " + rangeText(field.range) + ", got " + numberListText((*list)(const_cast<Settings&>(settings)));
        return std::nullopt;
    }
    const std::optional<double> value = fieldNumber(field, settings);
    if (!value) return std::nullopt;
    const bool inRange = *value >= field.range.min && *value <= field.range.max &&
                         (!field.range.powerOfTwo || (*value == std::floor(*value) && std::has_single_bit(std::uint64_t(*value))));
    if (std::isfinite(*value) && (inRange || (field.range.special && *value == *field.range.special))) return std::nullopt;
    // JSON, which fieldText writes, has no NaN or infinity: it would say "got null".
    const std::string got = std::isnan(*value) ? "nan" : std::isinf(*value) ? (*value > 0 ? "inf" : "-inf") : fieldText(field, settings);
    return field.key + ": " + rangeText(field.range) + ", got " + got;
}

// Throws iblab::Error(what, rangeProblem) for the first number outside its range.
template <typename Settings>
void validateRanges(const FieldTable<Settings>& table, const Settings& settings, std::string_view what)
{
    for (const auto& field : table)
        if (const std::optional<std::string> problem = rangeProblem(field, settings)) throw Error(std::string(what), *problem);
}

// Moves every number outside its field's range to the nearest end of it (NaN to the lower
// end) and returns whether any moved. For edits that bypass the text checks: ImGui keeps a
// value typed into a slider (Ctrl+click) as typed, -5 for a roughness or 1e30 for metallic.
// Power-of-two fields (sizes) have no nearest end that is valid: they are left to
// validateRanges.
template <typename Settings>
bool clampToRanges(const FieldTable<Settings>& table, Settings& settings)
{
    bool moved = false;
    for (const auto& field : table) {
        if (field.range.powerOfTwo || !rangeProblem(field, settings)) continue;
        auto clampNumber = [&field](auto& value) {
            using T = std::decay_t<decltype(value)>;
            const double v = double(value);
            const double clamped = std::isnan(v) ? field.range.min : std::clamp(v, field.range.min, field.range.max);
            value = T(clamped);
        };
        std::visit(
            [&](const auto& ref) {
                using Ref = std::decay_t<decltype(ref)>;
                if constexpr (std::is_same_v<Ref, std::function<int&(Settings&)>> || std::is_same_v<Ref, std::function<float&(Settings&)>> ||
                              std::is_same_v<Ref, std::function<double&(Settings&)>> ||
                              std::is_same_v<Ref, std::function<std::int64_t&(Settings&)>>) {
                    clampNumber(ref(settings));
                    moved = true;
                }
            },
            field.ref);
    }
    return moved;
}

} // namespace iblab
