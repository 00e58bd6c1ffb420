#pragma once
// The Study panel's work: a quick bench sweep, or the auto-quality choice, on the current
// environment and scene, a budgeted slice per GUI frame. It runs on a renderer of its own,
// so the view keeps its environment and bake.
#include <chrono>
#include <cstddef>
#include <memory>
#include <optional>

#include "lab/auto_quality.hpp"
#include "lab/bench_sweep.hpp"
#include "lab_session.hpp"
#include "ui/panels.hpp"
#include "frame/renderer.hpp"

namespace iblab::app {

class StudyRun {
public:
    void start(const LabSession& session, const FrameSettings& settings, ui::StudyState& study) { begin(session, settings, study, false); }

    // The auto quality mode: its candidates for this scene and environment, and the presets
    // beside them, measured like the sweep; the choice is made when the last one is in.
    void startAutoQuality(const LabSession& session, const FrameSettings& settings, ui::StudyState& study) { begin(session, settings, study, true); }

    void stop(ui::StudyState& study);
    // One slice of the sweep; the chart follows the points measured so far.
    void advance(ui::StudyState& study, std::chrono::steady_clock::duration budget);
    // The chosen bake and sampling on top of the session's: its environment cube and LUT stay.
    void applyAutoQuality(LabSession& session, FrameSettings& settings, ui::PanelState& panels) const;
    bool running() const { return bool(job_); }

private:
    void begin(const LabSession& session, const FrameSettings& settings, ui::StudyState& study, bool autoQuality);
    void finishAutoQuality(ui::StudyState& study);

    std::unique_ptr<Renderer> renderer_;
    std::unique_ptr<bench::BenchJob> job_;
    std::size_t pointsCharted_ = 0;
    bench::AutoCandidates candidates_;
    double targetSteps_ = bench::kDefaultAutoTargetSteps;
    std::optional<bench::AutoChoice> choice_;
};

} // namespace iblab::app
