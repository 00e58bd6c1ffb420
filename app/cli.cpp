#include "cli.hpp"

#include "commands.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>

#include <CLI/CLI.hpp>

#include "gui_app.hpp"
#include "headless_render.hpp"
#include "ibl/tonemap.hpp"
#include "lab_session.hpp"

namespace iblab::app {

void addFrameOptions(CLI::App& command, FrameSettings& settings)
{
    command.add_option("--env", settings.environment.source, "Environment: an .exr/.hdr file or builtin:NAME (white, sky, sun, lights, studio, black)")
        ->default_str("the bundled courtyard.exr");
    command.add_option("--env-yaw", settings.environment.yawDegrees, "Environment rotation about +Y, degrees (+90 brings +X to the front)")
        ->capture_default_str();
    command.add_option("--env-intensity", settings.environment.intensityEv, "Environment intensity, EV stops")->capture_default_str();
    command.add_option("--exposure", settings.toneMap.exposureEv, "Exposure before tone mapping, EV stops")->capture_default_str();
    std::string operators;
    for (ToneMapOperator op : allToneMapOperators()) operators += (operators.empty() ? "" : "|") + std::string(toneMapOperatorName(op));
    command
        .add_option_function<std::string>(
            "--tonemap",
            [&settings](const std::string& name) {
                const auto op = parseToneMapOperator(name);
                if (!op) throw CLI::ValidationError("--tonemap", "unknown operator \"" + name + "\"");
                settings.toneMap.op = *op;
            },
            "Tone map operator: " + operators)
        ->default_str(std::string(toneMapOperatorName(settings.toneMap.op)));
    command.add_option("--yaw", settings.camera.yawDegrees, "Camera yaw, degrees (0 looks down -Z, +90 down +X)")->capture_default_str();
    command.add_option("--pitch", settings.camera.pitchDegrees, "Camera pitch, degrees")->capture_default_str()->check(CLI::Range(-89.0f, 89.0f));
    command.add_option("--fov", settings.camera.fovDegrees, "Vertical field of view, degrees")->capture_default_str()->check(CLI::Range(1.0f, 170.0f));
}

int runCommandLine(int argc, char** argv)
{
    const auto processStart = std::chrono::steady_clock::now();
    CLI::App app{"iblab: a lab for image-based lighting. With no sub-command it opens the GUI, or renders the default view "
                 "to a PNG when there is no display."};
    app.set_version_flag("--version", "iblab 0.1.0");

    GuiOptions gui;
    addFrameOptions(app, gui.settings);
    bool forceHeadless = false;
    app.add_flag("--headless", forceHeadless, "Render the default view to a PNG even when a display exists");
    app.add_option("--quit-after-frames", gui.quitAfterFrames, "Close the window after N frames (scripted start-up timing)");

    std::vector<Command> commands;
    commands.push_back(addRenderCommand(app, processStart));

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
    if (!forceHeadless && displayAvailable()) {
        try {
            return runGui(gui);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "iblab: %s\n", e.what());
            return 1;
        }
    }
    if (!forceHeadless) std::fprintf(stderr, "iblab: no display (DISPLAY and WAYLAND_DISPLAY are unset or unusable); rendering the default view headless\n");
    RenderJob fallback;
    fallback.settings = gui.settings;
    fallback.output = std::filesystem::absolute("iblab-default.png").string();
    return runHeadlessRender(fallback, processStart);
}

} // namespace iblab::app
