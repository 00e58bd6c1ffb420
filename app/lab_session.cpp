#include "lab_session.hpp"

#include <cstdio>
#include <filesystem>
#include <utility>

#include "asset_paths.hpp"
#include "command_support.hpp"
#include "preset_json.hpp"
#include "io/builtin_environments.hpp"
#include "io/error.hpp"
#include "io/image_writer.hpp"
#include "scene/gltf_model.hpp"

namespace iblab::app {
namespace {

std::string shortName(const std::string& spec)
{
    return isBuiltinSpec(spec) ? spec : std::filesystem::path(spec).filename().string();
}

// "courtyard.exr: 2048x1024"; an imported bake says what it is (its image is only its sky).
std::string environmentLine(const Environment& env)
{
    const std::string size = std::to_string(env.image.width) + "x" + std::to_string(env.image.height);
    if (env.imported) return shortName(env.source) + ": imported " + importedBakeFormat(env.imported->kind) + ", shown as made (sky " + size + ")";
    return shortName(env.source) + ": " + size;
}

} // namespace

std::string defaultEnvironmentSpec() { return defaultEnvironmentPath(assetDirectory().string()); }

LabSession::LabSession(Renderer& renderer, bake::BakeSettings bakeSettings) : renderer_(renderer), bakeSettings_(std::move(bakeSettings)) {}

LabSession::~LabSession()
{
    if (pendingLoad_.valid()) pendingLoad_.wait(); // the worker only reads files; let it finish
}

void LabSession::requestEnvironment(const std::string& spec)
{
    // The map already on its way, asked for again (Enter in the path field, then the Load
    // button): one load and one bake, timed from the first request.
    const bool decoding = (pendingLoad_.valid() || decodeDeferred_) && spec == pendingSpec_;
    const bool baking = job_ && !pendingLoad_.valid() && spec == currentSpec_;
    if ((decoding || baking) && !queuedSpec_) return;
    // The user waits from their latest request, queued or not.
    switchRequested_ = std::chrono::steady_clock::now();
    switchInProgress_ = SwitchTiming{.environment = spec};
    switchAwaitsFrame_ = false;
    if (!pendingLoad_.valid() && findRecent(spec)) {
        recentRequested_ = spec;
        return;
    }
    recentRequested_.reset();
    // One load at a time, and the UI thread never waits for one: a request made while a
    // load runs is queued, and the newest queued request replaces older ones.
    if (pendingLoad_.valid()) {
        queuedSpec_ = spec;
        return;
    }
    pendingSpec_ = spec;
    startEarlyBake(spec);
    // With an early bake the decode waits for its first frame (pump starts it): the two
    // cores then read the cache and draw that frame undisturbed, and OpenEXR's one thread
    // pool is not shared between the map and the cache's files.
    decodeDeferred_ = early_.has_value();
    if (!decodeDeferred_) startDecode();
}

void LabSession::startDecode()
{
    decodeDeferred_ = false;
    pendingLoad_ = std::async(std::launch::async, [spec = pendingSpec_] { return iblab::loadEnvironment(spec); });
}

void LabSession::startEarlyBake(const std::string& spec)
{
    if (early_) withdrawEarlyBake();
    if (!cache_.enabled()) return;
    const std::optional<bake::BakeCache::SourceRecord> record = cache_.findSource(spec);
    if (!record) return;
    job_ = std::make_unique<bake::BakeJob>(renderer_.shaders(), spec, *record, bakeSettings_, cache_);
    early_ = EarlyBake{.spec = spec, .contentHash = record->contentHash, .previous = bake_};
}

void LabSession::withdrawEarlyBake()
{
    if (!early_) return;
    if (early_->jobRunning) job_.reset();
    if (early_->shown && !early_->decoded) {
        bake_ = early_->previous;
        renderer_.setBake(bake_);
    }
    early_.reset();
}

ui::StatusLine LabSession::finishLoad(Environment loaded, FrameSettings& settings)
{
    renderer_.setEnvironment(loaded.image);
    const double loadMs = millisecondsSince(switchRequested_);
    if (switchInProgress_) switchInProgress_->loadMs = loadMs;
    else if (lastSwitch_ && lastSwitch_->environment == pendingSpec_ && lastSwitch_->loadMs == 0.0) lastSwitch_->loadMs = loadMs; // shown early
    cache_.rememberSource(pendingSpec_.empty() ? loaded.source : pendingSpec_,
                          {loaded.contentHash, loaded.image.width, loaded.image.height});
    const std::string text = environmentLine(loaded);
    // Repairs, downsampling and LDR input are the loader's warnings: notes under the line,
    // since the environment loaded and is usable (the bundled courtyard has negative texels
    // from its stitching, repaired to 0, which is nobody's error).
    std::vector<std::string> notes = loaded.warnings;
    settings.environment.source = pendingSpec_.empty() ? loaded.source : pendingSpec_;
    currentSpec_ = settings.environment.source;
    if (early_ && early_->spec == currentSpec_ && early_->contentHash == loaded.contentHash) {
        // The early bake is this map's: it is shown, or its job is still reading the cache.
        early_->decoded = true;
        environment_ = std::make_shared<const Environment>(std::move(loaded));
        if (early_->shown) {
            bakeStatusAfterDecode_ = ui::StatusLine{early_->bakeStatus, false};
            rememberCurrent();
            early_.reset();
        }
        return {text, false, std::move(notes)};
    }
    // Not what the record said (the file was rewritten in place): bake what was decoded.
    withdrawEarlyBake();
    job_ = std::make_unique<bake::BakeJob>(renderer_.shaders(), loaded, bakeSettings_, &cache_);
    environment_ = std::make_shared<const Environment>(std::move(loaded));
    return {text, false, std::move(notes)};
}

std::optional<ui::StatusLine> LabSession::finishBake()
{
    const bool earlyJob = early_ && early_->jobRunning;
    if (earlyJob && job_->missedCache()) {
        // The record outlived its bake: bake the pixels once they are here (or now).
        const bool decoded = early_->decoded;
        job_.reset();
        early_.reset();
        if (decoded) job_ = std::make_unique<bake::BakeJob>(renderer_.shaders(), *environment_, bakeSettings_, &cache_);
        return std::nullopt;
    }
    auto result = std::make_shared<bake::BakeResult>(job_->takeResult());
    job_.reset();
    if (earlyJob) {
        early_->jobRunning = false;
        early_->shown = true;
    }
    char gpuMemory[48];
    std::snprintf(gpuMemory, sizeof gpuMemory, ", %.1f MiB of GPU memory", double(result->gpuBytes()) / (1024.0 * 1024.0));
    std::string text = "baked in " + std::to_string(int(result->totalMilliseconds + 0.5)) + " ms" + (result->fromCache ? " (from cache)" : "") + gpuMemory;
    for (const auto& note : result->notes) text += "; " + note;
    bake_ = result;
    renderer_.setBake(bake_);
    if (early_ && !early_->decoded) {
        early_->bakeStatus = text;
        text += "; reading " + shortName(early_->spec);
    } else {
        rememberCurrent();
        early_.reset();
    }
    if (switchInProgress_) {
        switchInProgress_->bakeMs = millisecondsSince(switchRequested_);
        switchInProgress_->fromCache = result->fromCache;
        switchAwaitsFrame_ = true;
    }
    return ui::StatusLine{text, false};
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

ui::StatusLine LabSession::showRecent(const RecentEnvironment& recent, FrameSettings& settings)
{
    early_.reset();
    decodeDeferred_ = false;
    job_.reset(); // a bake of the environment being left
    renderer_.setEnvironment(recent.environment->image);
    renderer_.setBake(recent.bake);
    environment_ = recent.environment;
    bake_ = recent.bake;
    currentSpec_ = recent.spec;
    settings.environment.source = recent.spec;
    if (switchInProgress_) {
        switchInProgress_->loadMs = switchInProgress_->bakeMs = millisecondsSince(switchRequested_);
        switchInProgress_->fromCache = true;
        switchAwaitsFrame_ = true;
    }
    const Environment& env = *recent.environment;
    ui::StatusLine line{environmentLine(env) + ", kept from earlier with its bake", false, env.warnings};
    rememberCurrent();
    return line;
}

LabSession::Finished LabSession::showRequestedRecent(FrameSettings& settings)
{
    Finished finished;
    if (!recentRequested_) return finished;
    const std::string spec = *std::exchange(recentRequested_, std::nullopt);
    const RecentEnvironment* recent = findRecent(spec);
    if (!recent) {
        requestEnvironment(spec); // changed since (a file saved again): load it
        return finished;
    }
    // showRecent reorders recent_: work from a copy of the entry.
    const RecentEnvironment entry = *recent;
    finished.environment = showRecent(entry, settings);
    finished.bake = ui::StatusLine{"kept from earlier (baked in " + std::to_string(int(entry.bake->totalMilliseconds + 0.5)) + " ms" +
                                       (entry.bake->fromCache ? ", from cache)" : ")"),
                                   false};
    return finished;
}

LabSession::Finished LabSession::pump(FrameSettings& settings, std::chrono::steady_clock::duration budget)
{
    if (recentRequested_) return showRequestedRecent(settings);
    // The early bake was shown in an earlier pump (or is gone): its frame has been drawn.
    if (decodeDeferred_ && !(early_ && early_->jobRunning)) startDecode();
    Finished finished;
    if (pendingLoad_.valid() && pendingLoad_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
        if (queuedSpec_) {
            // The user has asked for another environment since: this result is stale.
            withdrawEarlyBake();
            pendingLoad_ = {};
            requestEnvironment(*std::exchange(queuedSpec_, std::nullopt));
            return finished;
        }
        try {
            finished.environment = finishLoad(pendingLoad_.get(), settings);
            finished.bake = std::exchange(bakeStatusAfterDecode_, std::nullopt);
        } catch (const Error& e) {
            withdrawEarlyBake();
            switchInProgress_.reset();
            finished.environment = ui::StatusLine{e.what(), true};
            return finished;
        }
        // The bake starts in the same pump: from the cache it is often done in it.
    }
    if (job_) {
        try {
            if (!job_->runFor(budget)) finished.bake = finishBake();
            // The view shows the early bake from now on: the line names its map, not the last.
            if (early_ && early_->shown && !early_->decoded)
                finished.environment = ui::StatusLine{shortName(early_->spec) + ": shown from the bake cache while the file is read"};
        } catch (const std::exception& e) {
            withdrawEarlyBake();
            job_.reset();
            switchInProgress_.reset();
            finished.bake = ui::StatusLine{std::string("bake failed: ") + e.what(), true};
        }
    }
    return finished;
}

void LabSession::waitForLoad(std::chrono::steady_clock::duration timeout) const
{
    if (pendingLoad_.valid() && !job_) pendingLoad_.wait_for(timeout);
}

bool LabSession::busy() const { return pendingLoad_.valid() || decodeDeferred_ || queuedSpec_ || recentRequested_ || job_ != nullptr; }

std::string LabSession::activity() const
{
    if (pendingLoad_.valid() || decodeDeferred_) return "loading " + shortName(queuedSpec_ ? *queuedSpec_ : pendingSpec_);
    if (job_) {
        const std::optional<bake::BakePhase> phase = job_->currentPhase();
        return "baking: " + std::string(phase ? enumName(*phase) : "done");
    }
    return {};
}

bool LabSession::switching() const { return switchInProgress_.has_value() && !switchAwaitsFrame_; }

float LabSession::progress() const { return job_ ? job_->progress() : 0.0f; }

ui::StatusLine LabSession::loadEnvironment(const std::string& spec, FrameSettings& settings)
{
    requestEnvironment(spec);
    ui::StatusLine status;
    while (busy()) {
        waitForLoad(std::chrono::hours(1));
        const Finished finished = pump(settings, std::chrono::hours(1));
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

ui::StatusLine LabSession::loadModel(const std::string& path, FrameSettings& settings)
{
    try {
        const ModelData model = loadGltfModel(path);
        renderer_.setModel(model, path);
        modelMaterials_ = model.materials;
        settings.scene.kind = SceneKind::Model;
        settings.scene.modelPath = path;
        std::string text = shortName(path) + ": " + std::to_string(model.instances.size()) + " primitives, " +
                           std::to_string(model.materials.size()) + " materials, " + std::to_string(model.textures.size()) + " textures";
        for (const auto& warning : model.warnings) text += "; " + warning;
        modelLine_ = text;
        return {text, false};
    } catch (const Error& e) {
        // The model on screen stays: say which, as a failed environment load does (the error
        // replaced its line, and with it the only sign of what was still shown).
        ui::StatusLine status{e.what(), true};
        if (settings.scene.kind == SceneKind::Model && !modelLine_.empty()) status.notes.push_back("still showing " + modelLine_);
        return status;
    }
}

ui::StatusLine LabSession::exportModel(const std::string& outPath, const FrameSettings& settings) const
{
    if (settings.scene.kind != SceneKind::Model || settings.scene.modelPath.empty()) return {"export: no glTF model is loaded", true};
    const MaterialSettings& m = settings.material;
    auto tuned = [&](PbrMaterial material) {
        material.baseColorFactor = glm::vec4(m.baseColor, material.baseColorFactor.a);
        material.metallicFactor = m.metallic;
        material.roughnessFactor = m.roughness;
        return material;
    };
    std::vector<MaterialEdit> edits;
    for (std::size_t i = 0; i < modelMaterials_.size(); ++i) edits.push_back({int(i), tuned(modelMaterials_[i])});
    if (edits.empty()) edits.push_back({-1, tuned(PbrMaterial{})}); // primitives without a material get one
    try {
        const std::vector<std::string> warnings = exportGltfWithMaterials(settings.scene.modelPath, outPath, edits);
        std::string text = "exported " + outPath + " (" + std::to_string(edits.size()) + " materials)";
        for (const auto& warning : warnings) text += "; " + warning;
        return {text, false};
    } catch (const Error& e) {
        return {e.what(), true};
    }
}

ui::StatusLine LabSession::capture(const std::string& path, const FrameSettings& settings) const
{
    // What the frame was drawn with, bake included: loaded as a preset, it draws the same.
    const std::string settingsJson = presetJsonText(settings, bakeSettings_, path);
    const std::string extension = std::filesystem::path(path).extension().string();
    try {
        if (extension == ".png") {
            const DisplayReadback image = renderer_.readDisplayImage();
            writePng8(path, image.width, image.height, 4, image.rgba, {.bottomUp = true, .settingsJson = settingsJson});
        } else if (extension == ".exr") {
            // Opaque: the frame's alpha is its MSAA coverage, not an opacity of the
            // (unpremultiplied) colour, and would make compositing tools cut the silhouettes.
            FrameReadback image = renderer_.readHdrFrame();
            for (std::size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 1.0f;
            writeExr(path, image.width, image.height, 4, image.rgba, {.bottomUp = true, .settingsJson = settingsJson});
        } else {
            return {path + ": unknown screenshot format \"" + extension + "\" (use .png or .exr)", true};
        }
    } catch (const Error& e) {
        return {e.what(), true};
    }
    return {"saved " + path + " (+ " + path + ".json)", false};
}

void LabSession::frameDrawn()
{
    if (!switchAwaitsFrame_ || !switchInProgress_) return;
    switchInProgress_->firstFrameMs = millisecondsSince(switchRequested_);
    lastSwitch_ = std::exchange(switchInProgress_, std::nullopt);
    switchAwaitsFrame_ = false;
}

ui::EnvironmentCatalog LabSession::catalog() const
{
    ui::EnvironmentCatalog catalog;
    catalog.gallery = galleryEnvironments(assetDirectory().string());
    for (const auto& name : builtinEnvironmentNames()) catalog.builtins.push_back("builtin:" + name);
    return catalog;
}

} // namespace iblab::app
