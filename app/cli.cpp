#include "cli.hpp"

#include "commands.hpp"

#include <chrono>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <optional>
#include <regex>
#include <sstream>

#include <CLI/CLI.hpp>
#include <glm/glm.hpp>

#include "field_options.hpp"
#include "frame/conventions.hpp"
#include "io/builtin_environments.hpp"
#include "io/environment.hpp"
#include "io/image_codec.hpp"
#include "gui_app.hpp"
#include "headless_render.hpp"
#include "ibl/tonemap.hpp"
#include "lab_session.hpp"

namespace iblab::app {
namespace {

// CLI11's help, without the "{false}" it appends to the negated name of a flag pair
// ("--multiscatter,--no-multiscatter{false}"): the pair's help says which is the default.
class HelpFormatter : public CLI::Formatter {
public:
    std::string make_option_name(const CLI::Option* option, bool positional) const override
    {
        std::string name = CLI::Formatter::make_option_name(option, positional);
        for (std::size_t open = name.find('{'); open != std::string::npos; open = name.find('{', open)) {
            const std::size_t close = name.find('}', open);
            if (close == std::string::npos) break;
            name.erase(open, close + 1 - open);
        }
        return name;
    }
    // CLI11 writes a checked range and a set of names after the type: "INT:INT in [1 - 16384]"
    // and "TEXT:{cpu,gpu}"; shown as "INT [1..16384]" and "{cpu,gpu}".
    std::string make_option_opts(const CLI::Option* option) const override
    {
        static const std::regex range(R"((INT|FLOAT):(?:INT|FLOAT) in \[([^ \]]+) - ([^ \]]+)\])");
        static const std::regex names(R"(TEXT:(\{[^}]*\}))");
        const std::string opts = std::regex_replace(CLI::Formatter::make_option_opts(option), range, "$1 [$2..$3]");
        return std::regex_replace(opts, names, "$1");
    }
};

// "0.9,0.6,0.5" (linear) or "#e6a08c" (sRGB-encoded, as colour pickers give it).
std::optional<glm::vec3> parseColour(const std::string& text)
{
    if (text.size() == 7 && text[0] == '#') {
        glm::vec3 colour;
        for (int c = 0; c < 3; ++c) {
            const std::string hex = text.substr(1 + std::size_t(c) * 2, 2);
            if (hex.find_first_not_of("0123456789abcdefABCDEF") != std::string::npos) return std::nullopt;
            const float encoded = float(std::stoi(hex, nullptr, 16)) / 255.0f;
            colour[c] = srgbToLinear(encoded);
        }
        return colour;
    }
    glm::vec3 colour;
    char comma1 = 0, comma2 = 0;
    std::istringstream in(text);
    if (!(in >> colour.r >> comma1 >> colour.g >> comma2 >> colour.b) || comma1 != ',' || comma2 != ',' || !in.eof()) return std::nullopt;
    if (glm::any(glm::lessThan(colour, glm::vec3(0.0f))) || glm::any(glm::greaterThan(colour, glm::vec3(1.0f)))) return std::nullopt;
    return colour;
}

// The field of the frame's table with this JSON key (settings.cpp); its help text and range
// serve the options that need a form of their own.
const Field<FrameSettings>& frameField(std::string_view key)
{
    const Field<FrameSettings>* field = findField(frameSettingsFields(), key);
    if (!field) throw std::logic_error("no frame setting " + std::string(key));
    return *field;
}

// The field's help and its range without the special -1, which the option spells "auto".
std::string mipHelp(const Field<FrameSettings>& field)
{
    FieldRange levels = field.range;
    levels.special.reset();
    return std::string(field.help) + rangeHint(levels);
}

// --mip LEVEL|auto, and --b-mip for the split view's B side.
void addMipOption(CLI::App& command, const std::string& option, std::string_view key, FrameSettings& settings)
{
    const Field<FrameSettings>& field = frameField(key);
    command
        .add_option_function<std::string>(
            option,
            [&field, &settings, option](const std::string& value) {
                if (value == "auto") {
                    setFieldFromText(field, settings, "-1");
                    return;
                }
                int level = -1;
                try {
                    level = std::stoi(value);
                } catch (const std::exception&) {
                    throw CLI::ValidationError(option, "expected a mip level or auto, got \"" + value + "\"");
                }
                if (level < 0) throw CLI::ValidationError(option, "a mip level is >= 0");
                applyFieldText(field, settings, value);
            },
            mipHelp(field))
        ->type_name("INT|auto")
        ->default_str("auto");
}

} // namespace

void addConventionOption(CLI::App& command, std::string& convention)
{
    command.add_option("--convention", convention, "Bake and shade as " + conventionNames() + " do (split sum)")
        ->type_name("NAME")
        ->check([](const std::string& name) {
            return findConvention(name) ? std::string() : "unknown convention \"" + name + "\"; expected one of " + conventionNames();
        });
}

void addFrameOptions(CLI::App& command, FrameSettings& settings)
{
    // Every setting with a plain option comes from its table row (frameSettingsFields());
    // the ones below take forms of their own.
    addFieldOptions(command, frameSettingsFields(), settings);
    std::string builtins;
    for (const std::string& name : builtinEnvironmentNames()) builtins += (builtins.empty() ? "" : ", ") + name;
    command.add_option("--env", settings.environment.source, std::string(frameField("environment.source").help) + " (" + builtins + ")")
        ->type_name("FILE|builtin:NAME")
        ->default_str("courtyard.exr");
    command
        .add_option_function<std::string>(
            "--scene",
            [&settings](const std::string& value) {
                const std::optional<SceneKind> kind = parseEnum<SceneKind>(value);
                if (kind && *kind != SceneKind::Model) {
                    settings.scene.kind = *kind;
                    return;
                }
                const std::string ext = std::filesystem::path(value).extension().string();
                if (ext != ".gltf" && ext != ".glb") throw CLI::ValidationError("--scene", "expected sphere, grid, counting, sweep, none or a .gltf/.glb file, got \"" + value + "\"");
                settings.scene.kind = SceneKind::Model;
                settings.scene.modelPath = value;
            },
            std::string(frameField("scene.kind").help))
        ->type_name("NAME|FILE")
        ->default_str("sphere");
    addMipOption(command, "--mip", "sampling.forced_mip", settings);
    addMipOption(command, "--b-mip", "view.compare.forced_mip", settings);
    command
        .add_option_function<std::string>(
            "--base-color",
            [&settings](const std::string& value) {
                const auto colour = parseColour(value);
                if (!colour) throw CLI::ValidationError("--base-color", "expected r,g,b in 0..1 (linear) or #rrggbb (sRGB), got \"" + value + "\"");
                settings.material.baseColor = *colour;
            },
            std::string(frameField("material.base_color").help))
        ->type_name("R,G,B|#RRGGBB")
        ->default_str(fieldDefaultText(frameField("material.base_color"), settings));
    command.add_option("--distance", settings.camera.distance, fieldHelp(frameField("camera.distance")))->default_str("0");
    command
        .add_option_function<std::string>(
            "--split",
            [&settings](const std::string& position) {
                applyFieldText(frameField("view.split_position"), settings, position);
                settings.view.split = true;
            },
            fieldHelp(frameField("view.split_position")))
        ->type_name("FLOAT");
}

int runCommandLine(int argc, char** argv)
{
    const auto processStart = std::chrono::steady_clock::now();
    CLI::App app{"iblab: a lab for image-based lighting. With no sub-command it opens the GUI, or renders the default view "
                 "to a PNG when there is no display."};
    app.set_version_flag("--version", "iblab " IBLAB_VERSION);
    app.formatter(std::make_shared<HelpFormatter>()); // the sub-commands added below inherit it

    GuiOptions gui;
    gui.settings.camera.distance = 0.0f; // frame whatever scene is shown, unless --distance says otherwise
    addFrameOptions(app, gui.settings);
    addConventionOption(app, gui.convention);
    bool forceHeadless = false;
    app.add_flag("--headless", forceHeadless, "Render the default view to a PNG even when a display exists");
    app.add_option("--quit-after-frames", gui.quitAfterFrames, "Close the window after N frames, for start-up timing (0 keeps it open)")->capture_default_str();
    app.add_option_function<std::string>(
           "--window-size",
           [&gui](const std::string& value) {
               int width = 0, height = 0;
               char x = 0, extra = 0;
               if (std::sscanf(value.c_str(), "%d%c%d%c", &width, &x, &height, &extra) != 3 || (x != 'x' && x != 'X') || width < 320 ||
                   height < 240 || width > 16384 || height > 16384)
                   throw CLI::ValidationError("--window-size", "expected WIDTHxHEIGHT between 320x240 and 16384x16384, got \"" + value + "\"");
               gui.width = width;
               gui.height = height;
               gui.windowSizeGiven = true;
           },
           "GUI window size, from 320x240 to 16384x16384")
        ->type_name("WxH")
        ->default_str("1280x720");
    app.add_option("--script", gui.script,
                   "Run the GUI under a script of input events and checks (docs/gui-scripts.md); exits 0 when every check passed. "
                   "Offscreen when there is no display")
        ->check(CLI::Validator(CLI::ExistingFile).description(""))
        ->type_name("FILE");
    app.add_flag("--offscreen", gui.offscreen, "With --script: run the GUI frame in a headless EGL context even when a display exists");
    app.add_option("--coverage-out", gui.coverageOut, "With --script: write the controls the script showed and used (JSON)")->type_name("FILE");

    std::vector<Command> commands;
    commands.push_back(addRenderCommand(app, processStart));
    commands.push_back(addBakeCommand(app, processStart));
    commands.push_back(addShCommand(app, processStart));
    commands.push_back(addLutCommand(app, processStart));
    commands.push_back(addStressCommand(app, processStart));
    commands.push_back(addConventionsCommand(app, processStart));
    commands.push_back(addBenchCommand(app, processStart));
    commands.push_back(addCompareCommand(app, processStart));
    commands.push_back(addMeasureCommand(app, processStart));

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        // One line: "iblab: --tonemap: unknown operator "x"" and a pointer to --help.
        std::fprintf(stderr, "iblab: %s (see --help)\n", e.what());
        return 2;
    }

