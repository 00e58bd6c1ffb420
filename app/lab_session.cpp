#include "lab_session.hpp"

#include <cstdio>
#include <filesystem>
#include <utility>

#include "asset_paths.hpp"
#include "io/builtin_environments.hpp"
#include "io/error.hpp"
#include "io/imported_bake.hpp"

namespace iblab::app {

using Phase = EnvironmentSwitch::Phase;

namespace {

// "courtyard.exr: 2048x1024"; an imported bake says what it is (its image is only its sky).
std::string environmentLine(const Environment& env)
{
    const std::string size = std::to_string(env.image.width) + "x" + std::to_string(env.image.height);
    if (env.imported) return displayName(env.source) + ": imported " + importedBakeFormat(env.imported->kind) + ", shown as made (sky " + size + ")";
    return displayName(env.source) + ": " + size;
}

// A bake's notes (floats for a map brighter than a half float, cache repairs) after its
// status line, each after "; ": the same on the line of a bake kept from earlier.
std::string bakeNotes(const bake::BakeResult& result)
{
    std::string text;
    for (const std::string& note : result.notes)
        text += "; " + note;
    return text;
}

} // namespace

std::string defaultEnvironmentSpec() { return defaultEnvironmentPath(assetDirectory().string()); }

LabSession::LabSession(Renderer& renderer, bake::BakeSettings bakeSettings) : renderer_(renderer), bakeSettings_(std::move(bakeSettings)) {}

void LabSession::requestEnvironment(const std::string& spec)
{
    // The map already on its way, asked for again (Enter in the path field, then the Load
    // button): one load and one bake, timed from the first request.
    const bool decoding = switch_.loading() && spec == switch_.spec();
    const Phase phase = switch_.phase();
    const bool baking = job_ && spec == currentSpec_ && (phase == Phase::Baking || phase == Phase::Idle || phase == Phase::AwaitingFrame);
    if ((decoding || baking) && !switch_.hasQueued()) return;
    switch_.timeFrom(spec);
    // One load at a time, and the UI thread never waits for one: a request made while a
    // load runs is queued, and the newest queued request replaces older ones.
    if (switch_.decodeRunning()) {
        switch_.queue(spec);
        return;
    }
    startSwitch(spec);
}

void LabSession::startSwitch(const std::string& spec)
{
    // A recent map is shown by the next pump (EnvironmentSwitch::showRecentNext says why).
    switch_.dropRecentNext();
    if (findRecent(spec)) {
        switch_.showRecentNext(spec);
        return;
    }
    withdrawEarlyBake();
    switch_.begin(spec);
    const std::optional<bake::BakeCache::SourceRecord> record = cache_.enabled() ? cache_.findSource(spec) : std::nullopt;
    if (!record) {
        switch_.startDecode();
        return;
    }
    // With an early bake the decode waits for its first frame (pump starts it): the two
    // cores then read the cache and draw that frame undisturbed, and OpenEXR's one thread
    // pool is not shared between the map and the cache's files.
    job_ = std::make_unique<bake::BakeJob>(renderer_.shaders(), spec, *record, bakeSettings_, cache_);
    switch_.beginEarlyBake(record->contentHash, bake_);
}

void LabSession::withdrawEarlyBake()
{
    if (switch_.phase() == Phase::EarlyBake) job_.reset();
    if (switch_.phase() == Phase::EarlyBakeShown) {
        bake_ = switch_.bakeBeforeEarly();
        renderer_.setBake(bake_);
    }
    switch_.earlyBakeDropped();
}

StatusReport LabSession::finishLoad(Environment loaded)
{
    renderer_.setEnvironment(loaded.image);
    const std::string spec = switch_.spec().empty() ? loaded.source : switch_.spec();
    cache_.rememberSource(spec, {loaded.contentHash, loaded.image.width, loaded.image.height});
    const std::string text = environmentLine(loaded);
    // Repairs, downsampling and LDR input are the loader's warnings: notes under the line,
    // since the environment loaded and is usable (the bundled courtyard has negative texels
    // from its stitching, repaired to 0, which is nobody's error).
    std::vector<std::string> notes = loaded.warnings;
    currentSpec_ = spec;
    if (switch_.phase() == Phase::EarlyBakeShown && switch_.earlyContentHash() == loaded.contentHash) {
        // The early bake shown is this map's: the decoded pixels only join it.
        environment_ = std::make_shared<const Environment>(std::move(loaded));
        rememberCurrent();
        switch_.earlyBakeConfirmed();
        return {text, false, std::move(notes)};
    }
    // Not what the record said (the file was rewritten in place): bake what was decoded.
    withdrawEarlyBake();
    job_ = std::make_unique<bake::BakeJob>(renderer_.shaders(), loaded, bakeSettings_, &cache_);
    environment_ = std::make_shared<const Environment>(std::move(loaded));
    switch_.baking();
    return {text, false, std::move(notes)};
}

std::optional<StatusReport> LabSession::finishBake()
{
    const bool early = switch_.phase() == Phase::EarlyBake;
    if (early && job_->missedCache()) {
        // The record outlived its bake: the file decodes (at the next pump) and bakes.
        job_.reset();
        switch_.earlyBakeDropped();
        return std::nullopt;
    }
    auto result = std::make_shared<bake::BakeResult>(job_->takeResult());
    job_.reset();
    char gpuMemory[48];
    std::snprintf(gpuMemory, sizeof gpuMemory, ", %.1f MiB of GPU memory", double(result->gpuBytes()) / (1024.0 * 1024.0));
    std::string text = "baked in " + std::to_string(int(result->totalMilliseconds + 0.5)) + " ms" + (result->fromCache ? " (from cache)" : "") + gpuMemory;
    if (result->sourceUpsample > 1)
        text += "; from its " + std::to_string(result->sourceWidth * result->sourceUpsample) + "x" +
                std::to_string(result->sourceHeight * result->sourceUpsample) + " bilinear upsample, as fine as mip 1 needs";
    text += bakeNotes(*result);
    bake_ = result;
    renderer_.setBake(bake_);
    if (early) {
        switch_.earlyBakeShown(text, result->fromCache);
        return StatusReport{text + "; reading " + displayName(switch_.spec()), false};
    }
    rememberCurrent();
    // Else a re-bake of the shown map, or the bake of the map left by a switch that decodes.
    if (switch_.phase() == Phase::Baking) switch_.bakeShown(result->fromCache);
    return StatusReport{text, false};
}

std::optional<std::filesystem::file_time_type> LabSession::modificationTime(const std::string& spec)
{
    if (isBuiltinSpec(spec)) return std::nullopt;
    std::error_code ec;
    const auto time = std::filesystem::last_write_time(spec, ec);
    if (ec) return std::nullopt;
    return time;
}

const LabSession::RecentEnvironment* LabSession::findRecent(const std::string& spec) const
{
    for (const RecentEnvironment& recent : recent_)
        if (recent.spec == spec && recent.bake->settings == bakeSettings_ && recent.modified == modificationTime(spec)) return &recent;
    return nullptr;
}

void LabSession::rememberCurrent()
{
    if (!environment_ || !bake_ || currentSpec_.empty()) return;
    std::erase_if(recent_, [&](const RecentEnvironment& recent) { return recent.spec == currentSpec_; });
    recent_.push_front({currentSpec_, modificationTime(currentSpec_), environment_, bake_});
    if (recent_.size() > kRecentEnvironments) recent_.pop_back();
}

LabSession::Finished LabSession::showRecent(const RecentEnvironment& recent)
{
    // A bake of the environment being left (or an early bake of one asked for before) stops.
    job_.reset();
    switch_.begin(recent.spec);
    renderer_.setEnvironment(recent.environment->image);
    renderer_.setBake(recent.bake);
    environment_ = recent.environment;
    bake_ = recent.bake;
    currentSpec_ = recent.spec;
    switch_.recentShown();
    const Environment& env = *recent.environment;
    Finished shown;
    shown.environment = StatusReport{environmentLine(env) + ", kept from earlier with its bake", false, env.warnings};
    shown.bake = StatusReport{"kept from earlier (baked in " + std::to_string(int(recent.bake->totalMilliseconds + 0.5)) + " ms" +
                                  (recent.bake->fromCache ? ", from cache)" : ")") + bakeNotes(*recent.bake),
                              false};
    shown.environmentShown = recent.spec;
    rememberCurrent();
    return shown;
}

void LabSession::finishDecode(Finished& finished)
{
    if (const std::optional<std::string> queued = switch_.takeQueued()) {
        // The user has asked for another environment since: this result is stale.
        switch_.dropDecode();
        startSwitch(*queued);
        return;
    }
    try {
        finished.environment = finishLoad(switch_.takeDecoded());
        finished.environmentShown = currentSpec_;
        // A confirmed early bake's line, without "; reading FILE" now.
        if (switch_.phase() != Phase::Baking && !switch_.earlyBakeStatus().empty())
            finished.bake = StatusReport{switch_.earlyBakeStatus(), false};
    } catch (const Error& e) {
        withdrawEarlyBake();
        switch_.failed();
        finished.environment = StatusReport{e.what(), true};
    }
}

LabSession::Finished LabSession::pump(Clock::duration budget)
{
    // A recent environment asked for since the last pump: shown now, before the GUI draws the
    // panel that reports it; its lines, and nothing else this pump.
    if (const std::optional<std::string> spec = switch_.takeRecentNext()) {
        if (const RecentEnvironment* recent = findRecent(*spec)) return showRecent(RecentEnvironment(*recent)); // showRecent reorders recent_: a copy
        startSwitch(*spec); // no longer among the recent ones: loaded as any other
    }
    // The early bake was shown in an earlier pump (or is gone): its frame has been drawn.
    if (switch_.decodeWaits()) switch_.startDecode();
    Finished finished;
    if (switch_.decodeReady()) {
        finishDecode(finished);
        if (finished.environment && finished.environment->isError) return finished;
        // The bake starts in the same pump: from the cache it is often done in it.
    }
    if (job_) {
        try {
            if (!job_->runFor(budget)) finished.bake = finishBake();
            // The view shows the early bake from now on: the line names its map, not the last.
            if (switch_.phase() == Phase::EarlyBakeShown)
                finished.environment = StatusReport{displayName(switch_.spec()) + ": shown from the bake cache while the file is read"};
        } catch (const std::exception& e) {
            withdrawEarlyBake();
            job_.reset();
            switch_.bakeFailed();
            finished.bake = StatusReport{std::string("bake failed: ") + e.what(), true};
        }
    }
    return finished;
}

LabSession::FrameReport LabSession::update(const FrameUpdate& frame)
{
    if (frame.presented) switch_.frameDrawn(*frame.presented);
    if (frame.waitForDecode > Clock::duration::zero()) waitForLoad(frame.waitForDecode);
    FrameReport report;
    report.finished = pump(frame.budget);
    report.activity = activity();
    report.progress = progress();
    return report;
}

void LabSession::waitForLoad(Clock::duration timeout) const
{
    if (!job_) switch_.waitForDecode(timeout);
}

bool LabSession::busy() const { return switch_.busy() || job_ != nullptr; }

std::string LabSession::activity() const
{
    if (switch_.loading() || switch_.hasQueued()) return "loading " + displayName(switch_.shownAsLoading());
    if (job_) {
        const std::optional<bake::BakePhase> phase = job_->currentPhase();
        return "baking: " + std::string(phase ? enumName(*phase) : "done");
    }
    return {};
}

float LabSession::progress() const { return job_ ? job_->progress() : 0.0f; }

StatusReport LabSession::loadEnvironment(const std::string& spec)
{
    requestEnvironment(spec);
    StatusReport status;
    while (busy()) {
        waitForLoad(std::chrono::hours(1));
        const Finished finished = pump(std::chrono::hours(1));
        for (const auto& line : {finished.environment, finished.bake}) {
            if (!line) continue;
            if (line->isError) return *line;
            status.text += (status.text.empty() ? "" : "; ") + line->text;
            status.notes.insert(status.notes.end(), line->notes.begin(), line->notes.end());
        }
    }
    return status;
}

void LabSession::setBakeSettings(const bake::BakeSettings& settings)
{
    withdrawEarlyBake(); // read with the old settings; the decode bakes with the new ones
    bakeSettings_ = settings;
    // The furnace bake reads the LUT of the session's settings: make it again on next use.
    renderer_.setFurnaceBake(nullptr);
    if (environment_) job_ = std::make_unique<bake::BakeJob>(renderer_.shaders(), *environment_, bakeSettings_, &cache_);
}

void LabSession::ensureFurnaceBake()
{
    if (renderer_.hasFurnaceBake()) return;
    // A uniform environment needs no resolution: 64x32 keeps the bake to milliseconds,
    // while the LUT (which decides the furnace's answer) keeps the session's settings.
    const Environment white = iblab::loadEnvironment("builtin:white?width=64");
    bake::BakeJob job(renderer_.shaders(), white, bakeSettings_, &cache_);
    renderer_.setFurnaceBake(std::make_shared<bake::BakeResult>(job.runToCompletion()));
}

} // namespace iblab::app
