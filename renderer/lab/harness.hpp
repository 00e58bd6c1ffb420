#pragma once
// The harness every study of the lab runs on (the bench sweep, auto quality, the stress
// suite): an environment shown by a renderer, bakes of it that share the BRDF LUTs, frames
// rendered, timed and read back, and the reference renderer's frame to compare them with.
//
//   lab::Harness harness(renderer);
//   harness.loadEnvironment("builtin:sky");
//   const bake::BakeResult& baked = harness.bake(settings);  // or startBake + stepBake slices
//   harness.render(frame, width, height);                     // then renderer().readHdrFrame()
//   while (!harness.advanceReference(frame, width, height, budget).complete) {}
//   FrameError error = harness.compareWithReference(renderer().readHdrFrame(), frame.toneMap);
//   harness.retireBake();                                     // its LUTs wait for the next bake
//
// The LUT rule: a LUT depends on no environment, only on its geometry term, size and sample
// count, so a bake reuses every LUT the harness holds whose size and sample count are the
// ones its settings ask for, bakes the terms it asks for and lacks, and hands what it has on
// to the next bake when it is retired. The bakes never change while the renderer shows them:
// the LUTs are put in before the renderer gets the bake and taken back after it let go.
//
// Needs the context that was current when the renderer was made to be current at every call.
// Public header: no GL.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bake/bake_result.hpp"
#include "bake/bake_settings.hpp"
#include "frame/renderer.hpp"
#include "frame/settings.hpp"
#include "ibl/error_metrics.hpp"
#include "io/environment.hpp"

namespace iblab::lab {

// The error as the eye is shown it: both frames through the view's exposure, tone mapping and
// sRGB encoding (displayEncode, as ErrorSpace::Display), per pixel the largest channel
// difference in 8-bit steps (1 step = 1/255).
struct DisplayError {
    std::size_t pixels = 0;
    double p99Steps = 0.0; // nearest rank, as ErrorMetrics::p99Relative
    double rmsSteps = 0.0;
    double maxSteps = 0.0;
};

// A frame against the reference, over the same pixels both ways. NaN errors (and 0 pixels)
// where the reference resolves no surface pixel of the frame: not 0, which would read as exact.
struct FrameError {
    ErrorMetrics linear;  // linear HDR (measureResolvedError)
    DisplayError display; // after tone mapping (measureResolvedDisplayError)
};

// The reference renderer's frame of a scene, read back with the G-buffer layers that say
// which of its pixels are surfaces (the normal layer's alpha) and how rough (the view layer's).
struct ReferenceFrame {
    FrameReadback frame = {}, normalLayer = {}, viewLayer = {};
    int environmentWidth = 0;          // of the map it summed over
    double minResolvedRoughness = 0.0; // referenceMinResolvedRoughness of that width
    double milliseconds = 0.0;         // spent in its slices (read-backs not included)
    unsigned long long run = 0;        // the renderer's ReferenceStatus::run it was read from
    bool complete() const { return !frame.rgba.empty(); }
};

// The per-pixel relative error of `frame` against `reference` over the surface pixels (the
// G-buffer's normal layer has coverage in alpha) whose perceptual roughness (the view
// layer's alpha) is at least minRoughness: below it the reference's midpoint rule is not
// converged, and its error would swamp the estimators' (referenceMinResolvedRoughness).
// Of those, only the pixels the frame's surfaces cover wholly (isMeasuredPixel), so that an
// MSAA silhouette pixel, part sky, is left out. With no such pixel, every error field is NaN
// and `pixels` 0.
ErrorMetrics measureResolvedError(const FrameReadback& frame, const FrameReadback& reference, const FrameReadback& normalLayer,
                                  const FrameReadback& viewLayer, double minRoughness);
// The same pixels compared after `toneMap` in 8-bit steps (NaN steps when there are none).
DisplayError measureResolvedDisplayError(const FrameReadback& frame, const FrameReadback& reference, const FrameReadback& normalLayer,
                                         const FrameReadback& viewLayer, double minRoughness, const ToneMapSettings& toneMap);
// The surface pixels of the reference's layers with roughness at least minRoughness (1 or 0
// per pixel), whatever a frame covers: where a frame can be measured at all.
std::vector<std::uint8_t> resolvedSurfacePixels(const FrameReadback& normalLayer, const FrameReadback& viewLayer, double minRoughness);
// The largest roughness of a surface pixel in the reference's layers; -1 when none is a surface.
double roughestSurface(const FrameReadback& normalLayer, const FrameReadback& viewLayer);

class Harness {
public:
    explicit Harness(Renderer& renderer);
    ~Harness();
    Harness(const Harness&) = delete;
    Harness& operator=(const Harness&) = delete;

    Renderer& renderer();

    // Shows `spec` (loaded now unless `loaded` is given: a map already in memory) on the
    // renderer for the bakes and frames that follow; retires the bake and forgets the
    // reference of the previous one. Throws iblab::Error for a spec that does not load.
    const Environment& loadEnvironment(const std::string& spec, std::shared_ptr<const Environment> loaded = nullptr);
    const Environment& environment() const;

    // A bake of the environment in steps (the GUI runs a slice per frame): the held LUTs
    // reused, the rest baked. The last step hands the result to the renderer.
    void startBake(bake::BakeSettings settings);
    bool stepBake(); // true while steps remain
    float bakeProgress() const;    // of the bake under way, 0..1 (0 when none is)
    std::optional<bake::BakePhase> bakePhase() const; // the phase its next step runs (nullopt when none is)
    // startBake and every step; the result, which the renderer shows.
    const bake::BakeResult& bake(const bake::BakeSettings& settings);
    // The bake the renderer shows; throws std::logic_error when there is none.
    const bake::BakeResult& currentBake() const;
    // The renderer lets go of the bake; its LUTs are held for the next one.
    void retireBake();
    // Drops the environment, the bake and the held LUTs (their GL memory), when a study is done.
    void release();

    // Renders one frame (read it back with renderer().readHdrFrame() / readDisplayImage()).
    void render(const FrameSettings& settings, int width, int height);
    // Renders one frame untimed (it compiles the settings' shader permutation, which is not
    // their cost), then `repeats` frames, each timed with a steady clock around glFinish
    // (llvmpipe's timer queries are wrong at these sizes); their median in milliseconds.
    // The last frame stays in the renderer.
    double medianFrameMilliseconds(const FrameSettings& settings, int width, int height, int repeats);

    // Runs the reference renderer on the frame of these settings for about `budget`; once it
    // completes, it is read back into reference(). Settings the reference depends on (the
    // BRDF's geometry term and energy compensation, the scene, the size) start another one,
    // which replaces it, as does the next environment.
    ReferenceStatus advanceReference(const FrameSettings& settings, int width, int height, std::chrono::steady_clock::duration budget);
    const ReferenceFrame& reference() const;
    // `frame` against the reference over the pixels it resolves (minResolvedRoughness).
    FrameError compareWithReference(const FrameReadback& frame, const ToneMapSettings& toneMap) const;

private:
    struct State;
    std::unique_ptr<State> state_;
};

} // namespace iblab::lab
