#pragma once
// One environment switch, from the request to the first frame drawn with the new map's
// bake: its phase, the map asked for (and the one asked for meanwhile, which replaces it),
// the decode on the worker thread, a bake read early from the cache, and how long the user
// waited. LabSession does what each phase names (decode, bake, show); this type keeps the
// phase, so that "hold the last image?", "is it loading?" and the timing have one answer.
#include <chrono>
#include <cstdint>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "bake/bake_result.hpp"
#include "io/environment.hpp"

namespace iblab::app {

// What a user waits for when switching environments: from the request to the first frame
// drawn with the new lighting. Each time is since the request.
struct SwitchTiming {
    std::string environment;
    double loadMs = 0.0;       // the file decoded (on the worker thread); with a bake read early
                               // from the cache's record of the file, after the first frame
    double bakeMs = 0.0;       // the bake (or its cache lookup) handed to the renderer
    double firstFrameMs = 0.0; // the first frame with that bake drawn and presented
    bool fromCache = false;
};

class EnvironmentSwitch {
public:
    using Clock = std::chrono::steady_clock;

    enum class Phase {
        Idle,           // no switch under way (a re-bake of the shown map may run: not a switch)
        Decoding,       // the file decodes on the worker thread, or starts to at the next pump
        EarlyBake,      // a bake read from the cache's record of the file runs; the decode waits
        EarlyBakeShown, // that bake is shown over the previous map's pixels; the file decodes
                        // (from the pump after the bake's first frame) to confirm the record
        Baking,         // the decoded map's bake runs
        AwaitingFrame,  // its bake is shown; the first frame with it is not drawn yet
    };

    ~EnvironmentSwitch();

    Phase phase() const { return phase_; }
    // The map of the switch under way (or of the last one).
    const std::string& spec() const { return spec_; }
    // While the new map loads and bakes, the view keeps its last image (the previous map, lit
    // by its own bake) rather than drawing the new sky with the old lighting. Not once the
    // switch's timing is dropped (a failed bake): the map that stays is drawn again.
    bool holdsLastImage() const
    {
        return timing_ && (phase_ == Phase::Decoding || phase_ == Phase::EarlyBake || phase_ == Phase::Baking);
    }
    // The file is on its way (decoding, or waiting for an early bake to decode after).
    bool loading() const { return phase_ == Phase::Decoding || phase_ == Phase::EarlyBake || phase_ == Phase::EarlyBakeShown; }
    bool busy() const { return loading() || phase_ == Phase::Baking || queued_.has_value() || recentNext_.has_value(); }
    // The switch's bake is shown and its first frame is not reported yet.
    bool awaitsFrame() const { return timing_ && (phase_ == Phase::AwaitingFrame || (phase_ == Phase::EarlyBakeShown && !earlyFrameDrawn_)); }
    // The map the activity line names: the newest request.
    const std::string& shownAsLoading() const { return queued_ ? *queued_ : spec_; }

    // --- the request ---
    // The user waits from their latest request, queued or not: the timing starts again.
    void timeFrom(const std::string& spec)
    {
        requested_ = Clock::now();
        timing_ = SwitchTiming{.environment = spec};
    }
    // Another map asked for while one decodes: it replaces any queued before it.
    void queue(const std::string& spec) { queued_ = spec; }
    std::optional<std::string> takeQueued() { return std::exchange(queued_, std::nullopt); }
    bool hasQueued() const { return queued_.has_value(); }
    // A switch to spec starts (after withdrawEarlyBake of any before it): it decodes.
    void begin(const std::string& spec);

    // --- a recent map (one LabSession kept with its bake) ---
    // Asked for: the next pump shows it, before the GUI draws the panel that reports it (shown
    // at once, its first image went out beside the old map's status line). A payload beside
    // the phase, not a phase: until that pump the phase stays what it was, as the view still
    // shows it, and a map that is no longer recent by then switches from it (withdrawing an
    // early bake, say). A later request replaces it.
    void showRecentNext(const std::string& spec) { recentNext_ = spec; }
    void dropRecentNext() { recentNext_.reset(); }
    std::optional<std::string> takeRecentNext();

    // --- the decode ---
    // The file waits for its early bake's first frame, or a decode already runs.
    bool decodeWaits() const { return (phase_ == Phase::Decoding || phase_ == Phase::EarlyBakeShown) && !decode_.valid(); }
    bool decodeRunning() const { return decode_.valid(); }
    bool decodeReady() const { return decode_.valid() && decode_.wait_for(std::chrono::seconds(0)) == std::future_status::ready; }
    void startDecode();
    void waitForDecode(Clock::duration timeout) const
    {
        if (decode_.valid()) decode_.wait_for(timeout);
    }
    // The decoded map (rethrows the loader's error); records the load time.
    Environment takeDecoded();
    // The decode's result is stale (another map was asked for since): it is dropped.
    void dropDecode() { decode_ = {}; }

    // --- an early bake (BakeCache::findSource) ---
    // Its job runs; what it was read for and the bake shown until it is.
    void beginEarlyBake(std::uint64_t contentHash, std::shared_ptr<const bake::BakeResult> previous);
    std::uint64_t earlyContentHash() const { return earlyContentHash_; }
    const std::shared_ptr<const bake::BakeResult>& bakeBeforeEarly() const { return previous_; }
    // Its bake is shown; its status line, shown with "; reading FILE" until the decode lands.
    void earlyBakeShown(const std::string& bakeStatus, bool fromCache);
    const std::string& earlyBakeStatus() const { return earlyBakeStatus_; }
    // The cache had no bake for the record, or the early bake was withdrawn: the file
    // decodes (at the next pump) and bakes as any.
    void earlyBakeDropped();

    // --- the end ---
    void baking() { phase_ = Phase::Baking; }
    // The switch's bake is shown (its own, a kept recent one, or a confirmed early one).
    void bakeShown(bool fromCache);
    void recentShown();
    void earlyBakeConfirmed() { phase_ = awaitsFrame() ? Phase::AwaitingFrame : Phase::Idle; }
    // The decode or the bake failed: what was shown stays, and the switch is over (a bake that
    // failed while the file still decodes lets the decode go on, as its own bake may work).
    void failed();
    void bakeFailed();
    // A frame was presented at `presented`: completes a switch whose bake it showed.
    void frameDrawn(Clock::time_point presented);
    const std::optional<SwitchTiming>& lastSwitch() const { return last_; }

private:
    double msSinceRequest(Clock::time_point now = Clock::now()) const;

    Phase phase_ = Phase::Idle;
    std::string spec_;
    std::optional<std::string> queued_;
    std::optional<std::string> recentNext_; // a recent map the next pump shows
    std::future<Environment> decode_;
    std::uint64_t earlyContentHash_ = 0;                // what the record says the file decodes to
    std::shared_ptr<const bake::BakeResult> previous_;  // the bake shown before the early one
    std::string earlyBakeStatus_;
    bool earlyFrameDrawn_ = false;
    Clock::time_point requested_;
    std::optional<SwitchTiming> timing_; // of the switch under way, until its first frame
    std::optional<SwitchTiming> last_;
};

} // namespace iblab::app
