#pragma once
// What the 3D view renders in a frame, so that input always wins over rendering: no frame
// of the GUI spends more than a budget on the view, whatever the shading method costs.
//   - A change (a drag, a typed value, a key step, a combo choice) first renders a preview
//     with fewer pixels, sized from the measured cost of a full frame to fit the budget.
//   - The full-resolution frame, and each refinement of the sampled method after it, is
//     then drawn in bands of rows over several GUI frames (Renderer::renderFrameSlice); the
//     preview stays on screen until the last band is in.
//   - While input events wait in the queue, the view renders nothing: each event then costs
//     a frame of UI only, and a burst of key steps renders its last state alone.
//   - Input that changes nothing in the view (typing in a field, a control held still)
//     renders nothing.
// Frames that are cheap at full resolution are drawn whole, as before, with no glFinish.
#include <chrono>
#include <cstdint>
#include <optional>

#include "frame/renderer.hpp"
#include "gl/pass_timer.hpp"

namespace iblab::app {

// What an image of the view is made from.
struct ViewContent {
    FrameSettings settings;
    int width = 0, height = 0;
    std::uint64_t contentRevision = 0;
    // The reference's part in it: the error view turns into its heat map once the reference
    // is complete, and a side drawn with the reference method shows each step of it.
    bool referenceComplete = false;
    float referenceMethodProgress = 0.0f;
    bool operator==(const ViewContent&) const = default;
};

struct ViewFrameInput {
    ViewContent content;
    bool interacting = false;  // a drag, a held control, the wheel: previews, no refinement
    bool inputPending = false; // events still queued after this frame's
    bool hold = false;         // an environment switch keeps the last image
};

enum class ViewWork { None, Preview, Full, Slice };

class ViewScheduler {
public:
    using Clock = std::chrono::steady_clock;
    // The most a GUI frame spends on the view's bands (and the aim of a preview).
    static constexpr double kBudgetMs = 30.0;
    // A stream of input longer than this still shows a preview now and then.
    static constexpr auto kLongestHold = std::chrono::milliseconds(1000);

    // Decides this frame's work on the view and does it.
    ViewWork render(Renderer& renderer, const ViewFrameInput& in, Clock::time_point now);
    // What render would do now if no input were pending: None means the view is final.
    ViewWork plan(const Renderer& renderer, const ViewFrameInput& in) const;

    // Whether the last render call put a new image on screen.
    bool newImage() const { return newImage_; }
    // The image on screen is of these settings (at whatever resolution).
    bool showsSettingsOf(const ViewContent& content) const { return shown_ && shown_->settings == content.settings && sameImage(*shown_, content); }
    // The image on screen is of this content at full resolution, with no band under way.
    bool showsFinal(const Renderer& renderer, const ViewContent& content) const
    {
        return shown_ && *shown_ == content && shownScale_ >= 1.0f && renderer.sliceProgress() == 0.0f;
    }
    float shownScale() const { return shownScale_; }
    // The time a full-resolution frame of the shown settings takes (measured, or a preview's
    // time scaled by its share of the pixels); 0 before the first frame.
    double fullFrameMs() const { return msPerPixel_ * double(pixels_); }
    double lastWorkMs() const { return lastWorkMs_; }

private:
    static bool sameImage(const ViewContent& a, const ViewContent& b)
    {
        return a.width == b.width && a.height == b.height && a.contentRevision == b.contentRevision;
    }
    // The settings that decide what a frame costs per pixel.
    struct CostKey {
        SamplingSettings a, b;
        bool split = false;
        ViewMode mode = ViewMode::Final;
        int msaa = 1;
        SceneSettings scene;
        bool operator==(const CostKey&) const = default;
    };
    static CostKey costKeyOf(const FrameSettings& settings);
    std::optional<double> estimateMsPerPixel(const ViewContent& content) const;
    float previewScale(const ViewContent& content) const;
    void measured(const ViewContent& content, double ms, double pixels);

    std::optional<ViewContent> shown_;
    float shownScale_ = 1.0f;
    Clock::time_point lastDrawn_{};
    gl::PassTimer timer_;
    double msPerPixel_ = 0.0; // of a full-resolution frame, for costKey_
    std::optional<CostKey> costKey_;
    long long pixels_ = 0;    // of the full-resolution view
    double lastWorkMs_ = 0.0;
    bool newImage_ = false;
};

} // namespace iblab::app
