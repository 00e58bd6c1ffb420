#include "frame_scheduler.hpp"

#include <algorithm>
#include <cmath>

#include "frame/split_view.hpp"

namespace iblab::app {
namespace {

// Progressive refinement stops here: 64 rotated sample sets of any N are plenty to judge.
constexpr int kMaxAccumulatedFrames = 64;
// A preview whose cost is not known yet (another method, MSAA, scene) renders this share of
// the columns and rows: 1/64 of the pixels.
constexpr float kUnknownCostScale = 0.125f;
// A preview is a glimpse of the change; the full frame follows in slices.
constexpr float kSmallestPreviewScale = 0.0625f;

long long pixelsOf(const ViewContent& content) { return (long long)content.width * content.height; }

} // namespace

ViewScheduler::CostKey ViewScheduler::costKeyOf(const FrameSettings& settings)
{
    return {settings.sampling, settings.view.split ? settings.view.compare : SamplingSettings{}, settings.view.split, settings.view.mode,
            settings.view.msaaSamples, settings.scene};
}

std::optional<double> ViewScheduler::estimateMsPerPixel(const ViewContent& content) const
{
    if (!costKey_ || msPerPixel_ <= 0.0) return std::nullopt;
    const CostKey key = costKeyOf(content.settings);
    if (key == *costKey_) return msPerPixel_;
    // Only N changed (the + and - keys): the sampled method's cost follows N.
    CostKey sameN = key;
    sameN.a.samples = costKey_->a.samples;
    sameN.b.samples = costKey_->b.samples;
    if (!(sameN == *costKey_)) return std::nullopt;
    double ratio = 1.0;
    if (key.a.method == ShadingMethod::Sampled) ratio = std::max(ratio, double(key.a.samples) / double(std::max(costKey_->a.samples, 1)));
    if (key.split && key.b.method == ShadingMethod::Sampled)
        ratio = std::max(ratio, double(key.b.samples) / double(std::max(costKey_->b.samples, 1)));
    return msPerPixel_ * ratio;
}

float ViewScheduler::previewScale(const ViewContent& content) const
{
    const std::optional<double> perPixel = estimateMsPerPixel(content);
    if (!perPixel) return kUnknownCostScale;
    const double fullMs = *perPixel * double(pixelsOf(content));
    return std::clamp(float(std::sqrt(kBudgetMs / std::max(fullMs, 1e-3))), kSmallestPreviewScale, 1.0f);
}

void ViewScheduler::measured(const ViewContent& content, double ms, double pixels)
{
    if (pixels <= 0.0 || ms <= 0.0) return;
    msPerPixel_ = ms / pixels;
    costKey_ = costKeyOf(content.settings);
}

ViewWork ViewScheduler::plan(const Renderer& renderer, const ViewFrameInput& in) const
{
    if (in.hold) return ViewWork::None;
    const std::optional<double> perPixel = estimateMsPerPixel(in.content);
    const bool cheap = perPixel && *perPixel * double(pixelsOf(in.content)) <= kBudgetMs;
    if (!showsSettingsOf(in.content)) return cheap ? ViewWork::Full : ViewWork::Preview;
    // Holding a control still, or typing in a field, changes nothing in the view.
    if (in.interacting) return ViewWork::None;
    // A finished image needs no more frames: split-sum is deterministic, the sampled method
    // stops refining after kMaxAccumulatedFrames (or at once with a frozen sample set), the
    // error view waits for its reference, and the reference method shows each step of it.
    const int framesToConverge = renderer.lastFrameWasSampled() && !keepsExactSampleCount(in.content.settings) ? kMaxAccumulatedFrames : 1;
    const bool refine = shownScale_ < 1.0f || !(*shown_ == in.content) || renderer.sliceProgress() > 0.0f ||
                        renderer.accumulatedFrames() < framesToConverge;
    if (!refine) return ViewWork::None;
    return cheap ? ViewWork::Full : ViewWork::Slice;
}

ViewWork ViewScheduler::render(Renderer& renderer, const ViewFrameInput& in, Clock::time_point now)
{
    newImage_ = false;
    lastWorkMs_ = 0.0;
    pixels_ = pixelsOf(in.content);
    // Input first: while events wait, each frame handles them with the UI alone, and the
    // view renders the state they leave. A long stream still shows a preview now and then.
    if (in.inputPending && now - lastDrawn_ < kLongestHold) return ViewWork::None;
    const ViewWork work = plan(renderer, in);
    const FrameSettings& settings = in.content.settings;
    const auto start = Clock::now();
    if (work == ViewWork::Preview || work == ViewWork::Full) {
        Renderer::Options options;
        options.resolutionScale = work == ViewWork::Full ? 1.0f : previewScale(in.content);
        options.accumulate = work == ViewWork::Full && !in.interacting;
        timer_.begin();
        renderer.renderFrame(settings, in.content.width, in.content.height, options);
        timer_.end();
        if (const std::optional<double> ms = timer_.latestMilliseconds())
            measured(in.content, *ms, double(pixels_) * double(options.resolutionScale) * double(options.resolutionScale));
        shownScale_ = options.resolutionScale;
        newImage_ = true;
    } else if (work == ViewWork::Slice) {
        const auto budget = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double, std::milli>(kBudgetMs));
        const std::optional<double> perPixel = estimateMsPerPixel(in.content);
        const Renderer::Options options{1.0f, true, perPixel ? *perPixel * double(pixels_) : 0.0};
        if (renderer.renderFrameSlice(settings, in.content.width, in.content.height, options, budget)) {
            measured(in.content, renderer.lastSlicedFrameMs(), double(pixels_));
            shownScale_ = 1.0f;
            newImage_ = true;
        }
    }
    if (newImage_) {
        shown_ = in.content;
        lastDrawn_ = now;
    }
    lastWorkMs_ = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    return work;
}

} // namespace iblab::app
