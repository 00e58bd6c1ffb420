// Presets and captures' settings (app/preset_json): the bake travels with the frame settings,
// a convention is recognised again, and file paths survive a move of the preset.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "frame/conventions.hpp"
#include "io/atomic_file.hpp"
#include "preset_json.hpp"

namespace iblab::app {
namespace {

namespace fs = std::filesystem;

struct TempDir {
    fs::path path = fs::temp_directory_path() / ("iblab-preset-test-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "-" +
                                                 ::testing::UnitTest::GetInstance()->current_test_info()->name());
    TempDir() { fs::create_directories(path); }
    ~TempDir() { fs::remove_all(path); }
};

// Saved under LearnOpenGL's convention, a preset reads back its bake and is LearnOpenGL again;
// without "bake" in the file it read as iblab's default bake and convention.
TEST(PresetJson, CarriesTheBakeAndItsConvention)
{
    TempDir dir;
    const ConventionPreset* learnopengl = findConvention("learnopengl");
    ASSERT_NE(learnopengl, nullptr);
    FrameSettings settings;
    applyConvention(*learnopengl, settings.sampling);
    const bake::BakeSettings bake = conventionBakeSettings(*learnopengl);
    const fs::path file = dir.path / "look.json";
    writeTextFileAtomic(file.string(), presetJsonText(settings, bake, file));
    const Preset read = readPreset(file);
    EXPECT_EQ(read.settings, settings);
    ASSERT_TRUE(read.bake.has_value());
    EXPECT_EQ(bake::toJsonText(*read.bake), bake::toJsonText(bake));
    EXPECT_EQ(matchingConvention(*read.bake, read.settings.sampling), "learnopengl");
    EXPECT_EQ(matchingConvention(bake::defaultPreset(), FrameSettings{}.sampling), "iblab");
    // A preset written before the bake was saved still loads, leaving the bake alone.
    writeTextFileAtomic(file.string(), "{\"material\": {\"roughness\": 0.5}}");
    EXPECT_FALSE(readPreset(file).bake.has_value());
    // A bad bake value names its key.
    writeTextFileAtomic(file.string(), "{\"bake\": {\"prefilter\": {\"levels\": \"many\"}}}");
    try {
        readPreset(file);
        ADD_FAILURE() << "a bad bake value was accepted";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("bake.prefilter.levels"), std::string::npos) << e.what();
    }
}

// A preset beside its model finds it after both move (the path is relative to the preset);
// a preset moved alone finds it at its absolute path.
TEST(PresetJson, ModelPathsWorkFromAnotherDirectory)
{
    TempDir dir;
    fs::create_directories(dir.path / "a" / "models");
    std::ofstream(dir.path / "a" / "models" / "m.glb") << "x";
    FrameSettings settings;
    settings.scene.kind = SceneKind::Model;
    settings.scene.modelPath = (dir.path / "a" / "models" / "m.glb").string();
    settings.environment.source = "builtin:studio";
    const fs::path file = dir.path / "a" / "look.json";
    writeTextFileAtomic(file.string(), presetJsonText(settings, bake::defaultPreset(), file));
    EXPECT_NE(readTextFile(file.string()).find("\"models/m.glb\""), std::string::npos) << readTextFile(file.string());

    // Moved with its model: found beside it, not at the old place.
    fs::rename(dir.path / "a", dir.path / "b");
    const Preset moved = readPreset(dir.path / "b" / "look.json");
    EXPECT_EQ(fs::path(moved.settings.scene.modelPath), dir.path / "b" / "models" / "m.glb");

    // Moved alone: the absolute path it was saved with.
    fs::create_directories(dir.path / "c");
    fs::rename(dir.path / "b" / "look.json", dir.path / "c" / "look.json");
    fs::rename(dir.path / "b", dir.path / "a");
    const Preset alone = readPreset(dir.path / "c" / "look.json");
    EXPECT_EQ(fs::path(alone.settings.scene.modelPath), dir.path / "a" / "models" / "m.glb");
    // Builtin environments are names, not paths.
    EXPECT_EQ(alone.settings.environment.source, settings.environment.source);
}

} // namespace
} // namespace iblab::app
