#include "lab/bench_sweep.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <sstream>

#include <epoxy/gl.h>
#include <nlohmann/json.hpp>

#include "bake/bake_job.hpp"
#include "lab/auto_quality.hpp"
#include "frame/camera.hpp"
#include "io/error.hpp"
#include "gl/context_info.hpp"
#include "ibl/reference.hpp"
#include "ibl/tonemap.hpp"
#include "scene/gltf_model.hpp"
#include "lab/stress_suite.hpp"

namespace iblab::bench {
namespace {

using Clock = std::chrono::steady_clock;

// The error of a measurement over no pixel: NaN, which never reads as 0 (exact), and which
// compares false both ways, so that such a point neither dominates nor is dominated.
constexpr double kNoError = std::numeric_limits<double>::quiet_NaN();

double millisecondsSince(Clock::time_point start) { return std::chrono::duration<double, std::milli>(Clock::now() - start).count(); }

std::string formatNumber(double v, const char* format = "%g")
{
    char text[48];
    std::snprintf(text, sizeof text, format, v);
    return text;
}

std::string onOff(bool on, const char* what) { return std::string(on ? "" : "no ") + what; }

bool surfacePixel(const FrameReadback& normalLayer, std::size_t i) { return normalLayer.rgba[i * 4 + 3] != 0.0f; }
double roughnessAt(const FrameReadback& viewLayer, std::size_t i) { return double(viewLayer.rgba[i * 4 + 3]); }

// Surface pixels (coverage in the normal layer's alpha) the reference resolves (roughness
// in the view layer's alpha at least minRoughness).
std::vector<std::uint8_t> resolvedPixels(const FrameReadback& normalLayer, const FrameReadback& viewLayer, double minRoughness)
{
    const std::size_t pixels = std::size_t(normalLayer.width) * std::size_t(normalLayer.height);
    if (normalLayer.rgba.size() != pixels * 4 || viewLayer.rgba.size() != pixels * 4)
        throw std::invalid_argument("bench error measure: the reference's layers differ in size");
    std::vector<std::uint8_t> include(pixels);
    for (std::size_t i = 0; i < pixels; ++i) include[i] = surfacePixel(normalLayer, i) && roughnessAt(viewLayer, i) >= minRoughness;
    return include;
}

// Of those, the ones the error view measures (isMeasuredPixel): covered wholly by the
// frame's surfaces too, so that an MSAA silhouette pixel, part sky, is left out.
std::vector<std::uint8_t> resolvedPixels(const FrameReadback& frame, const FrameReadback& reference, const FrameReadback& normalLayer,
                                         const FrameReadback& viewLayer, double minRoughness)
{
    if (frame.rgba.size() != normalLayer.rgba.size() || reference.rgba.size() != normalLayer.rgba.size())
        throw std::invalid_argument("bench error measure: the frame, the reference and its layers differ in size");
    std::vector<std::uint8_t> include = resolvedPixels(normalLayer, viewLayer, minRoughness);
    for (std::size_t i = 0; i < include.size(); ++i) include[i] = include[i] && isMeasuredPixel(frame.rgba[i * 4 + 3], normalLayer.rgba[i * 4 + 3]);
    return include;
}

// Why the reference resolves none of the frame's surface pixels, naming what would; empty
// when it resolves some. `surfaces` says where the scene's roughness comes from (SceneFacts).
std::string unmeasuredReason(const FrameReadback& normalLayer, const FrameReadback& viewLayer, const ReferenceSummary& reference,
                             const std::string& surfaces, int mapWidth)
{
    const std::vector<std::uint8_t> include = resolvedPixels(normalLayer, viewLayer, reference.minResolvedRoughness);
    if (std::find(include.begin(), include.end(), std::uint8_t(1)) != include.end()) return "";
    double roughest = -1.0;
    for (std::size_t i = 0; i < include.size(); ++i)
        if (surfacePixel(normalLayer, i)) roughest = std::max(roughest, roughnessAt(viewLayer, i));
    if (roughest < 0.0) return "no surface in the frame (" + surfaces + ")";
    std::string why = "no surface pixel has roughness >= " + formatNumber(reference.minResolvedRoughness, "%.3g") + ", the smallest the " +
                      std::to_string(reference.environmentWidth) + "-wide reference resolves; the roughest is " + formatNumber(roughest, "%.3g") +
                      " (" + surfaces + ")";
    const int wider = referenceWidthFor(roughest, mapWidth);
    if (referenceMinResolvedRoughness(wider) > roughest)
        return why + ", which no reference over the " + std::to_string(mapWidth) + "-wide map resolves";
    return why + ": a reference " + std::to_string(wider) + " wide resolves it (--reference-width " + std::to_string(wider) + ")";
}

} // namespace

// The bake every point starts from: the default preset without the irradiance cubes (a
// diffuse point turns on the one it measures), the LUT of the default geometry term only.
bake::BakeSettings benchBaseBake(bool quick)
{
    bake::BakeSettings b = bake::defaultPreset();
    b.preset = quick ? "bench-quick" : "bench";
    b.irradiance = bake::IrradianceMethod::None; // the diffuse points choose theirs
    b.lut.schlickGgx = SamplingSettings{}.geometry == GeometryTerm::SchlickGGX;
    b.lut.heightCorrelatedSmith = !b.lut.schlickGgx;
    if (quick) {
        // Small enough that a bake is tens of milliseconds on llvmpipe.
        b.cube.maxFaceSize = 64;
        b.prefilter.faceSize = 32;
        b.prefilter.samples = 32;
        b.lut.size = 64;
        b.lut.samples = 256;
    } else {
        b.lut.samples = 1024;
    }
    return b;
}

std::vector<SweepPoint> sweepPoints(bool quick)
{
    const bake::BakeSettings base = benchBaseBake(quick);
    std::vector<SweepPoint> points;

    const std::vector<int> faces = quick ? std::vector<int>{32} : std::vector<int>{32, 64, 128};
    const std::vector<int> prefilterSamples = quick ? std::vector<int>{4, 16, 64} : std::vector<int>{4, 16, 64, 256, 1024};
    for (int face : faces)
        for (bool pdf : {true, false})
            for (int samples : prefilterSamples) {
                SweepPoint p;
                p.family = "split-sum";
                p.series = "split-sum f" + std::to_string(face) + ", " + onOff(pdf, "PDF mips");
                p.label = "split-sum, prefilter face " + std::to_string(face) + ", " + std::to_string(samples) + " samples, " + onOff(pdf, "PDF mips");
                p.parameter = samples;
                p.bake = base;
                p.bake.prefilter.faceSize = face;
                p.bake.prefilter.samples = samples;
                p.bake.prefilter.mipFiltering = pdf;
                points.push_back(p);
            }

    const std::vector<int> ns = quick ? std::vector<int>{1, 16} : std::vector<int>{1, 4, 16, 64, 256};
    for (bool pdf : {true, false})
        for (int n : ns) {
            SweepPoint p;
            p.family = "sampled";
            p.series = "sampled, " + onOff(pdf, "PDF mips");
            p.label = "sampled, N = " + std::to_string(n) + ", " + onOff(pdf, "PDF mips");
            p.parameter = n;
            p.bake = base;
            p.sampling.method = ShadingMethod::Sampled;
            p.sampling.samples = n;
            p.sampling.pdfMipFiltering = pdf;
            points.push_back(p);
        }

    // Diffuse sources under the base bake's split-sum specular: what differs between these
    // points is the diffuse term alone (the grid's dielectric rows show it).
    for (bool plain : {true, false}) {
        SweepPoint p;
        p.family = "diffuse";
        p.series = plain ? "SH9" : "SH9 windowed";
        p.label = plain ? "diffuse SH9 (no window)" : "diffuse SH9, Hanning window";
        p.bake = base;
        p.plainSh = plain;
        points.push_back(p);
    }
    for (double delta : quick ? std::vector<double>{0.1} : std::vector<double>{0.1, 0.05, 0.025}) {
        SweepPoint p;
        p.family = "diffuse";
        p.series = "Riemann cube";
        p.label = "diffuse irradiance cube, Riemann, sampleDelta " + formatNumber(delta);
        p.parameter = 1.0 / delta;
        p.bake = base;
        p.bake.irradiance = bake::IrradianceMethod::Riemann;
        p.bake.riemann.sampleDelta = float(delta);
        if (quick) p.bake.riemann.faceSize = 16;
        p.sampling.diffuse = DiffuseSource::IrradianceCube;
        points.push_back(p);
    }
    for (int samples : quick ? std::vector<int>{64} : std::vector<int>{64, 512, 4096}) {
        SweepPoint p;
        p.family = "diffuse";
        p.series = "importance cube";
        p.label = "diffuse irradiance cube, cosine importance, " + std::to_string(samples) + " samples";
        p.parameter = samples;
        p.bake = base;
        p.bake.irradiance = bake::IrradianceMethod::Importance;
        p.bake.importance.samples = samples;
        p.sampling.diffuse = DiffuseSource::IrradianceCube;
        points.push_back(p);
    }
    for (int groups : quick ? std::vector<int>{4} : std::vector<int>{4, 8}) {
        SweepPoint p;
        p.family = "diffuse";
        p.series = "moment cube";
        p.label = "diffuse irradiance cube, moments of " + std::to_string(groups) + "^2 texel groups per face";
        p.parameter = groups;
        p.bake = base;
        p.bake.irradiance = bake::IrradianceMethod::Moments;
        p.bake.moments.sourceFaceSize = groups;
        if (quick) p.bake.moments.faceSize = 16;
        p.sampling.diffuse = DiffuseSource::IrradianceCube;
        points.push_back(p);
    }
    return points;
}

std::vector<BenchEnvironment> builtinBenchEnvironments(int width)
{
    // A bright small light, saturated colour, and sub-texel detail: where methods differ most.
    // Prefixed, so that the builtin studio is not taken for the bundled studio.exr.
    std::vector<BenchEnvironment> list;
    for (const stress::StressEnvironment& e : stress::stressEnvironments(width))
        if (e.name == "sun-1e3" || e.name == "studio" || e.name == "slits") list.push_back({"builtin-" + e.name, e.spec, nullptr});
    return list;
}

BenchOptions defaultBenchOptions(bool quick, const std::string& assetDirectory)
{
    BenchOptions o;
    o.quick = quick;
    o.frame.scene.kind = SceneKind::Grid;
    o.points = sweepPoints(quick);
    if (quick) {
        o.width = o.height = 48;
        o.repeats = 3;
        o.environments.push_back({"sky", "builtin:sky?width=64", nullptr});
    } else {
        for (const std::string& path : galleryEnvironments(assetDirectory))
            o.environments.push_back({std::filesystem::path(path).stem().string(), path, nullptr});
        for (BenchEnvironment& e : builtinBenchEnvironments(512)) o.environments.push_back(std::move(e));
    }
    return o;
}

std::vector<std::string> bakePhasesRead(const SweepPoint& point)
{
    std::vector<std::string> phases{"upload", "environment_cube"};
    if (point.sampling.method == ShadingMethod::SplitSum) phases.push_back("prefilter");
    if (point.sampling.diffuse == DiffuseSource::Sh9 || point.sampling.method == ShadingMethod::Sampled) phases.push_back("sh9");
    else phases.push_back("irradiance_" + std::string(enumName(point.bake.irradiance)));
    return phases;
}

ErrorMetrics measureResolvedError(const FrameReadback& frame, const FrameReadback& reference, const FrameReadback& normalLayer,
                                  const FrameReadback& viewLayer, double minRoughness)
{
    ErrorMetrics m = computeErrorMetrics(frame.rgba, reference.rgba, resolvedPixels(frame, reference, normalLayer, viewLayer, minRoughness));
    if (m.pixels == 0) m.relativeRmse = m.meanRelative = m.maxRelative = m.p99Relative = kNoError;
    return m;
}

DisplayError measureResolvedDisplayError(const FrameReadback& frame, const FrameReadback& reference, const FrameReadback& normalLayer,
                                         const FrameReadback& viewLayer, double minRoughness, const ToneMapSettings& toneMap)
{
    const std::vector<std::uint8_t> include = resolvedPixels(frame, reference, normalLayer, viewLayer, minRoughness);
    const auto shown = [&](const FrameReadback& image, std::size_t i) {
        return displayEncode(glm::vec3(image.rgba[i * 4], image.rgba[i * 4 + 1], image.rgba[i * 4 + 2]), toneMap.exposureEv, toneMap.op);
    };
    std::vector<double> steps;
    double sumSquares = 0.0;
    DisplayError e;
    for (std::size_t i = 0; i < include.size(); ++i) {
        if (!include[i]) continue;
        const glm::vec3 difference = glm::abs(shown(frame, i) - shown(reference, i));
        const double s = 255.0 * double(std::max({difference.r, difference.g, difference.b}));
        steps.push_back(s);
        sumSquares += s * s;
        e.maxSteps = std::max(e.maxSteps, s);
    }
    e.pixels = steps.size();
    if (steps.empty()) {
        e.p99Steps = e.rmsSteps = e.maxSteps = kNoError;
        return e;
    }
    e.rmsSteps = std::sqrt(sumSquares / double(steps.size()));
    const std::size_t rank = std::size_t(std::ceil(0.99 * double(steps.size()))) - 1;
    std::nth_element(steps.begin(), steps.begin() + std::ptrdiff_t(rank), steps.end());
    e.p99Steps = steps[rank];
    return e;
}

bool measured(const BenchPoint& point) { return !std::isnan(point.error.relativeRmse); }

std::vector<std::string> unmeasuredEnvironments(const BenchReport& report)
{
    std::vector<std::string> lines;
    for (const ReferenceSummary& r : report.references)
        if (!r.unmeasured.empty()) lines.push_back(r.environment + ": not measured: " + r.unmeasured);
    return lines;
}

// NaN compares false both ways: a point without an error is neither dominated nor dominates.
void markDominated(std::vector<BenchPoint>& points, double (*error)(const BenchPoint&))
{
    for (BenchPoint& p : points)
        p.dominated = std::any_of(points.begin(), points.end(), [&](const BenchPoint& q) {
            return q.environment == p.environment && q.costMilliseconds < p.costMilliseconds && error(q) < error(p);
        });
}

void markDominated(std::vector<BenchPoint>& points)
{
    markDominated(points, [](const BenchPoint& p) { return p.error.relativeRmse; });
}

// ---- The job ------------------------------------------------------------------------------

struct BenchJob::State {
    enum class Phase { Load, Bake, Reference, Measure, Done };

