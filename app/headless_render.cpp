#include "headless_render.hpp"

#include <algorithm>
#include <filesystem>
#include <optional>
#include <cstdio>
#include <vector>

#include <epoxy/gl.h>
#include <nlohmann/json.hpp>

#include "asset_paths.hpp"
#include "frame/camera.hpp"
#include "commands.hpp"
#include "frame/conventions.hpp"
#include "frame/split_view.hpp"
#include "command_support.hpp"
#include "gl/shader_library.hpp"
#include "frame_capture.hpp"
#include "lab_session.hpp"
#include "loaded_model.hpp"
#include "view_overlays.hpp"

namespace iblab::app {
namespace {

using Clock = std::chrono::steady_clock;

int fail(const std::string& reason) { return failCommand("render", reason); }

struct RenderTimings {
    double contextMs = 0.0;
    double loadMs = 0.0;
    double referenceMs = 0.0; // 0 when the frame shows no reference
    double firstFrameMs = 0.0;
    std::vector<double> frameMs; // sorted
    std::vector<double> frameGpuMs; // sorted; empty where timer queries are not trusted
};

void timeWarmFrames(Renderer& renderer, const FrameSettings& settings, const RenderJob& job, RenderTimings& t)
{
    // Warm frames: the same passes again, timed one by one with glFinish, because
    // llvmpipe's timer queries are wrong at this size; a hardware renderer's frames are
    // also timed by GL_TIME_ELAPSED, the GPU's own time without the driver's latency.
    for (int i = 0; i < job.timingRepeats; ++i) {
        GpuTimeQuery gpuTime;
        const auto start = Clock::now();
        renderer.renderFrame(settings, job.width, job.height);
        const std::optional<double> gpuMs = gpuTime.finish();
        glFinish();
        t.frameMs.push_back(millisecondsSince(start));
        if (gpuMs) t.frameGpuMs.push_back(*gpuMs);
    }
    std::sort(t.frameMs.begin(), t.frameMs.end());
    std::sort(t.frameGpuMs.begin(), t.frameGpuMs.end());
}

nlohmann::ordered_json renderReport(const RenderJob& job, const std::string& rendererName, const std::string& environment,
                                    const std::string& scene, const FrameSettings& settings, Renderer& renderer,
                                    const ReferenceStatus& reference, const RenderTimings& t)
{
    nlohmann::ordered_json report;
    report["output"] = job.output;
    report["width"] = job.width;
    report["height"] = job.height;
    report["renderer"] = rendererName;
    report["environment"] = environment;
    if (!scene.empty()) report["scene"] = scene;
    if (settings.view.mode == ViewMode::Furnace)
        for (const SphereReading& r : renderer.measureSpheres(settings))
            report["furnace"].push_back({{"metallic", r.metallic},
                                         {"roughness", r.roughness},
                                         {"reflected", {r.radiance.r, r.radiance.g, r.radiance.b}}});
    if (reference.complete) report["timings_ms"]["reference"] = t.referenceMs;
    if (reference.complete && settings.view.mode == ViewMode::Error) {
        const ErrorReport error = renderer.measureError(settings);
        auto& out = report["error"];
        out["space"] = enumName(settings.view.errorSpace);
        out["reference_environment"] = {{"width", reference.environmentWidth},
                                        {"height", reference.environmentHeight},
                                        {"texel_degrees", reference.texelDegrees},
                                        {"min_resolved_roughness", reference.minResolvedRoughness}};
        out[settings.view.split ? "a" : "frame"] = errorMetricsJson(error.left);
        if (error.right) out["b"] = errorMetricsJson(*error.right);
    }
    const Renderer::ShadingLightsInfo lights = renderer.shadingLights();
    report["shading_lights"] = lights.count;
    if (lights.count > 0) report["timings_ms"]["shading_lights"] = lights.milliseconds;
    report["timings_ms"]["start_to_context"] = t.contextMs;
    report["timings_ms"]["environment_load"] = t.loadMs;
    report["timings_ms"]["start_to_first_frame"] = t.firstFrameMs;
    if (!t.frameMs.empty()) {
        report["timings_ms"]["frame_median"] = t.frameMs[t.frameMs.size() / 2];
        report["timings_ms"]["frame_min"] = t.frameMs.front();
        report["timings_ms"]["frame_repeats"] = t.frameMs.size();
        report["timing_method"] = "steady_clock around glFinish";
    }
    if (!t.frameGpuMs.empty()) {
        report["timings_ms"]["frame_gpu_median"] = t.frameGpuMs[t.frameGpuMs.size() / 2];
        report["timings_ms"]["frame_gpu_min"] = t.frameGpuMs.front();
        report["gpu_timing_method"] = "GL_TIME_ELAPSED query per frame";
    }
    return report;
}

} // namespace

int runHeadlessRender(const RenderJob& job, Clock::time_point processStart)
{
#ifdef NDEBUG
    const bool debugContext = job.glDebug;
#else
    const bool debugContext = true;
#endif
    try {
        HeadlessGl gl(debugContext, /*echoMessages=*/true);
        RenderTimings timings;
        timings.contextMs = millisecondsSince(processStart);

        Renderer renderer(shaderDirectory());
        FrameSettings settings = job.settings;
        bake::BakeSettings bakeSettings = bake::defaultPreset();
        if (const ConventionPreset* convention = findConvention(job.convention)) {
            bakeSettings = conventionBakeSettings(*convention);
            applyConvention(*convention, settings.sampling);
        }
        LabSession session(renderer, bakeSettings);
        const auto loadStart = Clock::now();
        const StatusReport loaded = session.loadEnvironment(settings.environment.source);
        if (loaded.isError) return fail(loaded.text);
        timings.loadMs = millisecondsSince(loadStart);
        std::string sceneStatus;
        if (settings.scene.kind == SceneKind::Model) {
            LoadedModel loadedModel(renderer);
            const StatusReport model = loadedModel.load(settings.scene.modelPath, /*modelShown=*/false);
            if (model.isError) return fail(model.text);
            sceneStatus = model.text;
            // A missing texture renders untextured: say so where a script sees it, since
            // stdout holds only the output's path (or the JSON, which has the line too).
            for (const std::string& warning : loadedModel.warnings())
                std::fprintf(stderr, "iblab render: warning: %s: %s\n", displayName(settings.scene.modelPath).c_str(), warning.c_str());
        }
        if (settings.view.mode == ViewMode::Furnace) session.ensureFurnaceBake();
        if (settings.camera.distance <= 0.0f) frameAtStart(renderer, settings, float(job.width) / float(job.height));

        // The error view and the reference method need the reference of this very frame: run
        // it to completion first.
        ReferenceStatus reference;
        if (showsReference(settings)) {
            const auto referenceStart = Clock::now();
            reference = renderer.advanceReference(settings, job.width, job.height, std::chrono::hours(24));
            if (!reference.complete) return fail("the reference did not complete (no bake?)");
            timings.referenceMs = millisecondsSince(referenceStart);
        }

        renderer.renderFrame(settings, job.width, job.height);
        glFinish();
        timings.firstFrameMs = millisecondsSince(processStart);

        timeWarmFrames(renderer, settings, job, timings);

        // Labels (grid axes, mip roughness, furnace energy) belong in the tone-mapped PNG;
        // the EXR stays the pure linear frame.
        if (std::filesystem::path(job.output).extension() == ".png") {
            OffscreenOverlay overlay;
            overlay.drawOver(renderer, settings, job.width, job.height);
        }
        const StatusReport written = writeCapture(renderer, job.output, settings, session.bakeSettings());
        if (written.isError) return fail(written.text);
        if (gl.debug.errorCount() > 0) return fail(std::to_string(gl.debug.errorCount()) + " GL error(s) while rendering; see above");

        if (job.json) {
            const nlohmann::ordered_json report =
                renderReport(job, gl.context.description(), loaded.joined(), sceneStatus, settings, renderer, reference, timings);
            std::printf("%s\n", report.dump(2).c_str());
        } else {
            std::printf("%s\n", job.output.c_str());
        }
        return 0;
    } catch (const std::exception& e) {
        // No context, a shader that does not compile, a bake that cannot start: one line.
        return fail(e.what());
    }
}

Command addRenderCommand(CLI::App& app, ProcessClock::time_point processStart)
{
    auto job = std::make_shared<RenderJob>();
    job->settings.camera.distance = 0.0f; // frame the scene unless --distance says otherwise
    CLI::App* command = app.add_subcommand("render", "Render one frame headless (EGL, no display) to a PNG or EXR");
    addFrameOptions(*command, job->settings);
    addConventionOption(*command, job->convention);
    command->add_option("--width", job->width, "Image width")->capture_default_str()->check(CLI::Range(1, 16384));
    command->add_option("--height", job->height, "Image height")->capture_default_str()->check(CLI::Range(1, 16384));
    command->add_option("-o,--output", job->output, "Output: FILE.png (tone-mapped 8-bit sRGB) or FILE.exr (linear HDR)")
        ->required()
        ->check([](const std::string& path) {
            const std::string ext = std::filesystem::path(path).extension().string();
            return ext == ".png" || ext == ".exr" ? std::string() : "the output must end in .png or .exr, got \"" + path + "\"";
        });
    command->add_option("--time", job->timingRepeats, "Re-render N times and report the median frame time (with --json)");
    command->add_flag("--json", job->json, "Print a JSON report (output, timings) instead of the output path");
    command->add_flag("--gl-debug", job->glDebug, "Use a KHR_debug context; any GL error fails the render");
    return {command, [job, processStart] {
                if (job->settings.environment.source.empty()) job->settings.environment.source = defaultEnvironmentSpec();
                return runHeadlessRender(*job, processStart);
            }};
}

} // namespace iblab::app
