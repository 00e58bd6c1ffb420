// GuiApp::state(): what a script can check, in JSON (docs/gui-scripts.md lists the keys).
#include <cmath>

#include <imgui.h>
#include <imgui_internal.h>

#include "gui_app_impl.hpp"
#include "ui/help_window.hpp"
#include "ui/overlays.hpp"
#include "ui/widgets.hpp"

namespace iblab::app {
namespace {

nlohmann::json statusJson(const ui::StatusLine& status) { return {{"text", status.text}, {"error", status.isError}, {"notes", status.notes}}; }

nlohmann::json switchJson(const std::optional<SwitchTiming>& timing)
{
    if (!timing) return nullptr;
    return {{"environment", timing->environment}, {"load_ms", timing->loadMs}, {"bake_ms", timing->bakeMs},
            {"first_frame_ms", timing->firstFrameMs}, {"from_cache", timing->fromCache}};
}

// Points the Study chart draws: with a positive error and cost (the axes are logarithmic).
std::size_t plottedPoints(const std::vector<ui::ParetoChart>& charts)
{
    std::size_t count = 0;
    for (const ui::ParetoChart& chart : charts)
        for (const ui::ChartSeries& series : chart.series)
            for (const ui::ChartPoint& point : series.points) count += point.x > 0.0 && point.y > 0.0 && std::isfinite(point.y);
    return count;
}

// Right and bottom too, so that a script can check the window is inside the display.
nlohmann::json chartWindowJson(const float (&rect)[4])
{
    return {{"x", rect[0]}, {"y", rect[1]}, {"width", rect[2]}, {"height", rect[3]}, {"right", rect[0] + rect[2]}, {"bottom", rect[1] + rect[3]}};
}

// The texts drawn over the view; with `outside`, only those not wholly inside it (cut off).
nlohmann::json overlayTextsJson(const ui::ViewRect& view, bool outside)
{
    nlohmann::json texts = nlohmann::json::array();
    for (const ui::OverlayText& t : ui::overlayTexts()) {
        const bool inside = t.x0 >= view.x0 && t.y0 >= view.y0 && t.x1 <= view.x1 && t.y1 <= view.y1;
        if (!outside || !inside) texts.push_back(t.text);
    }
    return texts;
}

// The texts drawn over the view that overlap another one (a title running into the next
// tile's title).
nlohmann::json overlappingOverlayTextsJson()
{
    nlohmann::json texts = nlohmann::json::array();
    const std::vector<ui::OverlayText>& drawn = ui::overlayTexts();
    for (std::size_t i = 0; i < drawn.size(); ++i) {
        for (std::size_t j = 0; j < drawn.size(); ++j) {
            const ui::OverlayText &a = drawn[i], &b = drawn[j];
            if (i != j && a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1) {
                texts.push_back(a.text);
                break;
            }
        }
    }
    return texts;
}

// Whether the last frame drew a tooltip (ImGui's window for them is "##Tooltip_00").
bool tooltipShown()
{
    const ImGuiWindow* window = ImGui::FindWindowByName("##Tooltip_00");
    return window && window->Active;
}

} // namespace

nlohmann::json GuiApp::state() const
{
    const Impl& a = *impl_;
    const ui::PanelState& p = a.panels;
    nlohmann::json labels = nlohmann::json::array();
    for (const ScreenLabel& label : a.renderer.sceneLabels(a.settings, a.stats.width, a.stats.height))
        labels.push_back({{"text", label.text}, {"x", p.viewRect.x0 + label.pixel.x}, {"y", float(a.stats.height) - label.pixel.y}});
    nlohmann::json popups = nlohmann::json::array();
    for (const ImGuiPopupData& popup : ImGui::GetCurrentContext()->OpenPopupStack)
        popups.push_back(popup.Window ? popup.Window->Name : "");
    return {
        {"frame", a.framesShown},
        {"idle", a.pace == LoopPace::Idle || a.pace == LoopPace::IdleAsleep},
        {"quit", a.quit},
        {"platform", platformKindName(a.platform.kind())},
        {"window", {{"width", a.platform.width()}, {"height", a.platform.height()}}},
        {"view", {{"x", p.viewRect.x0}, {"y", p.viewRect.y0}, {"width", p.viewRect.x1 - p.viewRect.x0}, {"height", p.viewRect.y1 - p.viewRect.y0},
                  {"overlay_texts", overlayTextsJson(p.viewRect, false)}, {"overlay_texts_outside", overlayTextsJson(p.viewRect, true)},
                  {"overlay_texts_overlapping", overlappingOverlayTextsJson()},
                  {"first_image_of_environment", {{"environment", a.firstImageOfEnvironment.environment}, {"status", a.firstImageOfEnvironment.status}}}}},
        {"settings", nlohmann::json::parse(toJsonText(a.settings))},
        {"unsaved_changes", a.unsavedChanges()},
        {"panels",
         {{"shown", p.showPanels},
          {"width", p.panelWidth},
          {"environment_status", statusJson(p.environmentStatus)},
          {"bake_status", statusJson(p.bakeStatus)},
          {"scene_status", statusJson(p.sceneStatus)},
          {"capture_status", statusJson(p.captureStatus)},
          {"preset_status", statusJson(p.presetStatus)},
          {"activity", p.activity.text},
          {"convention", p.convention},
          {"quit_dialog", p.quitDialog.open},
          {"hint", p.firstRunHint ? ui::kFirstRunHint : ""},
          {"sections", ui::sectionStates()},
          {"paths",
           {{"environment", p.environmentPath},
            {"model", p.modelPath},
            {"preset", p.presetPath},
            {"export", p.exportPath},
            {"bake_export", p.bakeExportPath},
            {"capture_folder", p.capture.directory}}},
          {"compare",
           {{"reference_current", p.compare.reference.current},
            {"reference_complete", p.compare.reference.complete},
            {"reference_progress", p.compare.reference.progress},
            {"error_valid", p.compare.error.valid},
            {"relative_rmse", p.compare.error.valid ? p.compare.error.left.relativeRmse : 0.0},
            {"pixels", p.compare.error.valid ? p.compare.error.left.pixels : 0}}},
          {"study",
           {{"running", p.study.running},
            {"status", statusJson(p.study.status)},
            {"charts", p.study.charts.size()},
            {"plotted_points", plottedPoints(p.study.charts)},
            {"chart_open", p.study.chartOpen},
            {"chart_window", chartWindowJson(p.study.chartWindow)},
            {"auto_quality", {{"running", p.study.autoQuality.running}, {"have_choice", p.study.autoQuality.haveChoice}, {"applied", p.study.autoQuality.applied}, {"chosen", p.study.autoQuality.chosen}}}}}}},
        {"session", {{"busy", a.session.busy()}, {"environment", a.session.environment() ? a.session.environment()->source : ""}, {"has_bake", a.renderer.hasBake()}, {"last_switch", switchJson(a.session.lastSwitch())}}},
        {"renderer",
         {{"accumulated_frames", a.renderer.accumulatedFrames()},
          {"content_revision", a.renderer.contentRevision()},
          {"sampled", a.renderer.lastFrameWasSampled()},
          {"render_ms", a.stats.renderMs},
          {"shows_current", a.view.showsSettingsOf(ViewContent{a.settings, a.stats.width, a.stats.height, a.renderer.contentRevision()})},
          {"slice_progress", a.renderer.sliceProgress()},
          {"images", a.viewImages},
          {"resolution_scale", a.stats.resolutionScale}}},
        {"ui",
         {{"popups", popups},
          {"help_open", p.helpOpen},
          {"want_text_input", ImGui::GetIO().WantTextInput},
          {"tooltip", tooltipShown()},
          {"mouse", {ImGui::GetIO().MousePos.x, ImGui::GetIO().MousePos.y}}}},
        {"labels", labels},
    };
}

} // namespace iblab::app