    Renderer& renderer;
    Phase phase = Phase::Load;
    std::optional<Clock::time_point> started;
    std::size_t environment = 0;
    std::size_t point = 0;
    std::shared_ptr<const Environment> loaded;
    FrameSettings frame;
    std::unique_ptr<bake::BakeJob> bakeJob;
    std::shared_ptr<bake::BakeResult> bake;
    // The LUT depends on no environment: baked by the first point, handed on to the next.
    std::array<bake::BakedTexture, 2> lut;
    ReferenceSummary reference;
    std::string surfaces; // SceneFacts::surfaces, for the reason when nothing can be measured
    FrameReadback referenceFrame, normalLayer, viewLayer;

    explicit State(Renderer& r) : renderer(r) {}

    FrameSettings frameFor(const SweepPoint& p) const
    {
        FrameSettings s = frame;
        s.sampling = p.sampling;
        return s;
    }
};

BenchJob::BenchJob(Renderer& renderer, BenchOptions options) : state_(std::make_unique<State>(renderer))
{
    if (options.environments.empty()) throw Error("iblab bench", "no environment to sweep");
    if (options.points.empty()) throw Error("iblab bench", "no sweep point");
    // Points are told apart by environment name (dominance, charts, tables).
    for (std::size_t i = 0; i < options.environments.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (options.environments[i].name == options.environments[j].name)
                throw Error("iblab bench", "two environments are named \"" + options.environments[i].name + "\" (" + options.environments[j].spec +
                                               " and " + options.environments[i].spec + ")");
    if (options.width < 8 || options.height < 8) throw Error("iblab bench", "the image must be at least 8x8");
    options.repeats = std::max(options.repeats, 1);
    options.frame.view.mode = ViewMode::Final;
    options.frame.view.split = false;
    for (const SweepPoint& p : options.points) bake::validate(p.bake);
    if (options.frame.scene.kind == SceneKind::Model) renderer.setModel(loadGltfModel(options.frame.scene.modelPath), options.frame.scene.modelPath);
    report_.renderer = gl::describeCurrentContext();
    report_.options = std::move(options);
}

BenchJob::~BenchJob() = default;

bool BenchJob::done() const { return state_->phase == State::Phase::Done; }

float BenchJob::progress() const
{
    const State& s = *state_;
    const double total = double(report_.options.environments.size() * report_.options.points.size());
    double done = double(report_.points.size());
    if (s.phase == State::Phase::Bake && s.bakeJob) done += 0.9 * s.bakeJob->progress();
    return float(std::min(1.0, done / total));
}

const BenchEnvironment* BenchJob::currentEnvironment() const
{
    return done() ? nullptr : &report_.options.environments[state_->environment];
}

std::string BenchJob::currentActivity() const
{
    const State& s = *state_;
    const BenchOptions& o = report_.options;
    if (s.phase == State::Phase::Done) return "";
    const std::string where = o.environments[s.environment].name + ": ";
    const SweepPoint& p = o.points[s.point];
    switch (s.phase) {
    case State::Phase::Load: return where + "loading";
    case State::Phase::Bake: return where + "baking " + p.label + (s.bakeJob ? " (" + s.bakeJob->currentPhase() + ")" : "");
    case State::Phase::Reference: return where + "reference";
    case State::Phase::Measure: return where + "rendering " + p.label;
    case State::Phase::Done: break;
    }
    return "";
}

bool BenchJob::step()
{
    State& s = *state_;
    BenchOptions& o = report_.options;
    if (!s.started) s.started = Clock::now();
    const auto startBake = [&] {
        bake::BakeSettings settings = o.points[s.point].bake;
        if (s.lut[std::size_t(GeometryTerm::SchlickGGX)]) settings.lut.schlickGgx = false;
        if (s.lut[std::size_t(GeometryTerm::HeightCorrelatedSmith)]) settings.lut.heightCorrelatedSmith = false;
        s.bakeJob = std::make_unique<bake::BakeJob>(s.renderer.shaders(), *s.loaded, settings);
        s.phase = State::Phase::Bake;
    };

    switch (s.phase) {
    case State::Phase::Load: {
        const BenchEnvironment& env = o.environments[s.environment];
        s.loaded = env.loaded ? env.loaded : std::make_shared<const Environment>(loadEnvironment(env.spec));
        s.renderer.setEnvironment(s.loaded->image);
        s.frame = o.frame;
        s.frame.environment.source = s.loaded->source;
        const SceneFacts facts = sceneFacts(o.frame, s.loaded->image);
        s.frame.view.referenceWidth = o.referenceWidth > 0 ? o.referenceWidth : referenceWidthFor(facts, o.quick);
        s.surfaces = facts.surfaces;
        if (o.frameCamera) {
            const SceneInfo scene = s.renderer.sceneInfo(s.frame);
            frameBox(s.frame.camera, scene.centre, scene.halfExtents, float(o.width) / float(o.height));
        }
        s.reference = {o.environments[s.environment].name, 0, 0.0, 0.0};
        s.referenceFrame = {};
        s.point = 0;
        startBake();
        return true;
    }
    case State::Phase::Bake: {
        if (s.bakeJob->step()) return true;
        s.bake = std::make_shared<bake::BakeResult>(s.bakeJob->takeResult());
        s.bakeJob.reset();
        for (std::size_t t = 0; t < s.lut.size(); ++t)
            if (s.lut[t]) s.bake->brdfLut[t] = std::move(s.lut[t]);
        // Plain SH9 is the same bake without the window: the renderer reads the windowed set.
        if (o.points[s.point].plainSh) s.bake->sh.irradianceWindowed = s.bake->sh.irradiance;
        s.renderer.setBake(s.bake);
        s.phase = s.referenceFrame.rgba.empty() ? State::Phase::Reference : State::Phase::Measure;
        return true;
    }
    case State::Phase::Reference: {
        // Slices of about 20 ms, so that the GUI's frame stays short.
        const auto start = Clock::now();
        const ReferenceStatus status = s.renderer.advanceReference(s.frameFor(o.points[s.point]), o.width, o.height, std::chrono::milliseconds(20));
        s.reference.milliseconds += millisecondsSince(start);
        if (!status.current) throw Error("iblab bench", "the reference did not start (no bake?)");
        if (!status.complete) return true;
        s.reference.environmentWidth = status.environmentWidth;
        s.reference.minResolvedRoughness = status.minResolvedRoughness;
        s.referenceFrame = s.renderer.readReferenceFrame();
        s.normalLayer = s.renderer.readReferenceLayer(ReferenceLayer::Normal);
        s.viewLayer = s.renderer.readReferenceLayer(ReferenceLayer::View);
        s.reference.unmeasured = unmeasuredReason(s.normalLayer, s.viewLayer, s.reference, s.surfaces, s.loaded->image.width);
        report_.references.push_back(s.reference);
        s.phase = State::Phase::Measure;
        return true;
    }
    case State::Phase::Measure: {
        const SweepPoint& p = o.points[s.point];
        const FrameSettings settings = s.frameFor(p);
        // One frame first: it compiles the method's shader permutation, which is not its cost.
        s.renderer.renderFrame(settings, o.width, o.height);
        glFinish();
        std::vector<double> frameMs;
        for (int i = 0; i < o.repeats; ++i) {
            const auto start = Clock::now();
            s.renderer.renderFrame(settings, o.width, o.height);
            glFinish(); // llvmpipe's timer queries are wrong at this size: wall clock around glFinish
            frameMs.push_back(millisecondsSince(start));
        }
        std::sort(frameMs.begin(), frameMs.end());

        BenchPoint measured;
        measured.environment = o.environments[s.environment].name;
        measured.setting = p;
        for (const std::string& phase : bakePhasesRead(p)) measured.bakeMilliseconds += s.bake->phaseMilliseconds(phase);
        measured.frameMilliseconds = frameMs[frameMs.size() / 2];
        measured.costMilliseconds = measured.bakeMilliseconds + double(o.costFrames) * measured.frameMilliseconds;
        const FrameReadback frame = s.renderer.readHdrFrame();
        measured.error = measureResolvedError(frame, s.referenceFrame, s.normalLayer, s.viewLayer, s.reference.minResolvedRoughness);
        measured.display = measureResolvedDisplayError(frame, s.referenceFrame, s.normalLayer, s.viewLayer, s.reference.minResolvedRoughness, o.frame.toneMap);
        report_.points.push_back(std::move(measured));
        markDominated(report_.points);

        s.lut = std::move(s.bake->brdfLut);
        s.renderer.setBake(nullptr);
        s.bake.reset();
        if (++s.point < o.points.size()) {
            startBake();
            return true;
        }
        if (++s.environment < o.environments.size()) {
            s.phase = State::Phase::Load;
            return true;
        }
        s.phase = State::Phase::Done;
        report_.seconds = std::chrono::duration<double>(Clock::now() - *s.started).count();
        s.loaded.reset();
        s.lut = {};
        return false;
    }
    case State::Phase::Done: return false;
    }
    return false;
}

bool BenchJob::runFor(std::chrono::steady_clock::duration budget)
{
    const auto start = Clock::now();
    while (step())
        if (Clock::now() - start >= budget) return true;
    return false;
}

BenchReport BenchJob::runToCompletion()
{
    while (step()) {
    }
    for (BenchEnvironment& e : report_.options.environments) e.loaded.reset();
    return report_;
}

// ---- Reports ------------------------------------------------------------------------------

namespace {

std::string diffuseName(const SweepPoint& p)
{
    if (p.sampling.diffuse == DiffuseSource::Sh9 || p.sampling.method == ShadingMethod::Sampled) return p.plainSh ? "sh9" : "sh9-windowed";
    return p.bake.irradiance == bake::IrradianceMethod::Moments      ? "moment-cube"
           : p.bake.irradiance == bake::IrradianceMethod::Importance ? "importance-cube"
                                                                     : "riemann-cube";
}

bool pdfFiltering(const SweepPoint& p)
{
    return p.sampling.method == ShadingMethod::Sampled ? p.sampling.pdfMipFiltering : p.bake.prefilter.mipFiltering;
}

std::string csvField(const std::string& text)
{
    if (text.find_first_of(",\"\n") == std::string::npos) return text;
    std::string quoted = "\"";
    for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

} // namespace

const std::vector<std::string>& benchCsvColumns()
{
    static const std::vector<std::string> columns{
        "environment", "family",        "series",         "label",        "method",        "diffuse",      "prefilter_face", "prefilter_samples",
        "pdf_mips",    "sampled_n",     "riemann_delta",  "importance_samples", "bake_ms", "frame_ms",     "cost_ms",        "relative_rmse",
        "mean_relative", "p99_relative", "max_relative",  "fireflies",    "pixels",        "display_p99_steps", "display_rms_steps",
        "display_max_steps", "dominated", "auto_chosen"};
    return columns;
}

std::string benchCsvText(const BenchReport& report)
{
    std::ostringstream out;
    const auto& columns = benchCsvColumns();
    for (std::size_t i = 0; i < columns.size(); ++i) out << (i ? "," : "") << columns[i];
    out << "\n";
    for (const BenchPoint& p : report.points) {
        const SweepPoint& s = p.setting;
        const bool splitSum = s.sampling.method == ShadingMethod::SplitSum;
        // Empty, not 0, where nothing was measured: 0 would read as exact.
        const auto error = [&](double value, const char* format) { return measured(p) ? formatNumber(value, format) : std::string(); };
        const std::vector<std::string> row{csvField(p.environment),
                                           s.family,
                                           csvField(s.series),
                                           csvField(s.label),
                                           std::string(enumName(s.sampling.method)),
                                           diffuseName(s),
                                           splitSum ? std::to_string(s.bake.prefilter.faceSize) : "",
                                           splitSum ? std::to_string(s.bake.prefilter.samples) : "",
                                           pdfFiltering(s) ? "1" : "0",
                                           splitSum ? "" : std::to_string(s.sampling.samples),
                                           s.bake.irradiance == bake::IrradianceMethod::Riemann ? formatNumber(s.bake.riemann.sampleDelta) : "",
                                           s.bake.irradiance == bake::IrradianceMethod::Importance ? std::to_string(s.bake.importance.samples) : "",
                                           formatNumber(p.bakeMilliseconds, "%.3f"),
                                           formatNumber(p.frameMilliseconds, "%.3f"),
                                           formatNumber(p.costMilliseconds, "%.3f"),
                                           error(p.error.relativeRmse, "%.6g"),
                                           error(p.error.meanRelative, "%.6g"),
                                           error(p.error.p99Relative, "%.6g"),
                                           error(p.error.maxRelative, "%.6g"),
                                           measured(p) ? std::to_string(p.error.fireflies) : "",
                                           std::to_string(p.error.pixels),
                                           error(p.display.p99Steps, "%.4g"),
                                           error(p.display.rmsSteps, "%.4g"),
                                           error(p.display.maxSteps, "%.4g"),
                                           p.dominated ? "1" : "0",
                                           p.chosen ? "1" : "0"};
        for (std::size_t i = 0; i < row.size(); ++i) out << (i ? "," : "") << row[i];
        out << "\n";
    }
    return out.str();
}

std::string benchJsonText(const BenchReport& report)
{
    const BenchOptions& o = report.options;
    nlohmann::ordered_json j;
    j["renderer"] = report.renderer;
    j["timing_method"] = "steady clock around glFinish, median of the repeats";
    j["options"] = {{"quick", o.quick},
                    {"scene", enumName(o.frame.scene.kind)},
                    {"width", o.width},
                    {"height", o.height},
                    {"repeats", o.repeats},
                    // null: chosen per environment from the scene (the references' environment_width)
                    {"reference_width", o.referenceWidth > 0 ? nlohmann::ordered_json(o.referenceWidth) : nlohmann::ordered_json(nullptr)},
                    {"cost", "bake_ms + " + std::to_string(o.costFrames) + " x frame_ms"},
                    {"error", "relative RMSE, linear HDR, surface pixels with roughness >= min_resolved_roughness; null where there is none (references' not_measured)"},
                    {"display_error", "largest channel difference after exposure, tone mapping and sRGB encoding, in 8-bit steps, same pixels"},
                    {"tone_map", std::string(enumName(o.frame.toneMap.op)) + ", exposure " + formatNumber(o.frame.toneMap.exposureEv) + " EV"}};
    for (const BenchEnvironment& e : o.environments) j["environments"].push_back({{"name", e.name}, {"spec", e.spec}});
    for (const ReferenceSummary& r : report.references) {
        nlohmann::ordered_json reference{{"environment", r.environment},
                                         {"environment_width", r.environmentWidth},
                                         {"min_resolved_roughness", r.minResolvedRoughness},
                                         {"milliseconds", r.milliseconds}};
        if (!r.unmeasured.empty()) reference["not_measured"] = r.unmeasured;
        j["references"].push_back(reference);
    }
    for (const BenchPoint& p : report.points) {
        const SweepPoint& s = p.setting;
        nlohmann::ordered_json point{{"environment", p.environment},
                                     {"family", s.family},
                                     {"series", s.series},
                                     {"label", s.label},
                                     {"method", enumName(s.sampling.method)},
                                     {"diffuse", diffuseName(s)},
                                     {"pdf_mips", pdfFiltering(s)}};
        if (s.sampling.method == ShadingMethod::SplitSum)
            point["prefilter"] = {{"face", s.bake.prefilter.faceSize}, {"samples", s.bake.prefilter.samples}, {"levels", s.bake.prefilter.levels}};
        else point["sampled_n"] = s.sampling.samples;
        if (s.bake.irradiance == bake::IrradianceMethod::Riemann) point["riemann_delta"] = s.bake.riemann.sampleDelta;
        if (s.bake.irradiance == bake::IrradianceMethod::Importance) point["importance_samples"] = s.bake.importance.samples;
        point["bake_phases"] = bakePhasesRead(s);
        point["bake_ms"] = p.bakeMilliseconds;
        point["frame_ms"] = p.frameMilliseconds;
        point["cost_ms"] = p.costMilliseconds;
        // null, not 0, where nothing was measured: 0 would read as exact.
        const auto error = [&](auto value) { return measured(p) ? nlohmann::ordered_json(value) : nlohmann::ordered_json(nullptr); };
        point["error"] = {{"relative_rmse", error(p.error.relativeRmse)},
                          {"mean_relative", error(p.error.meanRelative)},
                          {"p99_relative", error(p.error.p99Relative)},
                          {"max_relative", error(p.error.maxRelative)},
                          {"fireflies", error(p.error.fireflies)},
                          {"pixels", p.error.pixels}};
        point["display_error"] = {
            {"p99_steps", error(p.display.p99Steps)}, {"rms_steps", error(p.display.rmsSteps)}, {"max_steps", error(p.display.maxSteps)}};
        point["dominated"] = p.dominated;
        if (p.chosen) point["auto_chosen"] = true;
        j["points"].push_back(point);
    }
    j["seconds"] = report.seconds;
    return j.dump(2);
}

std::string benchMarkdown(const BenchReport& report)
{
    struct Environment {
        std::string name;
        std::vector<const BenchPoint*> points, front; // front: measured and not dominated
        double cheapest = 0.0;
        std::string unmeasured; // ReferenceSummary::unmeasured
        // The lowest error of a family and what it costs.
        const BenchPoint* best(const std::string& family) const
        {
            const BenchPoint* found = nullptr;
            for (const BenchPoint* p : points)
                if (measured(*p) && p->setting.family == family && (!found || p->error.relativeRmse < found->error.relativeRmse)) found = p;
            return found;
        }
    };
    std::vector<Environment> environments;
    for (const BenchEnvironment& e : report.options.environments) {
        Environment env{e.name, {}, {}, 0.0, {}};
        for (const BenchPoint& p : report.points) {
            if (p.environment != e.name) continue;
            env.points.push_back(&p);
            if (!p.dominated && measured(p)) env.front.push_back(&p);
        }
        if (env.points.empty()) continue;
        for (const ReferenceSummary& r : report.references)
            if (r.environment == e.name) env.unmeasured = r.unmeasured;
        std::sort(env.front.begin(), env.front.end(), [](const BenchPoint* a, const BenchPoint* b) { return a->costMilliseconds < b->costMilliseconds; });
        if (!env.front.empty()) env.cheapest = std::max(env.front.front()->costMilliseconds, 1e-9);
        environments.push_back(std::move(env));
    }

    std::ostringstream out;
    const auto bestCell = [&](const Environment& env, const char* family) {
        const BenchPoint* p = env.best(family);
        if (!p) return std::string("-");
        return formatNumber(p->error.relativeRmse, "%.3g") + " at " + formatNumber(p->costMilliseconds / env.cheapest, "%.1f") + "x (" + p->setting.label + ")";
    };
    out << "Per environment: how many settings nothing beats on both axes, and each family's lowest relative RMSE with its cost as a "
           "multiple of the environment's cheapest setting.\n\n";
    out << "| environment | not dominated | split-sum: lowest error | sampled: lowest error | diffuse variants: error range |\n|---|---|---|---|---|\n";
    for (const Environment& env : environments) {
        if (env.front.empty()) {
            out << "| " << env.name << " | not measured | n/a | n/a | n/a |\n";
            continue;
        }
        double lo = 1e300, hi = 0.0;
        for (const BenchPoint* p : env.points)
            if (measured(*p) && p->setting.family == "diffuse") lo = std::min(lo, p->error.relativeRmse), hi = std::max(hi, p->error.relativeRmse);
        out << "| " << env.name << " | " << env.front.size() << " of " << env.points.size() << " | " << bestCell(env, "split-sum") << " | "
            << bestCell(env, "sampled") << " | " << (hi > 0.0 ? formatNumber(lo, "%.3g") + " - " + formatNumber(hi, "%.3g") : "-") << " |\n";
    }
    out << "\n";
    for (const Environment& env : environments) {
        if (env.front.empty()) {
            out << "**" << env.name << "**: not measured: " << env.unmeasured << "\n\n";
            continue;
        }
        out << "**" << env.name << "**: " << env.front.size() << " of " << env.points.size() << " settings are not dominated\n\n";
        out << "| setting | cost / cheapest | relative RMSE | bake ms | frame ms |\n|---|---|---|---|---|\n";
        for (const BenchPoint* p : env.front)
            out << "| " << p->setting.label << " | " << formatNumber(p->costMilliseconds / env.cheapest, "%.2f") << " | "
                << formatNumber(p->error.relativeRmse, "%.3g") << " | " << formatNumber(p->bakeMilliseconds, "%.1f") << " | "
                << formatNumber(p->frameMilliseconds, "%.1f") << " |\n";
        out << "\n";
    }
    return out.str();
}

} // namespace iblab::bench
