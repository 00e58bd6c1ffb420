// `iblab sh` and `iblab lut`: SH9 projection and the BRDF LUT from the command line,
// headless. Each prints its result on stdout (or JSON with --json) and, on failure, exits
// non-zero with one line on stderr naming the file or the problem.
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <epoxy/gl.h>
#include <malloc.h>
#include <nlohmann/json.hpp>

#include "asset_paths.hpp"
#include "bake_export.hpp"
#include "bake/bake_accuracy.hpp"
#include "bake/bake_cache.hpp"
#include "bake/bake_files.hpp"
#include "bake/bake_job.hpp"
#include "bake/standalone_passes.hpp"
#include "command_support.hpp"
#include "field_options.hpp"
#include "commands.hpp"
#include "io/environment.hpp"
#include "io/builtin_environments.hpp"
#include "io/error.hpp"
#include "gl/context_error.hpp"
#include "gl/context_info.hpp"
#include "gl/shader_library.hpp"


namespace iblab::app {
namespace {

using Clock = std::chrono::steady_clock;
using nlohmann::ordered_json;

ordered_json shArray(const SH9Color& sh)
{
    ordered_json a = ordered_json::array();
    for (const glm::dvec3& c : sh.c)
        a.push_back({c.x, c.y, c.z});
    return a;
}


struct ShCommandOptions {
    std::string environment;
    std::string device = "cpu";
    std::string window = "hanning";
    double windowWidth = 0.0;
    bool json = false;
};

int runSh(const ShCommandOptions& o)
{
    try {
        const auto device = parseEnum<bake::ShDevice>(o.device);
        if (!device) throw Error("--device", "expected cpu or gpu, got \"" + o.device + "\"");
        const auto window = parseEnum<ShWindow>(o.window);
        if (!window) throw Error("--window", "expected none, hanning or lanczos, got \"" + o.window + "\"");
        const Environment environment = loadEnvironment(o.environment);
        SH9Color radiance;
        double ms = 0.0; // the projection only: upload and read-back included, context creation not
        if (*device == bake::ShDevice::Cpu) {
            const auto start = Clock::now();
            radiance = projectEquirect(environment.image);
            ms = millisecondsSince(start);
        } else {
            HeadlessGl gl(/*debugContext=*/true);
            gl::ShaderLibrary shaders(shaderDirectory());
            const bake::TimedSh9 projected = bake::projectSh9OnGpu(shaders, environment.image);
            radiance = projected.radiance;
            ms = projected.ms;
            if (gl.debug.errorCount() > 0) return failCommand("sh", "GL error: " + gl.debug.firstError());
        }
        const SH9Color irradiance = convolveWithCosineLobe(radiance);
        const double width = *window == ShWindow::None ? 0.0
                             : o.windowWidth > 0.0     ? o.windowWidth
                                                       : findNonNegativeWindowWidth(irradiance, *window);
        const SH9Color windowed = applyWindow(irradiance, *window, width);
        if (o.json) {
            ordered_json j;
            j["basis"] = kSh9Convention;
            j["radiance"] = shArray(radiance);
            j["irradiance"] = shArray(irradiance);
            j["irradiance_windowed"] = shArray(windowed);
            j["window"] = enumName(*window);
            j["window_width"] = width;
            j["source"] = environment.source;
            j["device"] = o.device;
            j["projection_ms"] = ms;
            std::printf("%s\n", j.dump(2).c_str());
        } else {
            static const char* names[] = {"(0,0)", "(1,-1)", "(1,0)", "(1,1)", "(2,-2)", "(2,-1)", "(2,0)", "(2,1)", "(2,2)"};
            std::printf("%s (%s, %.1f ms); %s\n", environment.source.c_str(), o.device.c_str(), ms, kSh9Convention);
            std::printf("%-7s %38s %38s\n", "l,m", "radiance L_lm", "irradiance E_lm");
            for (int i = 0; i < kSh9Count; ++i) {
                const glm::dvec3 L = radiance.c[std::size_t(i)];
                const glm::dvec3 E = irradiance.c[std::size_t(i)];
                std::printf("%-7s %12.6g %12.6g %12.6g %12.6g %12.6g %12.6g\n", names[i], L.x, L.y, L.z, E.x, E.y, E.z);
            }
        }
        return 0;
    } catch (const std::exception& e) {
        return failCommand("sh", e.what());
    }
}

struct LutCommandOptions {
    int size = 128;
    int samples = 1024;
    std::string geometry = "correlated";
    bool multiscatter = false;
    std::string output;
    bool json = false;
};

int runLut(const LutCommandOptions& o)
{
    try {
        const auto term = parseEnum<GeometryTerm>(o.geometry);
        if (!term) throw Error("--geometry", "expected schlick or correlated, got \"" + o.geometry + "\"");
        HeadlessGl gl(/*debugContext=*/true);
        gl::ShaderLibrary shaders(shaderDirectory());
        const bake::TimedLut baked = bake::bakeBrdfLut(shaders, o.size, o.samples, *term);
        const double ms = baked.ms;
        bake::writeLutExr(o.output, bake::read2D(baked.lut), o.samples, *term, o.multiscatter, false);
        if (gl.debug.errorCount() > 0) return failCommand("lut", "GL error: " + gl.debug.firstError());
        if (o.json) {
            ordered_json j;
            j["output"] = o.output;
            j["size"] = o.size;
            j["samples"] = o.samples;
            j["geometry"] = enumName(*term);
            j["multiscatter"] = o.multiscatter;
            j["bake_ms"] = ms;
            j["timing_method"] = "steady clock around the dispatch and glFinish";
            std::printf("%s\n", j.dump(2).c_str());
        } else {
            std::printf("%s\n", o.output.c_str());
        }
        return 0;
    } catch (const std::exception& e) {
        return failCommand("lut", e.what());
    }
}

std::string exrOnly(const std::string& path)
{
    return std::filesystem::path(path).extension() == ".exr" ? std::string() : "the output must end in .exr, got \"" + path + "\"";
}

} // namespace

Command addShCommand(CLI::App& app, ProcessClock::time_point)
{
    auto o = std::make_shared<ShCommandOptions>();
    CLI::App* c = app.add_subcommand("sh", "Project an environment onto SH9: radiance and irradiance coefficients");
    c->add_option("--env", o->environment, "Environment: an .exr/.hdr file or builtin:NAME")->required();
    c->add_option("--device", o->device, "Where to project: cpu (no GL needed) or gpu")->capture_default_str()->check(CLI::IsMember({"cpu", "gpu"}));
    c->add_option("--window", o->window, "Window for irradiance_windowed: none, hanning or lanczos")
        ->capture_default_str()
        ->check(CLI::IsMember({"none", "hanning", "lanczos"}));
    c->add_option("--window-width", o->windowWidth, "Window width in bands; 0 = the gentlest non-negative one")->capture_default_str();
    c->add_flag("--json", o->json, "Print {\"basis\", \"radiance\", \"irradiance\", ...} as JSON");
    return {c, [o] { return runSh(*o); }};
}

Command addLutCommand(CLI::App& app, ProcessClock::time_point)
{
    auto o = std::make_shared<LutCommandOptions>();
    CLI::App* c = app.add_subcommand("lut", "Bake the split-sum BRDF LUT on the GPU to an EXR: R = A, G = B, x = NdotV, y = "
                                            "roughness, first scanline = roughness near 0");
    c->add_option("--size", o->size, "Width and height")->capture_default_str()->check(CLI::Range(1, 4096));
    c->add_option("--samples", o->samples, "GGX samples per texel")->capture_default_str()->check(CLI::Range(1, 1 << 20));
    c->add_option("--geometry", o->geometry, "schlick (Schlick-GGX, k = alpha/2) or correlated (height-correlated Smith)")
        ->capture_default_str()
        ->check(CLI::IsMember({"schlick", "correlated", "schlick-ggx", "height-correlated-smith"}));
    c->add_flag("--multiscatter", o->multiscatter, "Store A + B in the B channel (energy compensation); otherwise B = 0");
    c->add_option("-o,--output", o->output, "Output FILE.exr")->required()->check(exrOnly);
    c->add_flag("--json", o->json, "Print a JSON report");
    return {c, [o] { return runLut(*o); }};
}

} // namespace iblab::app
