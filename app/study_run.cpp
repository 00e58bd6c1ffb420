#include "study_run.hpp"

#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "asset_paths.hpp"
#include "bench_chart.hpp"

namespace iblab::app {

void StudyRun::stop(ui::StudyState& study)
{
    job_.reset();
    study.running = false;
    study.autoQuality.running = false;
    study.status = {"stopped", false};
}

void StudyRun::advance(ui::StudyState& study, std::chrono::steady_clock::duration budget)
{
    if (!job_) return;
    try {
        const bool more = job_->runFor(budget);
        study.progress = job_->progress();
        study.activity = job_->currentActivity();
        if (job_->report().points.size() != pointsCharted_) {
            pointsCharted_ = job_->report().points.size();
            study.charts = study.autoQuality.running ? benchCharts(job_->report(), ChartError::DisplayP99, targetSteps_) : benchCharts(job_->report());
        }
        // A scene the reference cannot resolve measures nothing: say why at once, not
        // "measured" over an empty chart.
        const std::vector<std::string> unmeasured = bench::unmeasuredEnvironments(job_->report());
        if (!unmeasured.empty()) study.status = {unmeasured.front(), true};
        if (!more) {
            study.running = false;
            if (unmeasured.empty())
                study.status = {std::to_string(pointsCharted_) + " settings measured in " + std::to_string(int(job_->report().seconds)) + " s", false};
            if (study.autoQuality.running) finishAutoQuality(study);
            job_.reset();
        }
    } catch (const std::exception& e) {
        study.running = false;
        study.autoQuality.running = false;
        study.status = {e.what(), true};
        job_.reset();
    }
    if (!job_) pointsCharted_ = 0;
}

void StudyRun::applyAutoQuality(LabSession& session, FrameSettings& settings, ui::PanelState& panels) const
{
    if (!choice_ || !choice_->found) return;
    session.setBakeSettings(bench::appliedBakeSettings(*choice_, session.bakeSettings()));
    settings.sampling = bench::appliedSampling(*choice_, settings.sampling);
    panels.bakeStatus = {"auto quality: baking " + bench::describeSettings(choice_->chosen.setting), false};
    panels.study.autoQuality.applied = true;
}

void StudyRun::begin(const LabSession& session, const FrameSettings& settings, ui::StudyState& study, bool autoQuality)
{
    if (!session.environment()) {
        study.status = {"no environment loaded yet", true};
        return;
    }
    if (settings.scene.kind == SceneKind::None) {
        study.status = {"the scene has no surfaces to measure: pick sphere, grid or a model", true};
        return;
    }
    try {
        if (!renderer_) renderer_ = std::make_unique<Renderer>(shaderDirectory());
        bench::BenchOptions options = bench::defaultBenchOptions(/*quick=*/true, assetDirectory().string());
        const Environment& environment = *session.environment();
        options.environments = {{std::filesystem::path(environment.source).stem().string(), environment.source,
                                 std::make_shared<const Environment>(environment)}};
        options.frame = settings;
        options.width = options.height = 96; // the quick run's 48 is for tests; 96 still sweeps in seconds
        if (autoQuality) {
            candidates_ = bench::autoCandidates(/*quick=*/true, bench::sceneFacts(settings, environment.image));
            options.points = candidates_.points;
            for (bench::SweepPoint& preset : bench::presetPoints(/*quick=*/true)) options.points.push_back(std::move(preset));
            options.referenceWidth = candidates_.referenceWidth;
            targetSteps_ = study.autoQuality.targetSteps;
        }
        job_ = std::make_unique<bench::BenchJob>(*renderer_, options);
        ui::AutoQualityState kept = study.autoQuality;
        study = {true, 0.0f, "", {}, {}, true, kept};
        study.autoQuality.running = autoQuality;
        if (autoQuality) {
            study.autoQuality.haveChoice = false;
            study.autoQuality.applied = false;
            choice_.reset();
        }
    } catch (const std::exception& e) {
        study.status = {e.what(), true};
    }
}

void StudyRun::finishAutoQuality(ui::StudyState& study)
{
    bench::BenchReport report = job_->report();
    choice_ = bench::chooseAuto(report, targetSteps_, candidates_);
    bench::markChosen(report.points, *choice_);
    study.charts = benchCharts(report, ChartError::DisplayP99, targetSteps_);
    ui::AutoQualityState& shown = study.autoQuality;
    shown.running = false;
    shown.haveChoice = choice_->found;
    shown.meetsTarget = choice_->meetsTarget;
    shown.reasons = choice_->reasons;
    shown.presets.clear();
    if (!choice_->found) {
        study.status = {choice_->reasons.back(), true};
        return;
    }
    const auto numbers = [](const bench::BenchPoint& p) {
        char text[160];
        std::snprintf(text, sizeof text, "cost %.1f ms (bake %.1f + frame %.2f), display p99 %.2f steps, RMS %.2f", p.costMilliseconds,
                      p.bakeMilliseconds, p.frameMilliseconds, p.display.p99Steps, p.display.rmsSteps);
        return std::string(text);
    };
    shown.chosen = bench::describeSettings(choice_->chosen.setting);
    shown.numbers = numbers(choice_->chosen);
    for (const bench::BenchPoint& p : report.points)
        if (p.setting.family == bench::SweepFamily::Preset) shown.presets.push_back(p.setting.mark + " preset: " + numbers(p));
}

} // namespace iblab::app