    for (const Command& command : commands)
        if (*command.subcommand) return command.run();

    if (gui.settings.environment.source.empty()) gui.settings.environment.source = defaultEnvironmentSpec();
    // The GUI and the headless fallback read an environment file first thing: load the image
    // libraries (about 0.3 s) while the window and context are made.
    preloadImageCodec();
    if (!gui.script.empty()) {
        try {
            return runGui(gui);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "iblab: %s\n", e.what());
            return 1;
        }
    }
    if (!forceHeadless && displayAvailable()) {
        try {
            return runGui(gui);
        } catch (const WindowUnavailable& e) {
            std::fprintf(stderr, "iblab: %s; rendering the default view headless\n", e.what());
            forceHeadless = true; // the message above already says why
        } catch (const std::exception& e) {
            std::fprintf(stderr, "iblab: %s\n", e.what());
            return 1;
        }
    } else if (!forceHeadless) {
        std::fprintf(stderr, "iblab: no display (DISPLAY and WAYLAND_DISPLAY are unset or unusable); rendering the default view headless\n");
    }
    RenderJob fallback;
    fallback.settings = gui.settings;
    fallback.convention = gui.convention;
    fallback.output = std::filesystem::absolute("iblab-default.png").string();
    return runHeadlessRender(fallback, processStart);
}

} // namespace iblab::app
