// Every row of every settings table survives JSON (presets, sidecars, the bake cache key) and
// the command line: the test walks the tables, gives each field a value that is not its
// default, writes it, reads it into default settings and compares the whole struct. A new row
// is covered without being listed here.
#include <bit>
#include <cmath>
#include <string>
#include <type_traits>
#include <vector>

#include <CLI/CLI.hpp>
#include <gtest/gtest.h>

#include "bake/bake_settings.hpp"
#include "field_options.hpp"
#include "frame/settings.hpp"

namespace iblab {
namespace {

// A valid value of the field other than the one it has in `settings`.
template <typename Settings>
void setOtherValue(const Field<Settings>& field, Settings& settings)
{
    const FieldRange& range = field.range;
    auto number = [&](double current) {
        const double low = std::isfinite(range.min) ? range.min : current - 100.0;
        const double high = std::isfinite(range.max) ? range.max : current + 100.0;
        double value = low + 0.37 * (high - low);
        if (range.powerOfTwo) value = double(std::bit_floor(std::uint64_t(value)));
        if (value == current) value = range.powerOfTwo ? value / 2 : low + 0.61 * (high - low);
        return value;
    };
    std::visit(
        [&](const auto& ref) {
            using Ref = std::decay_t<decltype(ref)>;
            if constexpr (std::is_same_v<Ref, EnumFieldRef<Settings>>) {
                const std::string_view current = ref.get(settings);
                for (std::string_view choice : ref.choices)
                    if (choice != current) {
                        ref.set(settings, choice);
                        return;
                    }
            } else {
                auto& target = ref(settings);
                using T = std::decay_t<decltype(target)>;
                if constexpr (std::is_same_v<T, bool>) target = !target;
                else if constexpr (std::is_same_v<T, std::string>) target = target + "-other";
                else if constexpr (std::is_same_v<T, glm::vec3>) target = glm::vec3(0.25f, 0.5f, 0.75f) + target * 0.125f;
                else if constexpr (std::is_same_v<T, NumberList>) target = NumberList{0.5, 3.0, 1.25};
                else if constexpr (std::is_integral_v<T>) target = T(std::llround(number(double(target))));
                else target = T(number(double(target)));
            }
        },
        field.ref);
}

// The arguments that give the field its value in `settings`: "--name VALUE", or the flag's
// name or its opposite.
template <typename Settings>
std::vector<std::string> cliArguments(const Field<Settings>& field, const Settings& settings)
{
    const std::string text = fieldText(field, settings);
    if (field.cliForm == CliForm::Value) return {field.cli, text};
    const bool named = field.cliForm == CliForm::Flag;
    return {(text == "on") == named ? field.cli : app::oppositeFlag(field.cli, field.cliPrefix)};
}

template <typename Settings>
void expectEveryFieldRoundTrips(const FieldTable<Settings>& table)
{
    int viaCli = 0;
    for (const Field<Settings>& field : table) {
        SCOPED_TRACE(field.key);
        Settings changed;
        setOtherValue(field, changed);
        ASSERT_FALSE(changed == Settings{}) << "no other value found";
        ASSERT_FALSE(rangeProblem(field, changed)) << *rangeProblem(field, changed);

        Settings fromJsonText;
        fromJson(table, nlohmann::json::parse(toJson(table, changed).dump()), fromJsonText, "settings");
        EXPECT_TRUE(fromJsonText == changed) << "JSON: " << fieldText(field, fromJsonText) << " != " << fieldText(field, changed);

        // Rows without a generic option (CliForm::None) are JSON and UI only, or have an
        // option of app/cli.cpp's own that reads more forms (--env, --scene, --mip auto).
        if (field.cliForm == CliForm::None) continue;
        ++viaCli;
        CLI::App command;
        Settings parsed;
        for (const Field<Settings>& each : table)
            if (each.cliForm != CliForm::None) app::addFieldOption(command, each, parsed);
        std::vector<std::string> args = cliArguments(field, changed);
        std::vector<const char*> argv{"iblab"};
        for (const std::string& arg : args) argv.push_back(arg.c_str());
        ASSERT_NO_THROW(command.parse(int(argv.size()), argv.data())) << args[0];
        EXPECT_TRUE(parsed == changed) << "CLI " << args[0] << ": " << fieldText(field, parsed) << " != " << fieldText(field, changed);
    }
    EXPECT_GT(viaCli, 0);
}

TEST(SettingsRoundTrip, EveryFrameFieldSurvivesJsonAndTheCommandLine) { expectEveryFieldRoundTrips(frameSettingsFields()); }

TEST(SettingsRoundTrip, EveryBakeFieldSurvivesJsonAndTheCommandLine) { expectEveryFieldRoundTrips(bake::bakeSettingsFields()); }

// Presets and bake caches written while the factors were text still load.
TEST(SettingsRoundTrip, MipSampleFactorsReadTheirOldTextForm)
{
    bake::BakeSettings s;
    fromJson(bake::bakeSettingsFields(), nlohmann::json::parse(R"({"prefilter": {"mip_sample_scale": "0.5,1,4"}})"), s, "bake");
    EXPECT_EQ(s.prefilter.mipSampleScale, (NumberList{0.5, 1.0, 4.0}));
    fromJson(bake::bakeSettingsFields(), nlohmann::json::parse(R"({"prefilter": {"mip_sample_scale": ""}})"), s, "bake");
    EXPECT_TRUE(s.prefilter.mipSampleScale.empty());
    const nlohmann::json written = nlohmann::json::parse(bake::toJsonText(bake::BakeSettings{}, -1));
    EXPECT_EQ(written["prefilter"]["mip_sample_scale"], nlohmann::json::array({1.0, 1.0, 4.0}));
}

} // namespace
} // namespace iblab
