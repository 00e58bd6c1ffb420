#pragma once
// The one way an enum gets its names, for JSON, the command line, the UI and reports.
// Next to each enum that has names, a specialisation lists them:
//
//   template <> struct EnumNames<GeometryTerm> {
//       static constexpr std::array<EnumName<GeometryTerm>, 4> entries{{
//           {GeometryTerm::SchlickGGX, "schlick-ggx"}, ..., {GeometryTerm::SchlickGGX, "schlick"}}};
//   };
//
// The first entry of a value is its one spelling, written everywhere; later entries of the
// same value are older spellings that are still read (presets and scripts saved before a
// rename keep loading), never written or offered.
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace iblab {

template <typename Enum>
struct EnumName {
    Enum value;
    std::string_view name;
};

template <typename Enum>
struct EnumNames; // specialised next to each enum

template <typename Enum>
constexpr std::string_view enumName(Enum value)
{
    for (const auto& entry : EnumNames<Enum>::entries)
        if (entry.value == value) return entry.name;
    return "?";
}

template <typename Enum>
constexpr std::optional<Enum> parseEnum(std::string_view name)
{
    for (const auto& entry : EnumNames<Enum>::entries)
        if (entry.name == name) return entry.value;
    return std::nullopt;
}

// The canonical names in declaration order of the table, aliases left out.
template <typename Enum>
std::vector<std::string_view> enumChoices()
{
    std::vector<std::string_view> names;
    for (const auto& entry : EnumNames<Enum>::entries)
        if (enumName(entry.value) == entry.name) names.push_back(entry.name);
    return names;
}

// "a, b or c", for error messages and help texts.
template <typename Enum>
std::string enumChoicesText()
{
    const std::vector<std::string_view> names = enumChoices<Enum>();
    std::string text;
    for (std::size_t i = 0; i < names.size(); ++i) {
        if (i > 0) text += i + 1 == names.size() ? " or " : ", ";
        text += names[i];
    }
    return text;
}

} // namespace iblab
