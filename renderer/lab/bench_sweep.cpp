#include "lab/bench_sweep.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <utility>

#include "bake/bake_result.hpp"
#include "lab/auto_quality.hpp"
#include "lab/format.hpp"
#include "frame/camera.hpp"
#include "io/error.hpp"
#include "gl/context_info.hpp"
#include "ibl/reference.hpp"
#include "scene/gltf_model.hpp"
#include "lab/stress_suite.hpp"

namespace iblab::bench {
namespace {

using Clock = std::chrono::steady_clock;

using lab::formatNumber;

std::string onOff(bool on, const char* what) { return std::string(on ? "" : "no ") + what; }

// Why the reference resolves none of the frame's surface pixels, naming what would; empty
// when it resolves some. `surfaces` says where the scene's roughness comes from (SceneFacts).
std::string unmeasuredReason(const lab::ReferenceFrame& frame, const ReferenceSummary& reference, const std::string& surfaces, int mapWidth)
{
    const std::vector<std::uint8_t> include = lab::resolvedSurfacePixels(frame.normalLayer, frame.viewLayer, reference.minResolvedRoughness);
    if (std::find(include.begin(), include.end(), std::uint8_t(1)) != include.end()) return "";
    const double roughest = lab::roughestSurface(frame.normalLayer, frame.viewLayer);
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
                p.family = SweepFamily::SplitSum;
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
            p.family = SweepFamily::Sampled;
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
        p.family = SweepFamily::Diffuse;
        p.series = plain ? "SH9" : "SH9 windowed";
        p.label = plain ? "diffuse SH9 (no window)" : "diffuse SH9, Hanning window";
        p.bake = base;
        if (plain) p.sampling.diffuse = DiffuseSource::Sh9Plain;
        points.push_back(p);
    }
    for (double delta : quick ? std::vector<double>{0.1} : std::vector<double>{0.1, 0.05, 0.025}) {
        SweepPoint p;
        p.family = SweepFamily::Diffuse;
        p.series = "Riemann cube";
        p.label = "diffuse irradiance cube, Riemann, sampleDelta " + formatNumber(delta, "%g");
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
        p.family = SweepFamily::Diffuse;
        p.series = "importance cube";
        p.label = "diffuse irradiance cube, cosine importance, " + std::to_string(samples) + " samples";
        p.parameter = samples;
        p.bake = base;
        p.bake.irradiance = bake::IrradianceMethod::Importance;
        p.bake.importance.samples = samples;
        p.sampling.diffuse = DiffuseSource::IrradianceCube;
        points.push_back(p);
    }
    // Where and how wide the cube is read, each on the base bake with the default's diffuse
    // (the moment irradiance cube), so that the split sum at R among them is today's default
    // shading and a run of this family alone has its baseline (docs/accuracy-study.md).
    for (const auto& [method, direction] : {std::pair{ShadingMethod::SplitSum, SpecularDirection::Reflection},
                                            std::pair{ShadingMethod::SplitSum, SpecularDirection::Frostbite},
                                            std::pair{ShadingMethod::SplitSum, SpecularDirection::Filament},
                                            std::pair{ShadingMethod::FittedLobe, SpecularDirection::Reflection}}) {
        SweepPoint p;
        p.family = SweepFamily::SpecularLobe;
        p.bake = base;
        p.bake.irradiance = bake::IrradianceMethod::Moments;
        if (quick) p.bake.moments.faceSize = 16;
        p.sampling.diffuse = DiffuseSource::IrradianceCube;
        p.sampling.method = method;
        p.sampling.specularDirection = direction;
        p.series = specularReadName(p.sampling);
        p.label = p.series + ", prefilter face " + std::to_string(base.prefilter.faceSize) + ", " + std::to_string(base.prefilter.samples) + " samples";
        p.parameter = base.prefilter.samples;
        points.push_back(p);
    }
    for (int groups : quick ? std::vector<int>{4} : std::vector<int>{4, 8}) {
        SweepPoint p;
        p.family = SweepFamily::Diffuse;
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

std::string specularReadName(const SamplingSettings& sampling)
{
    if (sampling.method == ShadingMethod::FittedLobe) return "fitted lobe";
    if (sampling.method != ShadingMethod::SplitSum) return "";
    switch (sampling.specularDirection) {
    case SpecularDirection::Reflection: return "split-sum";
    case SpecularDirection::Frostbite: return "split-sum, Frostbite direction";
    case SpecularDirection::Filament: return "split-sum, Filament direction";
    }
    return "";
}

std::vector<BenchEnvironment> builtinBenchEnvironments(int width)
{
    // Prefixed, so that the builtin studio is not taken for the bundled studio.exr.
    std::vector<BenchEnvironment> list;
    for (const stress::StressEnvironment& e : stress::stressEnvironments(width))
        if (e.inBench) list.push_back({"builtin-" + e.name, e.spec, nullptr});
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

std::vector<bake::BakePhase> bakePhasesRead(const SweepPoint& point)
{
    using bake::BakePhase;
    std::vector<BakePhase> phases{BakePhase::Upload, BakePhase::EnvironmentCube};
    if (readsPrefilteredCube(point.sampling.method)) phases.push_back(BakePhase::Prefilter);
    if (point.sampling.diffuse != DiffuseSource::IrradianceCube || point.sampling.method == ShadingMethod::Sampled) phases.push_back(BakePhase::Sh9);
    else phases.push_back(bake::irradiancePhase(point.bake.irradiance));
    return phases;
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

    lab::Harness harness;
    Phase phase = Phase::Load;
    std::optional<Clock::time_point> started;
    std::size_t environment = 0;
    std::size_t point = 0;
    FrameSettings frame;
    ReferenceSummary reference;
    std::string surfaces; // SceneFacts::surfaces, for the reason when nothing can be measured

    explicit State(Renderer& r) : harness(r) {}

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
    if (options.frame.scene.kind == SceneKind::Model) renderer.setModel(loadDrawableGltfModel(options.frame.scene.modelPath), options.frame.scene.modelPath);
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
    if (s.phase == State::Phase::Bake) done += 0.9 * s.harness.bakeProgress();
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
    const std::optional<bake::BakePhase> bakePhase = s.harness.bakePhase();
    switch (s.phase) {
    case State::Phase::Load: return where + "loading";
    case State::Phase::Bake: return where + "baking " + p.label + (bakePhase ? " (" + std::string(enumName(*bakePhase)) + ")" : "");
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
        s.harness.startBake(o.points[s.point].bake);
        s.phase = State::Phase::Bake;
    };

    switch (s.phase) {
    case State::Phase::Load: {
        const BenchEnvironment& env = o.environments[s.environment];
        const Environment& loaded = s.harness.loadEnvironment(env.spec, env.loaded);
        s.frame = o.frame;
        s.frame.environment.source = loaded.source;
        const SceneFacts facts = sceneFacts(o.frame, loaded.image);
        s.frame.view.referenceWidth = o.referenceWidth > 0 ? o.referenceWidth : referenceWidthFor(facts, o.quick);
        s.surfaces = facts.surfaces;
        if (o.frameCamera) {
            const SceneInfo scene = s.harness.renderer().sceneInfo(s.frame);
            frameBox(s.frame.camera, scene.centre, scene.halfExtents, float(o.width) / float(o.height));
        }
        s.reference = {env.name, 0, 0.0, 0.0, {}};
        s.point = 0;
        startBake();
        return true;
    }
    case State::Phase::Bake: {
        if (s.harness.stepBake()) return true;
        s.phase = s.harness.reference().complete() ? State::Phase::Measure : State::Phase::Reference;
        return true;
    }
    case State::Phase::Reference: {
        // Slices of about 20 ms, so that the GUI's frame stays short.
        const ReferenceStatus status = s.harness.advanceReference(s.frameFor(o.points[s.point]), o.width, o.height, std::chrono::milliseconds(20));
        s.reference.milliseconds = s.harness.reference().milliseconds;
        if (!status.current) throw Error("iblab bench", "the reference did not start (no bake?)");
        if (!status.complete) return true;
        s.reference.environmentWidth = status.environmentWidth;
        s.reference.minResolvedRoughness = status.minResolvedRoughness;
        s.reference.unmeasured = unmeasuredReason(s.harness.reference(), s.reference, s.surfaces, s.harness.environment().image.width);
        report_.references.push_back(s.reference);
        s.phase = State::Phase::Measure;
        return true;
    }
    case State::Phase::Measure: {
        const SweepPoint& p = o.points[s.point];
        BenchPoint measured;
        measured.environment = o.environments[s.environment].name;
        measured.setting = p;
        measured.frameMilliseconds = s.harness.medianFrameMilliseconds(s.frameFor(p), o.width, o.height, o.repeats);
        for (const bake::BakePhase phase : bakePhasesRead(p)) measured.bakeMilliseconds += s.harness.currentBake().phaseMilliseconds(phase);
        measured.costMilliseconds = measured.bakeMilliseconds + double(o.costFrames) * measured.frameMilliseconds;
        const lab::FrameError error = s.harness.compareWithReference(s.harness.renderer().readHdrFrame(), o.frame.toneMap);
        measured.error = error.linear;
        measured.display = error.display;
        report_.points.push_back(std::move(measured));
        markDominated(report_.points);

        // Consecutive points on the same bake (the sampled N, the diffuse SH9 variants, the
        // specular reads) measure the one bake: baking it again would give the same textures.
        const bool nextSharesBake = s.point + 1 < o.points.size() && bake::toJsonText(o.points[s.point + 1].bake) == bake::toJsonText(p.bake);
        if (!nextSharesBake) s.harness.retireBake();
        if (++s.point < o.points.size()) {
            if (!nextSharesBake) startBake();
            return true;
        }
        if (++s.environment < o.environments.size()) {
            s.phase = State::Phase::Load;
            return true;
        }
        s.phase = State::Phase::Done;
        report_.seconds = std::chrono::duration<double>(Clock::now() - *s.started).count();
        s.harness.release();
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


} // namespace iblab::bench
