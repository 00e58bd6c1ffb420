// The Study section (quick sweep, auto quality) and its floating chart window: Dear ImGui
// code that edits the study state and asks the app to run studies, never calling GL.
#include "ui/panels.hpp"

#include <algorithm>
#include <cstdio>
#include <string>

#include <imgui.h>

#include "ui/pareto_chart.hpp"
#include "ui/status_area.hpp"
#include "ui/widgets.hpp"

namespace iblab::ui {

void drawStudyPanel(PanelState& state, UiRequests& requests)
{
    Section section("Study");
    if (!section) return;
    StudyState& study = state.study;
    ImGui::TextWrapped("Speed against accuracy on the current environment and scene: the quick sweep of `iblab bench` (split-sum prefilter "
                       "samples, runtime N, diffuse sources), each point baked, timed and compared with the reference.");
    if (!study.running) {
        if (button("Run quick sweep")) requests.startStudy = true;
        if (!study.charts.empty()) {
            ImGui::SameLine();
            if (button(study.chartOpen ? "Hide chart" : "Show chart")) study.chartOpen = !study.chartOpen;
        }
    } else {
        // Stop sits at the far end of the row, away from where "Run quick sweep" is drawn: a
        // click meant for Stop that lands just after the run ends must not start another.
        const float stopWidth = ImGui::CalcTextSize("Stop").x + 2.0f * ImGui::GetStyle().FramePadding.x;
        ImGui::ProgressBar(study.progress, ImVec2(std::max(40.0f, ImGui::GetContentRegionAvail().x - stopWidth - ImGui::GetStyle().ItemSpacing.x), 0.0f));
        ImGui::SameLine();
        if (button("Stop")) requests.stopStudy = true;
        ImGui::TextDisabled("%s", study.activity.c_str());
    }
    drawStatus(study.status);

    ImGui::Separator();
    ImGui::TextUnformatted("Auto quality");
    AutoQualityState& autoQuality = study.autoQuality;
    ImGui::TextWrapped("The cheapest settings whose 99th-percentile error after tone mapping stays within the target, measured on this "
                       "environment and scene. 20 steps: 99%% of the pixels within 20 of 255 levels of the reference, a difference "
                       "seen side by side rather than at a glance.");
    sliderFloat("Target", &autoQuality.targetSteps, 0.25f, 64.0f, "p99 %.2f 8-bit steps", ImGuiSliderFlags_Logarithmic);
    ImGui::BeginDisabled(study.running);
    if (button("Choose")) requests.startAutoQuality = true;
    ImGui::EndDisabled();
    if (autoQuality.haveChoice) {
        ImGui::SameLine();
        ImGui::BeginDisabled(study.running);
        if (button("Apply")) requests.applyAutoQuality = true;
        ImGui::EndDisabled();
        if (autoQuality.meetsTarget) ImGui::TextColored(ImVec4(0.5f, 0.9f, 0.5f, 1.0f), "Chosen (within the target):");
        else ImGui::TextColored(ImVec4(1.0f, 0.6f, 0.3f, 1.0f), "Target out of reach; the most accurate:");
        ImGui::TextWrapped("%s", autoQuality.chosen.c_str());
        ImGui::TextWrapped("%s", autoQuality.numbers.c_str());
        ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
        for (const std::string& preset : autoQuality.presets) ImGui::TextWrapped("%s", preset.c_str());
        ImGui::PopStyleColor();
        const bool why = ImGui::TreeNodeEx("Why", ImGuiTreeNodeFlags_DefaultOpen);
        itemRegistry().recordLastItem("Why", "header");
        if (why) {
            for (const std::string& reason : autoQuality.reasons) {
                ImGui::Bullet();
                ImGui::TextWrapped("%s", reason.c_str());
            }
            ImGui::TreePop();
        }
    }
}

void drawStudyChartWindow(StudyState& study)
{
    if (study.charts.empty() || !study.chartOpen) return;
    ImGui::SetNextWindowSize(ImVec2(760, 480), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowPos(ImVec2(ImGui::GetIO().DisplaySize.x - 780, 20), ImGuiCond_FirstUseEver);
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowSizeConstraints(ImVec2(0, 0), ImVec2(std::max(display.x, 1.0f), std::max(display.y, 1.0f)));
    // Not focused when it appears: it reappears with a run's first point, and taking focus
    // then cancelled a click on the panel pressed the frame before (Stop, in
    // tests/gui/scripts/tour_study.txt, lost in 4 of 6 runs with a warm bake cache).
    const bool open = ImGui::Begin("Study: speed against accuracy", &study.chartOpen, ImGuiWindowFlags_NoFocusOnAppearing);
    // The window stays on screen: a window shrunk under it pushed it off, where it stayed
    // after the window grew back.
    const ImVec2 position = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
    const ImVec2 inside(std::clamp(position.x, 0.0f, std::max(0.0f, display.x - size.x)), std::clamp(position.y, 0.0f, std::max(0.0f, display.y - size.y)));
    if (inside.x != position.x || inside.y != position.y) ImGui::SetWindowPos(inside);
    study.chartWindow[0] = inside.x;
    study.chartWindow[1] = inside.y;
    study.chartWindow[2] = size.x;
    study.chartWindow[3] = size.y;
    if (!open) {
        ImGui::End();
        return;
    }
    itemRegistry().pushScope("Study chart");
    for (std::size_t i = 0; i < study.charts.size(); ++i) {
        const ParetoChart& chart = study.charts[i];
        const ImVec2 chartSize(std::max(ImGui::GetContentRegionAvail().x, 420.0f), std::max(ImGui::GetContentRegionAvail().y, 260.0f));
        const ImVec2 origin = ImGui::GetCursorScreenPos();
        ImGui::PushID(int(i));
        canvas("##chart", chartSize, "canvas");
        const bool hovered = ImGui::IsItemHovered();
        ImGui::PopID();
        const ChartHover hover = drawParetoChart(*ImGui::GetWindowDrawList(), chart, origin, chartSize,
                                                 hovered ? std::optional<ImVec2>(ImGui::GetIO().MousePos) : std::nullopt);
        if (hover.valid()) ImGui::SetTooltip("%s", chart.series[std::size_t(hover.series)].points[std::size_t(hover.point)].tooltip.c_str());
    }
    itemRegistry().popScope();
    ImGui::End();
}

} // namespace iblab::ui
