#pragma once
// What the GUI and the headless commands share: which environment is loaded (and what
// loading it found) and its bake. Environment files load on a worker thread and bakes run in
// slices (EnvironmentSwitch keeps the phase of a switch), so the GUI stays responsive; the
// headless commands wait for both. The session reports what it shows; its caller's settings
// are the caller's to change (Finished::environmentShown).
#include <chrono>
#include <deque>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "bake/bake_cache.hpp"
#include "bake/bake_job.hpp"
#include "environment_switch.hpp"
#include "frame/renderer.hpp"
#include "io/environment.hpp"
#include "status_report.hpp"

namespace iblab::app {

std::string defaultEnvironmentSpec();

class LabSession {
public:
    using Clock = std::chrono::steady_clock;

    explicit LabSession(Renderer& renderer, bake::BakeSettings bakeSettings = bake::defaultPreset());

    // Starts loading spec (a path or builtin:NAME) in the background, or queues it behind the
    // load that is running. Until it succeeds the current environment and bake stay; a
    // failure leaves them and reports one line. One of the last few environments is shown by
    // the next pump, which reports it: the GUI pumps before it draws its panel, so the first
    // frame with the new lighting has the new status line beside it.
    void requestEnvironment(const std::string& spec);
    // Blocking form for the commands and tests: loads, uploads and bakes to completion.
    StatusReport loadEnvironment(const std::string& spec);

    // What happened since the last pump.
    struct Finished {
        std::optional<StatusReport> environment; // loaded (or kept from earlier), or failed
        std::optional<StatusReport> bake;
        // The environment now shown, as it was asked for: the caller's
        // settings.environment.source, which the session never writes itself.
        std::optional<std::string> environmentShown;
    };
    // Advances background work for about `budget`: a finished load starts its bake; a
    // finished bake goes to the renderer.
    Finished pump(Clock::duration budget);

    // The GUI's one call per frame.
    struct FrameUpdate {
        Clock::duration budget{};
        // When the previous frame was presented (none before the first): completes a switch
        // whose bake that frame showed.
        std::optional<Clock::time_point> presented;
        // The previous frame drew nothing new and no input waits: wait this long at most for
        // a decoding map before pumping. On two cores each drawn frame took CPU from the decode.
        Clock::duration waitForDecode{};
    };
    struct FrameReport {
        Finished finished;
        std::string activity; // activity() after the pump
        float progress = 0.0f;
    };
    FrameReport update(const FrameUpdate& frame);

    bool busy() const;
    // Blocks until the environment file being decoded on the worker thread is ready, or for
    // `timeout`; returns at once when none is, or a bake runs. Waiting here instead of polling
    // leaves the decode the CPU that drawing or pumping would take (two cores here).
    void waitForLoad(Clock::duration timeout) const;
    // The view keeps its last image: an environment was asked for and its bake is not shown
    // yet (and there is a last image, lit by the previous bake).
    bool holdsLastImage() const { return switch_.holdsLastImage() && bake_ != nullptr; }
    // A switch's bake is shown and the frame that showed it is not reported yet (update's
    // `presented`): its timing is not in lastSwitch() yet.
    bool awaitsFrame() const { return switch_.awaitsFrame(); }
    // "loading courtyard.exr", "baking: prefilter 40%", or "" when idle.
    std::string activity() const;
    float progress() const;

    // Bakes the loaded environment again with these settings (a convention preset's, say), in
    // slices like any bake; the current bake stays on screen until the new one is done. The
    // next environment loads with them too.
    void setBakeSettings(const bake::BakeSettings& settings);

    // The furnace view's bake of builtin:white (small and quick; made once, on first use).
    void ensureFurnaceBake();

    const std::optional<SwitchTiming>& lastSwitch() const { return switch_.lastSwitch(); }

    const Environment* environment() const { return environment_.get(); } // null before the first load
    const std::shared_ptr<const bake::BakeResult>& bake() const { return bake_; }
    const bake::BakeSettings& bakeSettings() const { return bakeSettings_; }

private:
    // The last few environments with their bakes: switching back to one shows it at once
    // (its textures stay on the GPU: ~8 MiB for the default preset, with 6 MiB of pixels).
    struct RecentEnvironment {
        std::string spec;
        std::optional<std::filesystem::file_time_type> modified; // a changed file loads again
        std::shared_ptr<const Environment> environment;
        std::shared_ptr<const bake::BakeResult> bake;
    };
    static constexpr std::size_t kRecentEnvironments = 4;
    static std::optional<std::filesystem::file_time_type> modificationTime(const std::string& spec);
    const RecentEnvironment* findRecent(const std::string& spec) const;
    void rememberCurrent();
    Finished showRecent(const RecentEnvironment& recent);

    // Shows spec from the recent ones, or starts its switch: an early bake when the cache has
    // a record of the file (BakeCache::findSource), else its decode.
    void startSwitch(const std::string& spec);
    void finishDecode(Finished& finished);
    StatusReport finishLoad(Environment loaded);
    std::optional<StatusReport> finishBake();
    // Puts back the bake shown before an early bake that turned out not to belong.
    void withdrawEarlyBake();

    Renderer& renderer_;
    bake::BakeSettings bakeSettings_;
    bake::BakeCache cache_;
    std::shared_ptr<const Environment> environment_; // shared with recent_: switching copies no pixels
    std::shared_ptr<const bake::BakeResult> bake_;
    std::unique_ptr<bake::BakeJob> job_; // the switch's bake (early or of the decoded map), or a re-bake
    std::string currentSpec_;            // what environment_ was asked for as
    std::deque<RecentEnvironment> recent_; // most recent first
    EnvironmentSwitch switch_;           // declared after job_ etc.: destroyed first, it waits for its decode
};

} // namespace iblab::app
