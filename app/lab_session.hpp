#pragma once
// What the GUI and the headless commands share: which environment is loaded (and what
// loading it found), its bake, the loaded model, and writing screenshots with their
// settings. Environment files load on a worker thread and bakes run in slices, so the GUI
// stays responsive; the headless commands wait for both.
#include <chrono>
#include <deque>
#include <filesystem>
#include <future>
#include <memory>
#include <optional>
#include <string>

#include "bake/bake_cache.hpp"
#include "bake/bake_job.hpp"
#include "io/environment.hpp"
#include "ui/panels.hpp"
#include "frame/renderer.hpp"
#include "scene/material.hpp"

namespace iblab::app {

std::string defaultEnvironmentSpec();

class LabSession {
public:
    explicit LabSession(Renderer& renderer, bake::BakeSettings bakeSettings = bake::defaultPreset());
    ~LabSession();

    // Starts loading spec (a path or builtin:NAME) in the background, or queues it behind the
    // load that is running. Until it succeeds the current environment and bake stay; a
    // failure leaves them and reports one line.
    void requestEnvironment(const std::string& spec);
    // Blocking form for scripts: loads, uploads and bakes to completion. On success
    // settings.environment.source is updated.
    ui::StatusLine loadEnvironment(const std::string& spec, FrameSettings& settings);

    // What finished during one pump: the environment load and/or the bake.
    struct Finished {
        std::optional<ui::StatusLine> environment;
        std::optional<ui::StatusLine> bake;
    };
    // Advances background work for about `budget`: a finished load starts its bake; a
    // finished bake goes to the renderer.
    Finished pump(FrameSettings& settings, std::chrono::steady_clock::duration budget);
    // Shows a requested environment that is among the recent ones at once (pump calls it
    // first, so that the frame then drawn has the new lighting and the status line with it).
    Finished showRequestedRecent(FrameSettings& settings);
    bool busy() const;
    // Blocks until the environment file being decoded on the worker thread is ready, or for
    // `timeout`; returns at once when none is. Waiting here instead of polling leaves the
    // decode the CPU that drawing or pumping would take (two cores here).
    void waitForLoad(std::chrono::steady_clock::duration timeout) const;
    // An environment was asked for and its bake is not shown yet.
    bool switching() const;
    // "loading courtyard.exr", "baking: prefilter 40%", or "" when idle.
    std::string activity() const;
    float progress() const;

    // Bakes the loaded environment again with these settings (a convention preset's, say), in
    // slices like any bake; the current bake stays on screen until the new one is done. The
    // next environment loads with them too.
    void setBakeSettings(const bake::BakeSettings& settings);

    // The furnace view's bake of builtin:white (small and quick; made once, on first use).
    void ensureFurnaceBake();

    // Loads a .gltf/.glb for SceneKind::Model; on failure the current scene stays.
    ui::StatusLine loadModel(const std::string& path, FrameSettings& settings);
    // The loaded model's status line ("material_spheres.glb: 3 primitives, ..."), or "".
    const std::string& modelLine() const { return modelLine_; }

    // Writes a copy of the loaded glTF whose materials carry the material panel's factors.
    ui::StatusLine exportModel(const std::string& outPath, const FrameSettings& settings) const;

    // Writes the last rendered frame: .png = tone-mapped sRGB, .exr = linear HDR, both with
    // the settings embedded and in a .json sidecar.
    ui::StatusLine capture(const std::string& path, const FrameSettings& settings) const;

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
    // The GUI calls this after presenting a frame: it completes a switch whose bake is done.
    void frameDrawn();
    const std::optional<SwitchTiming>& lastSwitch() const { return lastSwitch_; }

    ui::EnvironmentCatalog catalog() const;
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
    ui::StatusLine showRecent(const RecentEnvironment& recent, FrameSettings& settings);

    ui::StatusLine finishLoad(Environment loaded, FrameSettings& settings);
    std::optional<ui::StatusLine> finishBake();
    // A file the cache has a record of (BakeCache::findSource): its bake is read from the
    // cache while the file decodes, and shown as soon as it is read; the decoded pixels then
    // only have to match the record's hash. Nothing starts for a file without a record.
    void startEarlyBake(const std::string& spec);
    void startDecode(); // of pendingSpec_, on the worker thread
    // Puts back the bake shown before an early bake that turned out not to belong.
    void withdrawEarlyBake();

    Renderer& renderer_;
    bake::BakeSettings bakeSettings_;
    bake::BakeCache cache_;
    std::shared_ptr<const Environment> environment_; // shared with recent_: switching copies no pixels
    std::shared_ptr<const bake::BakeResult> bake_;
    std::unique_ptr<bake::BakeJob> job_;
    std::vector<PbrMaterial> modelMaterials_; // of the loaded model, for export
    std::string modelLine_;                   // its status line, kept under a failed load's error
    std::string pendingSpec_;
    std::optional<std::string> queuedSpec_; // asked for while pendingLoad_ runs
    std::future<Environment> pendingLoad_;
    bool decodeDeferred_ = false; // pendingSpec_ decodes after its early bake's first frame
    std::string currentSpec_;                   // what environment_ was asked for as
    std::optional<std::string> recentRequested_; // a spec of recent_, shown at the next pump
    std::deque<RecentEnvironment> recent_;      // most recent first
    std::chrono::steady_clock::time_point switchRequested_;
    std::optional<SwitchTiming> switchInProgress_;
    bool switchAwaitsFrame_ = false;
    std::optional<SwitchTiming> lastSwitch_;
    struct EarlyBake {
        std::string spec;
        std::uint64_t contentHash = 0; // what the record says the file decodes to
        std::shared_ptr<const bake::BakeResult> previous; // shown until the early bake is
        bool jobRunning = true;  // job_ is the early job
        bool shown = false;      // its bake is bake_ (environment_ is still the previous one)
        bool decoded = false;    // the file decoded to contentHash: environment_ is its own
        std::string bakeStatus;  // shown with "; reading FILE" until the decode lands
    };
    std::optional<EarlyBake> early_;
    // The shown early bake's status line once its file has decoded (the next pump reports it).
    std::optional<ui::StatusLine> bakeStatusAfterDecode_;
};

} // namespace iblab::app
