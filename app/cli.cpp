#include "cli.hpp"

#include "commands.hpp"

#include <chrono>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>

#include <CLI/CLI.hpp>
#include <glm/glm.hpp>

#include "frame/conventions.hpp"
#include "io/builtin_environments.hpp"
#include "gui_app.hpp"
#include "headless_render.hpp"
#include "ibl/tonemap.hpp"
#include "lab_session.hpp"

namespace iblab::app {
namespace {

// An option whose value is one of an enum's names (settings.hpp spells them once).
template <typename Enum>
void addNamedOption(CLI::App& command, const std::string& name, const std::string& help, Enum& target, bool (*parse)(std::string_view, Enum&),
                    std::string_view (*nameOf)(Enum))
{
    command
        .add_option_function<std::string>(
            name,
            [&target, parse, name](const std::string& value) {
                if (!parse(value, target)) throw CLI::ValidationError(name, "unknown value \"" + value + "\"");
            },
            help)
        ->default_str(std::string(nameOf(target)));
}

// "0.9,0.6,0.5" (linear) or "#e6a08c" (sRGB-encoded, as colour pickers give it).
std::optional<glm::vec3> parseColour(const std::string& text)
{
    if (text.size() == 7 && text[0] == '#') {
        glm::vec3 colour;
        for (int c = 0; c < 3; ++c) {
            const std::string hex = text.substr(1 + std::size_t(c) * 2, 2);
            if (hex.find_first_not_of("0123456789abcdefABCDEF") != std::string::npos) return std::nullopt;
            const float encoded = float(std::stoi(hex, nullptr, 16)) / 255.0f;
            colour[c] = encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
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

// The estimator's options. The split view's B side has the same set, prefixed --b-.
void addSamplingOptions(CLI::App& command, SamplingSettings& sampling, const std::string& prefix, const std::string& helpPrefix)
{
    addNamedOption(command, prefix + "method", helpPrefix + "Shading: splitsum|sampled", sampling.method, parseShadingMethod, shadingMethodName);
    command.add_option(prefix + "samples", sampling.samples, helpPrefix + "N, samples per pixel for the sampled method")->capture_default_str()->check(CLI::Range(1, kMaxSampleCount));
    const std::string mipOption = prefix + "mip";
    command
        .add_option_function<std::string>(
            mipOption,
            [&sampling, mipOption](const std::string& value) {
                if (value == "auto") {
                    sampling.forcedMip = -1;
                    return;
                }
                try {
                    sampling.forcedMip = std::stoi(value);
                } catch (const std::exception&) {
                    throw CLI::ValidationError(mipOption, "expected a mip level or auto, got \"" + value + "\"");
                }
                if (sampling.forcedMip < 0) throw CLI::ValidationError(mipOption, "a mip level is >= 0");
            },
            helpPrefix + "Mip level to read (prefiltered mip for split-sum, source mip for sampled), or auto")
        ->default_str("auto");
    command.add_flag("!" + prefix + "no-pdf-filtering", sampling.pdfMipFiltering, helpPrefix + "Sampled method: read every sample from mip 0 instead of the PDF-chosen mip");
    command.add_option(prefix + "mip-bias", sampling.mipBias, helpPrefix + "Bias added to the PDF-chosen mip (0 LearnOpenGL, 1 Filament)")->capture_default_str();
    addNamedOption(command, prefix + "geometry", helpPrefix + "Geometry term: schlick|correlated", sampling.geometry, parseGeometryTerm, geometryTermShortName);
    addNamedOption(command, prefix + "diffuse", helpPrefix + "Diffuse source: sh9|irradiance-cube", sampling.diffuse, parseDiffuseSource, diffuseSourceName);
    command.add_flag(prefix + "cosine-diffuse", sampling.cosineSampledDiffuse, helpPrefix + "Sampled method: diffuse from N cosine samples instead of SH9");
    command.add_flag(prefix + "multiscatter", sampling.multiscatter, helpPrefix + "Multiple-scattering energy compensation from the LUT");
    command.add_flag(prefix + "rough-fresnel-lut", sampling.roughFresnelOnLut,
                     helpPrefix + "Split sum as LearnOpenGL: F_roughness(n.v) * A + B instead of F0 * A + B");
    command.add_flag(prefix + "normalize-accepted", sampling.normalizeByAccepted,
                     helpPrefix + "Sampled method: divide by the samples above the horizon (LearnOpenGL) instead of by N");
    command.add_flag(prefix + "freeze-samples", sampling.freezeSampleSet,
                     helpPrefix + "Sampled method: keep exactly N samples per pixel (no rotated sample sets added over frames)");
}

} // namespace

void addConventionOption(CLI::App& command, std::string& convention)
{
    command.add_option("--convention", convention, "Bake and shade as " + conventionNames() + " do (split sum)")
        ->check([](const std::string& name) {
            return findConvention(name) ? std::string() : "unknown convention \"" + name + "\"; expected one of " + conventionNames();
        });
}

void addFrameOptions(CLI::App& command, FrameSettings& settings)
{
    std::string builtins;
    for (const std::string& name : builtinEnvironmentNames()) builtins += (builtins.empty() ? "" : ", ") + name;
    command.add_option("--env", settings.environment.source, "Environment: an .exr/.hdr file or builtin:NAME (" + builtins + ")")
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
    // Scene, material and method: every view of the UI can be rendered headless.
    command
        .add_option_function<std::string>(
            "--scene",
            [&settings](const std::string& value) {
                if (parseSceneKind(value, settings.scene.kind) && settings.scene.kind != SceneKind::Model) return;
                const std::string ext = std::filesystem::path(value).extension().string();
                if (ext != ".gltf" && ext != ".glb") throw CLI::ValidationError("--scene", "expected sphere, grid, counting, sweep, none or a .gltf/.glb file, got \"" + value + "\"");
                settings.scene.kind = SceneKind::Model;
                settings.scene.modelPath = value;
            },
            "Scene: sphere|grid|counting|sweep|none|FILE.gltf|FILE.glb")
        ->default_str("sphere");
    command.add_option("--counting-spheres", settings.scene.countingSpheres, "Spheres in the N = 1..k counting strip")
        ->capture_default_str()
        ->check(CLI::Range(1, 64));
    addSamplingOptions(command, settings.sampling, "--", "");
    command.add_option("--metallic", settings.material.metallic, "Metallic, 0..1")->capture_default_str()->check(CLI::Range(0.0f, 1.0f));
    command.add_option("--roughness", settings.material.roughness, "Perceptual roughness, 0..1")->capture_default_str()->check(CLI::Range(0.0f, 1.0f));
    command.add_option("--ao", settings.material.ambientOcclusion, "Ambient occlusion, 0..1")->capture_default_str()->check(CLI::Range(0.0f, 1.0f));
    command.add_option("--specular", settings.material.specular, "Dielectric reflectance (F0 = 0.16 specular^2)")->capture_default_str()->check(CLI::Range(0.0f, 1.0f));
    command
        .add_option_function<std::string>(
            "--base-color",
            [&settings](const std::string& value) {
                const auto colour = parseColour(value);
                if (!colour) throw CLI::ValidationError("--base-color", "expected r,g,b in 0..1 (linear) or #rrggbb (sRGB), got \"" + value + "\"");
                settings.material.baseColor = *colour;
            },
            "Base colour: r,g,b (linear, 0..1) or #rrggbb (sRGB)");
    command.add_flag("!--model-material", settings.material.overrideModel, "Keep a glTF model's own material factors instead of the sliders'");
    addNamedOption(command, "--view", "View: final|prefilter-mips|lut|furnace|irradiance|error", settings.view.mode, parseViewMode, viewModeName);
    addNamedOption(command, "--background", "Background: environment|irradiance|prefilter-mip|solid", settings.view.background, parseBackgroundMode,
                   backgroundModeName);
    command.add_option("--background-mip", settings.view.backgroundMip, "Prefiltered mip shown by --background prefilter-mip")->capture_default_str();
    command.add_option("--msaa", settings.view.msaaSamples, "Multisample anti-aliasing of the lit frame: samples per pixel, 1 (off), 2, 4 or 8")
        ->capture_default_str()
        ->check(CLI::IsMember({1, 2, 4, 8}));
    command.add_option("--distance", settings.camera.distance, "Camera distance from its target")->default_str("0: frame the scene");
    // Speed against accuracy: the error view against the reference, and the A/B split.
    addNamedOption(command, "--error-space", "--view error compares: linear (HDR, before tone mapping)|display (after)", settings.view.errorSpace,
                   parseErrorSpace, errorSpaceName);
    command.add_option("--error-scale", settings.view.errorScale, "--view error: the relative error at the top of the colour bar")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
    command.add_option("--reference-width", settings.view.referenceWidth,
                       "Width of the environment the reference sums over (halved from the loaded map until it fits; height = width / 2)")
        ->capture_default_str()
        ->check(CLI::Range(2, 4096));
    command
        .add_option_function<float>(
            "--split",
            [&settings](float position) {
                settings.view.split = true;
                settings.view.splitPosition = position;
            },
            "A/B split view: the divider's position, 0..1 from the left; A (the options above) left, B (--b-*) right")
        ->check(CLI::Range(0.0f, 1.0f));
    addSamplingOptions(command, settings.view.compare, "--b-", "Split view, right side: ");
}

int runCommandLine(int argc, char** argv)
{
    const auto processStart = std::chrono::steady_clock::now();
    CLI::App app{"iblab: a lab for image-based lighting. With no sub-command it opens the GUI, or renders the default view "
                 "to a PNG when there is no display."};
    app.set_version_flag("--version", "iblab 0.1.0");

    GuiOptions gui;
    gui.settings.camera.distance = 0.0f; // frame whatever scene is shown, unless --distance says otherwise
    addFrameOptions(app, gui.settings);
    addConventionOption(app, gui.convention);
    bool forceHeadless = false;
    app.add_flag("--headless", forceHeadless, "Render the default view to a PNG even when a display exists");
    app.add_option("--quit-after-frames", gui.quitAfterFrames, "Close the window after N frames (scripted start-up timing)");
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
           },
           "GUI window size, WIDTHxHEIGHT")
        ->default_str("1280x720");
    app.add_option("--script", gui.script,
                   "Run the GUI under a script of input events and checks (docs/gui-scripts.md); exits 0 when every check passed. "
                   "Offscreen when there is no display")
        ->check(CLI::ExistingFile);
    app.add_flag("--offscreen", gui.offscreen, "With --script: run the GUI frame in a headless EGL context even when a display exists");
    app.add_option("--coverage-out", gui.coverageOut, "With --script: write the controls the script showed and used (JSON)");

    std::vector<Command> commands;
    commands.push_back(addRenderCommand(app, processStart));
    commands.push_back(addBakeCommand(app, processStart));
    commands.push_back(addShCommand(app, processStart));
    commands.push_back(addLutCommand(app, processStart));
    commands.push_back(addStressCommand(app, processStart));
    commands.push_back(addConventionsCommand(app, processStart));
    commands.push_back(addBenchCommand(app, processStart));

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
