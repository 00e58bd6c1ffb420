#include "lab/harness.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <epoxy/gl.h>

#include "bake/bake_job.hpp"
#include "ibl/tonemap.hpp"

namespace iblab::lab {
namespace {

using Clock = std::chrono::steady_clock;

// The error of a measurement over no pixel: NaN, which never reads as 0 (exact), and which
// compares false both ways, so that such a point neither dominates nor is dominated.
constexpr double kNoError = std::numeric_limits<double>::quiet_NaN();

double millisecondsSince(Clock::time_point start) { return std::chrono::duration<double, std::milli>(Clock::now() - start).count(); }

bool surfacePixel(const FrameReadback& normalLayer, std::size_t i) { return normalLayer.rgba[i * 4 + 3] != 0.0f; }
double roughnessAt(const FrameReadback& viewLayer, std::size_t i) { return double(viewLayer.rgba[i * 4 + 3]); }

// Of the resolved surface pixels, the ones the error view measures (isMeasuredPixel):
// covered wholly by the frame's surfaces too.
std::vector<std::uint8_t> resolvedPixels(const FrameReadback& frame, const FrameReadback& reference, const FrameReadback& normalLayer,
                                         const FrameReadback& viewLayer, double minRoughness)
{
    if (frame.rgba.size() != normalLayer.rgba.size() || reference.rgba.size() != normalLayer.rgba.size())
        throw std::invalid_argument("bench error measure: the frame, the reference and its layers differ in size");
    std::vector<std::uint8_t> include = resolvedSurfacePixels(normalLayer, viewLayer, minRoughness);
    for (std::size_t i = 0; i < include.size(); ++i) include[i] = include[i] && isMeasuredPixel(frame.rgba[i * 4 + 3], normalLayer.rgba[i * 4 + 3]);
    return include;
}

} // namespace

std::vector<std::uint8_t> resolvedSurfacePixels(const FrameReadback& normalLayer, const FrameReadback& viewLayer, double minRoughness)
{
    const std::size_t pixels = std::size_t(normalLayer.width) * std::size_t(normalLayer.height);
    if (normalLayer.rgba.size() != pixels * 4 || viewLayer.rgba.size() != pixels * 4)
        throw std::invalid_argument("bench error measure: the reference's layers differ in size");
    std::vector<std::uint8_t> include(pixels);
    for (std::size_t i = 0; i < pixels; ++i) include[i] = surfacePixel(normalLayer, i) && roughnessAt(viewLayer, i) >= minRoughness;
    return include;
}

double roughestSurface(const FrameReadback& normalLayer, const FrameReadback& viewLayer)
{
    double roughest = -1.0;
    const std::size_t pixels = std::min(normalLayer.rgba.size(), viewLayer.rgba.size()) / 4;
    for (std::size_t i = 0; i < pixels; ++i)
        if (surfacePixel(normalLayer, i)) roughest = std::max(roughest, roughnessAt(viewLayer, i));
    return roughest;
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

// ---- The harness ---------------------------------------------------------------------------

struct Harness::State {
    // A LUT between bakes, with the sample count it was baked with (its size is its own).
    struct HeldLut {
        bake::BakedTexture texture;
        int samples = 0;
    };

    Renderer& renderer;
    std::shared_ptr<const Environment> environment;
    std::unique_ptr<bake::BakeJob> bakeJob;
    // Handed to the renderer as const; changed here only before it gets it and after it let go.
    std::shared_ptr<bake::BakeResult> bake;
    std::array<HeldLut, 2> luts; // [int(GeometryTerm)]
    ReferenceFrame reference;

    explicit State(Renderer& r) : renderer(r) {}

    bool reusable(GeometryTerm term, const bake::LutSettings& lut) const
    {
        const HeldLut& held = luts[std::size_t(term)];
        return held.texture && held.texture.size == lut.size && held.samples == lut.samples;
    }
};

Harness::Harness(Renderer& renderer) : state_(std::make_unique<State>(renderer)) {}

// The renderer may be gone already (it often outlives the harness, but need not): the bake it
// may still hold is shared, so nothing is left dangling by not telling it.
Harness::~Harness() = default;

Renderer& Harness::renderer() { return state_->renderer; }

const Environment& Harness::loadEnvironment(const std::string& spec, std::shared_ptr<const Environment> loaded)
{
    State& s = *state_;
    retireBake();
    s.environment = loaded ? std::move(loaded) : std::make_shared<const Environment>(iblab::loadEnvironment(spec));
    s.renderer.setEnvironment(s.environment->image);
    s.reference = {};
    return *s.environment;
}

const Environment& Harness::environment() const
{
    if (!state_->environment) throw std::logic_error("lab::Harness: no environment loaded");
    return *state_->environment;
}

void Harness::startBake(bake::BakeSettings settings)
{
    State& s = *state_;
    retireBake();
    if (s.reusable(GeometryTerm::SchlickGGX, settings.lut)) settings.lut.schlickGgx = false;
    if (s.reusable(GeometryTerm::HeightCorrelatedSmith, settings.lut)) settings.lut.heightCorrelatedSmith = false;
    s.bakeJob = std::make_unique<bake::BakeJob>(s.renderer.shaders(), environment(), settings);
}

bool Harness::stepBake()
{
    State& s = *state_;
    if (!s.bakeJob) return false;
    if (s.bakeJob->step()) return true;
    s.bake = std::make_shared<bake::BakeResult>(s.bakeJob->takeResult());
    s.bakeJob.reset();
    for (std::size_t t = 0; t < s.luts.size(); ++t)
        if (s.reusable(GeometryTerm(t), s.bake->settings.lut)) s.bake->brdfLut[t] = std::move(s.luts[t].texture);
    s.renderer.setBake(s.bake);
    return false;
}

float Harness::bakeProgress() const { return state_->bakeJob ? state_->bakeJob->progress() : 0.0f; }

std::optional<bake::BakePhase> Harness::bakePhase() const { return state_->bakeJob ? state_->bakeJob->currentPhase() : std::nullopt; }

const bake::BakeResult& Harness::bake(const bake::BakeSettings& settings)
{
    startBake(settings);
    while (stepBake()) {
    }
    return currentBake();
}

const bake::BakeResult& Harness::currentBake() const
{
    if (!state_->bake) throw std::logic_error("lab::Harness: no bake");
    return *state_->bake;
}

void Harness::retireBake()
{
    State& s = *state_;
    s.bakeJob.reset();
    if (!s.bake) return;
    s.renderer.setBake(nullptr);
    // Only the harness holds it now: taking its LUTs back changes nothing anyone sees. (A bake
    // someone else kept keeps its LUTs, and the next bake makes its own.)
    if (s.bake.use_count() == 1)
        for (std::size_t t = 0; t < s.luts.size(); ++t)
            if (s.bake->brdfLut[t]) s.luts[t] = {std::move(s.bake->brdfLut[t]), s.bake->settings.lut.samples};
    s.bake.reset();
}

void Harness::release()
{
    retireBake();
    state_->luts = {};
    state_->environment.reset();
    state_->reference = {};
}

void Harness::render(const FrameSettings& settings, int width, int height) { state_->renderer.renderFrame(settings, width, height); }

double Harness::medianFrameMilliseconds(const FrameSettings& settings, int width, int height, int repeats)
{
    Renderer& renderer = state_->renderer;
    renderer.renderFrame(settings, width, height);
    glFinish();
    std::vector<double> frameMs;
    for (int i = 0; i < std::max(repeats, 1); ++i) {
        const auto start = Clock::now();
        renderer.renderFrame(settings, width, height);
        glFinish();
        frameMs.push_back(millisecondsSince(start));
    }
    std::sort(frameMs.begin(), frameMs.end());
    return frameMs[frameMs.size() / 2];
}

ReferenceStatus Harness::advanceReference(const FrameSettings& settings, int width, int height, std::chrono::steady_clock::duration budget)
{
    State& s = *state_;
    const auto start = Clock::now();
    const ReferenceStatus status = s.renderer.advanceReference(settings, width, height, budget);
    if (status.current && status.run != s.reference.run) s.reference = {.run = status.run};
    s.reference.milliseconds += millisecondsSince(start);
    if (status.complete && !s.reference.complete()) {
        s.reference.environmentWidth = status.environmentWidth;
        s.reference.minResolvedRoughness = status.minResolvedRoughness;
        s.reference.frame = s.renderer.readReferenceFrame();
        s.reference.normalLayer = s.renderer.readReferenceLayer(ReferenceLayer::Normal);
        s.reference.viewLayer = s.renderer.readReferenceLayer(ReferenceLayer::View);
    }
    return status;
}

const ReferenceFrame& Harness::reference() const { return state_->reference; }

FrameError Harness::compareWithReference(const FrameReadback& frame, const ToneMapSettings& toneMap) const
{
    const ReferenceFrame& r = state_->reference;
    if (!r.complete()) throw std::logic_error("lab::Harness: no complete reference to compare with");
    return {measureResolvedError(frame, r.frame, r.normalLayer, r.viewLayer, r.minResolvedRoughness),
            measureResolvedDisplayError(frame, r.frame, r.normalLayer, r.viewLayer, r.minResolvedRoughness, toneMap)};
}

} // namespace iblab::lab
