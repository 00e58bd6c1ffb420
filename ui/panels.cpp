#include "panels.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <imgui.h>

#include "ibl/tonemap.hpp"

namespace iblab::ui {
namespace {

void drawStatus(const StatusLine& status)
{
    if (status.text.empty()) return;
    const ImVec4 colour = status.isError ? ImVec4(1.0f, 0.45f, 0.4f, 1.0f) : ImVec4(0.6f, 0.85f, 0.6f, 1.0f);
    ImGui::PushStyleColor(ImGuiCol_Text, colour);
    ImGui::TextWrapped("%s", status.text.c_str());
    ImGui::PopStyleColor();
}

// The live curve: displayed value (after sRGB encoding, what lands on screen) against
// scene luminance in stops around mid grey, evaluated by the very function the shader
// runs. Drawn by hand for the axes, the mid-grey marker and the hover readout.
void drawToneCurve(const ToneMapSettings& settings)
{
    constexpr float kMinStops = -8.0f, kMaxStops = 8.0f, kMidGrey = 0.18f;
    const ImVec2 size(ImGui::GetContentRegionAvail().x, 120.0f);
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    ImGui::InvisibleButton("##tonecurve", size);
    ImDrawList* draw = ImGui::GetWindowDrawList();
    const ImVec2 end(origin.x + size.x, origin.y + size.y);
    draw->AddRectFilled(origin, end, ImGui::GetColorU32(ImGuiCol_FrameBg));
    auto toScreen = [&](float stops, float value) {
        return ImVec2(origin.x + (stops - kMinStops) / (kMaxStops - kMinStops) * size.x, end.y - value * size.y);
    };
    const ImU32 gridColour = ImGui::GetColorU32(ImGuiCol_Border);
    for (float stops = kMinStops; stops <= kMaxStops; stops += 2.0f) draw->AddLine(toScreen(stops, 0.0f), toScreen(stops, 1.0f), gridColour);
    for (float value : {0.25f, 0.5f, 0.75f}) draw->AddLine(toScreen(kMinStops, value), toScreen(kMaxStops, value), gridColour);
    draw->AddLine(toScreen(0.0f, 0.0f), toScreen(0.0f, 1.0f), ImGui::GetColorU32(ImGuiCol_TextDisabled), 2.0f);

    auto displayed = [&](float stops) { return displayEncode(glm::vec3(kMidGrey * std::exp2(stops)), settings.exposureEv, settings.op).g; };
    constexpr int kPoints = 160;
    ImVec2 points[kPoints];
    for (int i = 0; i < kPoints; ++i) {
        const float stops = kMinStops + (kMaxStops - kMinStops) * float(i) / float(kPoints - 1);
        points[i] = toScreen(stops, displayed(stops));
    }
    draw->AddPolyline(points, kPoints, ImGui::GetColorU32(ImGuiCol_PlotLines), ImDrawFlags_None, 2.0f);
    draw->AddText(ImVec2(origin.x + 4, origin.y + 2), ImGui::GetColorU32(ImGuiCol_TextDisabled), "display value");
    if (ImGui::IsItemHovered()) {
        const float stops = kMinStops + (ImGui::GetIO().MousePos.x - origin.x) / size.x * (kMaxStops - kMinStops);
        draw->AddCircleFilled(toScreen(stops, displayed(stops)), 4.0f, ImGui::GetColorU32(ImGuiCol_PlotLinesHovered));
        ImGui::SetTooltip("scene %.4g (%+.1f stops from mid grey) -> display %.3f (8-bit %d)", kMidGrey * std::exp2(stops), stops,
                          displayed(stops), int(displayed(stops) * 255.0f + 0.5f));
    }
    ImGui::TextDisabled("x: scene luminance, mid grey x 2^[%.0f..%+.0f]; line at mid grey", kMinStops, kMaxStops);
}

std::string displayName(const std::string& source)
{
    if (source.rfind("builtin:", 0) == 0) return source;
    return std::filesystem::path(source).filename().string();
}

} // namespace

void drawEnvironmentPanel(EnvironmentSettings& settings, PanelState& state, UiRequests& requests)
{
    if (!ImGui::CollapsingHeader("Environment", ImGuiTreeNodeFlags_DefaultOpen)) return;
    if (ImGui::BeginCombo("Source", displayName(settings.source).c_str())) {
        ImGui::TextDisabled("Bundled (CC0)");
        for (const auto& path : state.catalog.gallery)
            if (ImGui::Selectable(displayName(path).c_str(), path == settings.source)) requests.loadEnvironment = path;
        ImGui::Separator();
        ImGui::TextDisabled("Procedural");
        for (const auto& name : state.catalog.builtins)
            if (ImGui::Selectable(name.c_str(), name == settings.source)) requests.loadEnvironment = name;
        ImGui::EndCombo();
    }
    ImGui::InputTextWithHint("##envpath", ".exr / .hdr path or builtin:NAME", state.environmentPath, sizeof state.environmentPath);
    ImGui::SameLine();
    if (ImGui::Button("Load") && state.environmentPath[0] != '\0') requests.loadEnvironment = std::string(state.environmentPath);
    ImGui::SliderFloat("Yaw", &settings.yawDegrees, -180.0f, 180.0f, "%.1f deg");
    ImGui::SliderFloat("Intensity", &settings.intensityEv, -10.0f, 10.0f, "%+.2f EV");
    drawStatus(state.environmentStatus);
}

void drawToneMapPanel(ToneMapSettings& settings)
{
    if (!ImGui::CollapsingHeader("Tone mapping", ImGuiTreeNodeFlags_DefaultOpen)) return;
    if (ImGui::BeginCombo("Operator", toneMapOperatorLabel(settings.op))) {
        for (ToneMapOperator op : allToneMapOperators())
            if (ImGui::Selectable(toneMapOperatorLabel(op), op == settings.op)) settings.op = op;
        ImGui::EndCombo();
    }
    ImGui::SliderFloat("Exposure", &settings.exposureEv, -10.0f, 10.0f, "%+.2f EV");
    ImGui::SameLine();
    if (ImGui::SmallButton("0")) settings.exposureEv = 0.0f;

    drawToneCurve(settings);
}

void drawCameraPanel(CameraSettings& settings)
{
    if (!ImGui::CollapsingHeader("Camera", ImGuiTreeNodeFlags_DefaultOpen)) return;
    ImGui::SliderFloat("Yaw##camera", &settings.yawDegrees, -180.0f, 180.0f, "%.1f deg");
    ImGui::SliderFloat("Pitch", &settings.pitchDegrees, -89.0f, 89.0f, "%.1f deg");
    ImGui::SliderFloat("Field of view", &settings.fovDegrees, 10.0f, 120.0f, "%.0f deg");
}

void drawCapturePanel(PanelState& state, UiRequests& requests)
{
    if (!ImGui::CollapsingHeader("Capture", ImGuiTreeNodeFlags_DefaultOpen)) return;
    ImGui::InputText("File", state.capture.path, sizeof state.capture.path);
    if (ImGui::Button("Save screenshot (F12)")) requests.captureTo = std::string(state.capture.path);
    ImGui::SameLine();
    ImGui::TextDisabled(".png: tone-mapped sRGB, .exr: linear HDR");
    drawStatus(state.captureStatus);
}

void drawStatsOverlay(const FrameStats& stats)
{
    ImGui::Text("%dx%d  frame %.1f ms  passes %.1f ms", stats.width, stats.height, stats.frameMs, stats.renderMs);
    ImGui::TextDisabled("%s", stats.renderer.c_str());
}

void drawControlWindow(FrameSettings& settings, PanelState& state, const FrameStats& stats, UiRequests& requests)
{
    if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Tab)) && !ImGui::GetIO().WantTextInput) state.showPanels = !state.showPanels;
    if (!state.showPanels) return;
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(360, 0), ImGuiCond_FirstUseEver);
    ImGui::Begin("iblab");
    drawStatsOverlay(stats);
    drawEnvironmentPanel(settings.environment, state, requests);
    drawToneMapPanel(settings.toneMap);
    drawCameraPanel(settings.camera);
    drawCapturePanel(state, requests);
    ImGui::End();
}

} // namespace iblab::ui
