#include "preset_json.hpp"

#include <stdexcept>

#include <nlohmann/json.hpp>

#include "frame/conventions.hpp"
#include "io/atomic_file.hpp"
#include "io/builtin_environments.hpp"
#include "io/error.hpp"
#include "io/settings_fields.hpp"

namespace iblab::app {
namespace {

namespace fs = std::filesystem;

// The path settings hold files in, by their preset keys.
struct PathSetting {
    const char* key;
    std::string& (*ref)(FrameSettings&);
};
constexpr PathSetting kPathSettings[] = {
    {"environment.source", [](FrameSettings& s) -> std::string& { return s.environment.source; }},
    {"scene.model", [](FrameSettings& s) -> std::string& { return s.scene.modelPath; }},
};

bool isFilePath(const std::string& value) { return !value.empty() && !isBuiltinSpec(value); }

nlohmann::ordered_json& at(nlohmann::ordered_json& j, std::string_view dottedKey)
{
    nlohmann::ordered_json* node = &j;
    for (std::size_t dot; (dot = dottedKey.find('.')) != std::string_view::npos; dottedKey.remove_prefix(dot + 1))
        node = &(*node)[std::string(dottedKey.substr(0, dot))];
    return (*node)[std::string(dottedKey)];
}

std::string bakeKey(const bake::BakeSettings& bake) { return toJson(bake::bakeSettingsFields(), bake).dump(); }

} // namespace

std::string presetJsonText(const FrameSettings& settings, const bake::BakeSettings& bake, const fs::path& file)
{
    nlohmann::ordered_json j = nlohmann::ordered_json::parse(toJsonText(settings));
    std::error_code ignored;
    const fs::path directory = fs::weakly_canonical(fs::absolute(file).parent_path(), ignored);
    FrameSettings copy = settings;
    for (const PathSetting& path : kPathSettings) {
        const std::string& value = path.ref(copy);
        if (!isFilePath(value)) continue;
        std::error_code error;
        const fs::path absolute = fs::weakly_canonical(fs::absolute(value), error);
        if (error) continue;
        const fs::path relative = absolute.lexically_relative(directory);
        if (!relative.empty()) at(j, path.key) = relative.generic_string();
        j["absolute_paths"][path.key] = absolute.generic_string();
    }
    j["bake"] = toJson(bake::bakeSettingsFields(), bake);
    return j.dump(2);
}

Preset readPreset(const fs::path& file)
{
    Preset preset{frameSettingsFromJsonText(readTextFile(file.string())), std::nullopt};
    const nlohmann::json j = nlohmann::json::parse(readTextFile(file.string()));
    const fs::path directory = fs::absolute(file).parent_path();
    for (const PathSetting& path : kPathSettings) {
        std::string& value = path.ref(preset.settings);
        if (!isFilePath(value) || fs::path(value).is_absolute()) continue;
        std::error_code error;
        if (fs::exists(directory / value, error)) {
            value = (directory / value).lexically_normal().string();
        } else if (j.contains("absolute_paths") && j["absolute_paths"].is_object() && j["absolute_paths"].contains(path.key) &&
                   j["absolute_paths"][path.key].is_string() && fs::exists(j["absolute_paths"][path.key].get<std::string>(), error)) {
            value = j["absolute_paths"][path.key].get<std::string>();
        }
    }
    if (j.contains("bake")) {
        if (!j["bake"].is_object()) throw std::runtime_error("bake: expected a JSON object");
        bake::BakeSettings bake = bake::defaultPreset();
        fromJson(bake::bakeSettingsFields(), j["bake"], bake, "bake");
        try {
            bake::validate(bake);
        } catch (const Error& e) {
            throw std::runtime_error(e.what()); // the caller names the file
        }
        preset.bake = bake;
    }
    return preset;
}

std::string matchingConvention(const bake::BakeSettings& bake, const SamplingSettings& sampling)
{
    for (const ConventionPreset& convention : conventionPresets()) {
        SamplingSettings as = sampling;
        applyConvention(convention, as);
        // Which LUTs are baked beside the one the shading reads changes nothing drawn (the
        // lab's default bakes both; a convention only its own).
        bake::BakeSettings own = conventionBakeSettings(convention);
        const bool hasLut = convention.geometry == GeometryTerm::SchlickGGX ? bake.lut.schlickGgx : bake.lut.heightCorrelatedSmith;
        own.lut.schlickGgx = bake.lut.schlickGgx;
        own.lut.heightCorrelatedSmith = bake.lut.heightCorrelatedSmith;
        if (as == sampling && hasLut && bakeKey(own) == bakeKey(bake)) return std::string(convention.name);
    }
    return "";
}

} // namespace iblab::app
