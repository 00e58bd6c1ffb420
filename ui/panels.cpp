#include "panels.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <imgui.h>

#include "conventions.hpp"
#include "ibl/error_metrics.hpp"
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
    if (!state.activity.text.empty()) ImGui::ProgressBar(state.activity.progress, ImVec2(-1.0f, 0.0f), state.activity.text.c_str());
    drawStatus(state.bakeStatus);
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

void drawCameraPanel(CameraSettings& settings, UiRequests& requests)
{
    if (!ImGui::CollapsingHeader("Camera")) return;
    ImGui::SliderFloat("Yaw##camera", &settings.yawDegrees, -180.0f, 180.0f, "%.1f deg");
    ImGui::SliderFloat("Pitch", &settings.pitchDegrees, -89.0f, 89.0f, "%.1f deg");
    ImGui::SliderFloat("Field of view", &settings.fovDegrees, 10.0f, 120.0f, "%.0f deg");
    ImGui::SliderFloat("Distance", &settings.distance, 0.1f, 200.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
    if (ImGui::Button("Frame the scene")) requests.frameScene = true;
    ImGui::SameLine();
    ImGui::TextDisabled("drag: orbit, wheel: zoom, double-click: frame");
}

// A combo over an enum whose names settings.hpp spells; returns true when it changed.
template <typename Enum, std::size_t N>
bool enumCombo(const char* label, Enum& value, const std::array<Enum, N>& values, std::string_view (*nameOf)(Enum))
{
    bool changed = false;
    if (ImGui::BeginCombo(label, std::string(nameOf(value)).c_str())) {
        for (Enum v : values)
            if (ImGui::Selectable(std::string(nameOf(v)).c_str(), v == value)) {
                changed = v != value;
                value = v;
            }
        ImGui::EndCombo();
    }
    return changed;
}

void drawMaterialPanel(MaterialSettings& settings, const SceneSettings& scene)
{
    if (!ImGui::CollapsingHeader("Material", ImGuiTreeNodeFlags_DefaultOpen)) return;
    if (scene.kind == SceneKind::Model) ImGui::Checkbox("Override the model's factors", &settings.overrideModel);
    ImGui::ColorEdit3("Base colour", &settings.baseColor.x, ImGuiColorEditFlags_Float);
    if (scene.kind == SceneKind::Grid) ImGui::TextDisabled("The grid sets metallic (rows) and roughness (columns).");
    ImGui::SliderFloat("Metallic", &settings.metallic, 0.0f, 1.0f);
    ImGui::SliderFloat("Roughness", &settings.roughness, 0.0f, 1.0f);
    ImGui::SliderFloat("AO", &settings.ambientOcclusion, 0.0f, 1.0f);
    ImGui::SliderFloat("Specular", &settings.specular, 0.0f, 1.0f, "%.2f");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Dielectric F0 = 0.16 specular^2: 0.5 gives 4%%");
}

namespace {

// The estimator's controls; the frame's own (A) and the split view's B use the same.
void drawSamplingControls(SamplingSettings& settings)
{
    enumCombo("Method", settings.method, std::array{ShadingMethod::SplitSum, ShadingMethod::Sampled}, shadingMethodName);
    if (settings.method == ShadingMethod::Sampled) {
        ImGui::SliderInt("N samples", &settings.samples, 1, 1024, "%d", ImGuiSliderFlags_Logarithmic);
        ImGui::Checkbox("PDF mip filtering", &settings.pdfMipFiltering);
        if (settings.pdfMipFiltering) ImGui::SliderFloat("Mip bias", &settings.mipBias, -1.0f, 3.0f, "%+.2f");
        ImGui::Checkbox("Cosine-sampled diffuse", &settings.cosineSampledDiffuse);
        ImGui::Checkbox("Normalise by accepted samples", &settings.normalizeByAccepted);
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("LearnOpenGL's normalisation; off divides by N (unbiased)");
    }
    bool automatic = settings.forcedMip < 0;
    if (ImGui::Checkbox("Auto mip", &automatic)) settings.forcedMip = automatic ? -1 : 0;
    if (!automatic) {
        ImGui::SameLine();
        ImGui::SetNextItemWidth(120.0f);
        ImGui::SliderInt("Forced mip", &settings.forcedMip, 0, 10);
    }
    enumCombo("Geometry term", settings.geometry, std::array{GeometryTerm::SchlickGGX, GeometryTerm::HeightCorrelatedSmith}, geometryTermShortName);
    enumCombo("Diffuse", settings.diffuse, std::array{DiffuseSource::Sh9, DiffuseSource::IrradianceCube}, diffuseSourceName);
    ImGui::Checkbox("Multiple-scattering compensation", &settings.multiscatter);
    if (settings.method == ShadingMethod::SplitSum) {
        ImGui::Checkbox("F_roughness on the LUT", &settings.roughFresnelOnLut);
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("LearnOpenGL's split sum: F_roughness(n.v) A + B; off: F0 A + B (exact)");
    }
}

// "sampled N=16" or "splitsum", the divider's labels.
// The smoothest roughness the scene shows, where the settings say it (a glTF's own
// materials are not known here).
std::optional<float> smoothestRoughness(const FrameSettings& settings)
{
    switch (settings.scene.kind) {
    case SceneKind::Sphere:
    case SceneKind::Counting: return settings.material.roughness;
    case SceneKind::Grid:
    case SceneKind::Sweep: return 0.0f;
    case SceneKind::Model: return settings.material.overrideModel ? std::optional<float>(settings.material.roughness) : std::nullopt;
    case SceneKind::None: return std::nullopt;
    }
    return std::nullopt;
}

std::string samplingSummary(const SamplingSettings& s)
{
    std::string text(shadingMethodName(s.method));
    if (s.method == ShadingMethod::Sampled) text += " N=" + std::to_string(s.samples) + (s.pdfMipFiltering ? "" : " mip0");
    if (s.forcedMip >= 0) text += " mip " + std::to_string(s.forcedMip);
    text += ", " + std::string(geometryTermShortName(s.geometry));
    if (s.multiscatter) text += ", ms";
    if (s.roughFresnelOnLut && s.method == ShadingMethod::SplitSum) text += ", F_r on LUT";
    return text;
}

void drawMetricsTable(const char* id, const ErrorMetrics& m)
{
    if (!ImGui::BeginTable(id, 2, ImGuiTableFlags_SizingStretchProp)) return;
    auto row = [](const char* name, const char* format, double value) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(name);
        ImGui::TableNextColumn();
        ImGui::Text(format, value);
    };
    row("relative RMSE", "%.4f", m.relativeRmse);
    row("mean relative error", "%.4f", m.meanRelative);
    row("99th percentile", "%.4f", m.p99Relative);
    row("max", "%.4f", m.maxRelative);
    row("fireflies (> 3x)", "%.0f", double(m.fireflies));
    row("surface pixels", "%.0f", double(m.pixels));
    ImGui::EndTable();
}

} // namespace

void drawConventionPanel(PanelState& state, UiRequests& requests)
{
    if (!ImGui::CollapsingHeader("Conventions")) return;
    ImGui::TextWrapped("Bake and shade as another viewer does; the Compare section's A/B split and error view show what it changes.");
    for (const ConventionPreset& convention : conventionPresets()) {
        const bool current = state.convention == convention.name;
        if (ImGui::RadioButton(std::string(convention.title).c_str(), current) && !current)
            requests.applyConvention = std::string(convention.name);
        if (ImGui::IsItemHovered()) {
            ImGui::BeginTooltip();
            for (const auto& [aspect, choice] : conventionChoices(convention)) ImGui::Text("%-20s %s", aspect.c_str(), choice.c_str());
            ImGui::EndTooltip();
        }
    }
}

void drawSamplingPanel(SamplingSettings& settings)
{
    if (!ImGui::CollapsingHeader("Sampling", ImGuiTreeNodeFlags_DefaultOpen)) return;
    drawSamplingControls(settings);
}

void drawComparePanel(ViewSettings& view, const SamplingSettings& frameSampling, const CompareState& state, std::optional<float> sceneMinRoughness)
{
    if (!ImGui::CollapsingHeader("Compare")) return;
    bool errorView = view.mode == ViewMode::Error;
    if (ImGui::Checkbox("Error against the reference", &errorView)) view.mode = errorView ? ViewMode::Error : ViewMode::Final;
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("The full integral over the environment's texels: no split sum, no N = V = R");
    if (errorView) {
        enumCombo("Compare", view.errorSpace, std::array{ErrorSpace::Linear, ErrorSpace::Display}, errorSpaceName);
        ImGui::SliderFloat("Colour bar top", &view.errorScale, 0.01f, 4.0f, "%.3f", ImGuiSliderFlags_Logarithmic);
        const std::array widths{32, 64, 128, 256, 512};
        if (ImGui::BeginCombo("Reference map", (std::to_string(view.referenceWidth) + " x " + std::to_string(view.referenceWidth / 2)).c_str())) {
            for (int w : widths)
                if (ImGui::Selectable((std::to_string(w) + " x " + std::to_string(w / 2)).c_str(), w == view.referenceWidth)) view.referenceWidth = w;
            ImGui::EndCombo();
        }
        const ReferenceStatus& r = state.reference;
        if (r.current) {
            char text[96];
            std::snprintf(text, sizeof text, "reference %.0f%% (%dx%d)", 100.0 * r.progress, r.environmentWidth, r.environmentHeight);
            ImGui::ProgressBar(r.progress, ImVec2(-1.0f, 0.0f), text);
            ImGui::TextDisabled("texel %.2f deg: converged for roughness >= %.2f", r.texelDegrees, r.minResolvedRoughness);
            if (sceneMinRoughness && *sceneMinRoughness < r.minResolvedRoughness)
                ImGui::TextColored(ImVec4(1.0f, 0.75f, 0.3f, 1.0f),
                                   "Roughness %.2f is below that: there the heatmap measures the reference's texels, not the method. "
                                   "Use a wider reference map.",
                                   *sceneMinRoughness);
        }
        if (state.error.valid) {
            ImGui::TextUnformatted(view.split ? "A (left)" : "Frame");
            drawMetricsTable("##errorA", state.error.left);
            if (state.error.right) {
                ImGui::TextUnformatted("B (right)");
                drawMetricsTable("##errorB", *state.error.right);
            }
        }
    }
    ImGui::Separator();
    ImGui::Checkbox("A/B split", &view.split);
    if (!view.split) return;
    ImGui::SliderFloat("Divider", &view.splitPosition, 0.0f, 1.0f, "%.2f");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Or drag the line in the view");
    if (ImGui::Button("Copy A's sampling to B")) view.compare = frameSampling;
    ImGui::TextDisabled("B, right of the divider:");
    ImGui::PushID("B");
    drawSamplingControls(view.compare);
    ImGui::PopID();
}

void drawScenePanel(SceneSettings& settings, PanelState& state, UiRequests& requests)
{
    if (!ImGui::CollapsingHeader("Scene", ImGuiTreeNodeFlags_DefaultOpen)) return;
    const std::array kinds{SceneKind::Sphere, SceneKind::Grid, SceneKind::Counting, SceneKind::Sweep, SceneKind::Model, SceneKind::None};
    if (enumCombo("Scene", settings.kind, kinds, sceneKindName)) requests.sceneChanged = true;
    if (settings.kind == SceneKind::Counting || settings.kind == SceneKind::Sweep) {
        if (ImGui::SliderInt(settings.kind == SceneKind::Counting ? "Spheres (N = 1..k)" : "Spheres (roughness 0..1)", &settings.countingSpheres, 2, 16))
            requests.sceneChanged = true;
        ImGui::TextDisabled(settings.kind == SceneKind::Counting ? "Sampled method; try builtin:lights, forced mip 0, metallic 1."
                                                                 : "Sampled method at the Sampling panel's N; try builtin:lights.");
    }
    ImGui::InputTextWithHint("##model", ".gltf / .glb path", state.modelPath, sizeof state.modelPath);
    ImGui::SameLine();
    if (ImGui::Button("Load model") && state.modelPath[0] != '\0') requests.loadModel = std::string(state.modelPath);
    if (settings.kind == SceneKind::Model && !settings.modelPath.empty()) {
        ImGui::InputText("##export", state.exportPath, sizeof state.exportPath);
        ImGui::SameLine();
        if (ImGui::Button("Export glTF")) requests.exportModel = std::string(state.exportPath);
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("A copy of the model with the material sliders' factors (.glb or .gltf)");
    }
    drawStatus(state.sceneStatus);
}

void drawViewPanel(ViewSettings& settings)
{
    if (!ImGui::CollapsingHeader("View")) return;
    const std::array modes{ViewMode::Final, ViewMode::PrefilterMips, ViewMode::Lut, ViewMode::Furnace, ViewMode::Irradiance, ViewMode::Error};
    enumCombo("View", settings.mode, modes, viewModeName);
    const std::array backgrounds{BackgroundMode::Environment, BackgroundMode::Irradiance, BackgroundMode::PrefilterMip, BackgroundMode::SolidColour};
    enumCombo("Background", settings.background, backgrounds, backgroundModeName);
    if (settings.background == BackgroundMode::PrefilterMip) ImGui::SliderInt("Mip", &settings.backgroundMip, 0, 8);
    if (settings.background == BackgroundMode::SolidColour) ImGui::ColorEdit3("Colour", &settings.solidColour.x, ImGuiColorEditFlags_Float);
}

void drawPresetPanel(PanelState& state, UiRequests& requests)
{
    if (!ImGui::CollapsingHeader("Preset")) return;
    ImGui::InputText("##preset", state.presetPath, sizeof state.presetPath);
    ImGui::SameLine();
    if (ImGui::Button("Save")) requests.savePreset = std::string(state.presetPath);
    ImGui::SameLine();
    if (ImGui::Button("Load##preset")) requests.loadPreset = std::string(state.presetPath);
    drawStatus(state.presetStatus);
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
    if (stats.resolutionScale < 1.0f) {
        ImGui::SameLine();
        ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.3f, 1.0f), " %.0f%% res", 100.0f * stats.resolutionScale);
    } else if (stats.accumulatedFrames > 1) {
        ImGui::SameLine();
        ImGui::TextDisabled(" x%d", stats.accumulatedFrames);
    }
    ImGui::TextDisabled("%s", stats.renderer.c_str());
}

// Overlays are drawn in the view's pixels (y up, as the renderer reports them), placed at
// viewOrigin (top-left of the view in window coordinates, y down).
void drawDebugOverlay(const std::vector<DebugTile>& tiles, bool axes, glm::vec2 viewOrigin, float viewHeight, const std::string& probeText)
{
    ImDrawList* draw = ImGui::GetBackgroundDrawList();
    const ImU32 text = IM_COL32(230, 230, 230, 255);
    for (const DebugTile& tile : tiles) {
        const float left = viewOrigin.x + tile.rect.x, right = viewOrigin.x + tile.rect.z;
        const float top = viewOrigin.y + viewHeight - tile.rect.w, bottom = viewOrigin.y + viewHeight - tile.rect.y;
        draw->AddText(ImVec2(left, top - 18.0f), text, tile.label.c_str());
        if (!axes) continue;
        // Unit axes on both edges: x = n.v along the bottom, y = roughness up the left side.
        for (int i = 0; i <= 4; ++i) {
            const float t = float(i) / 4.0f;
            char value[8];
            std::snprintf(value, sizeof value, "%.2f", t);
            const float x = left + t * (right - left), y = bottom - t * (bottom - top);
            draw->AddLine(ImVec2(x, bottom), ImVec2(x, bottom + 5.0f), text);
            draw->AddText(ImVec2(x - 12.0f, bottom + 6.0f), text, value);
            draw->AddLine(ImVec2(left - 5.0f, y), ImVec2(left, y), text);
            draw->AddText(ImVec2(left - 40.0f, y - 7.0f), text, value);
        }
    }
    if (!probeText.empty() && !ImGui::GetIO().WantCaptureMouse) ImGui::SetTooltip("%s", probeText.c_str());
}

void drawSceneLabels(const std::vector<ScreenLabel>& labels, glm::vec2 viewOrigin, float viewHeight)
{
    ImDrawList* draw = ImGui::GetBackgroundDrawList();
    for (const ScreenLabel& label : labels) {
        const ImVec2 size = ImGui::CalcTextSize(label.text.c_str());
        const ImU32 colour = label.title ? IM_COL32(255, 255, 255, 255) : IM_COL32(210, 210, 210, 230);
        draw->AddText(ImVec2(viewOrigin.x + label.pixel.x - size.x * 0.5f, viewOrigin.y + viewHeight - label.pixel.y - size.y * 0.5f), colour,
                      label.text.c_str());
    }
}

void drawSphereReadings(const std::vector<SphereReading>& readings, glm::vec2 viewOrigin, float viewHeight)
{
    ImDrawList* draw = ImGui::GetBackgroundDrawList();
    for (const SphereReading& r : readings) {
        char text[32];
        std::snprintf(text, sizeof text, "%.3f", 0.2126f * r.radiance.r + 0.7152f * r.radiance.g + 0.0722f * r.radiance.b);
        const ImVec2 size = ImGui::CalcTextSize(text);
        const ImVec2 at(viewOrigin.x + r.pixel.x - size.x * 0.5f, viewOrigin.y + viewHeight - r.pixel.y - size.y * 0.5f);
        draw->AddRectFilled(ImVec2(at.x - 2, at.y - 1), ImVec2(at.x + size.x + 2, at.y + size.y + 1), IM_COL32(0, 0, 0, 160));
        draw->AddText(at, IM_COL32(255, 255, 255, 255), text);
    }
}

void drawErrorLegend(const ViewSettings& view, glm::vec2 viewOrigin, glm::vec2 viewSize)
{
    ImDrawList* draw = ImGui::GetBackgroundDrawList();
    constexpr float kBarWidth = 220.0f, kBarHeight = 14.0f, kMargin = 16.0f;
    constexpr int kSteps = 64;
    const ImVec2 origin(viewOrigin.x + viewSize.x - kBarWidth - kMargin - 12.0f, viewOrigin.y + viewSize.y - kBarHeight - kMargin - 22.0f);
    draw->AddRectFilled(ImVec2(origin.x - 10.0f, origin.y - 22.0f), ImVec2(origin.x + kBarWidth + 14.0f, origin.y + kBarHeight + 22.0f),
                        IM_COL32(0, 0, 0, 170), 4.0f);
    for (int i = 0; i < kSteps; ++i) {
        // The very map the error view's shader draws (error_metrics.glsl, compiled as C++).
        const glm::vec3 c = falseColour((float(i) + 0.5f) / float(kSteps));
        const float x0 = origin.x + kBarWidth * float(i) / float(kSteps), x1 = origin.x + kBarWidth * float(i + 1) / float(kSteps);
        draw->AddRectFilled(ImVec2(x0, origin.y), ImVec2(x1, origin.y + kBarHeight), ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, 1.0f)));
    }
    const ImU32 text = IM_COL32(235, 235, 235, 255);
    for (int i = 0; i <= 4; ++i) {
        const float t = float(i) / 4.0f;
        char label[16];
        std::snprintf(label, sizeof label, "%.3g", double(t * view.errorScale));
        const float x = origin.x + t * kBarWidth;
        draw->AddLine(ImVec2(x, origin.y + kBarHeight), ImVec2(x, origin.y + kBarHeight + 4.0f), text);
        draw->AddText(ImVec2(x - ImGui::CalcTextSize(label).x * 0.5f, origin.y + kBarHeight + 4.0f), text, label);
    }
    const std::string title = std::string("relative error, ") + (view.errorSpace == ErrorSpace::Linear ? "linear HDR" : "display");
    draw->AddText(ImVec2(origin.x, origin.y - 18.0f), text, title.c_str());
}

void drawReferenceProgress(const ReferenceStatus& status, glm::vec2 viewOrigin, glm::vec2 viewSize)
{
    char text[128];
    std::snprintf(text, sizeof text, "reference %.0f%% (%dx%d texels): showing the frame until it completes", 100.0 * status.progress,
                  status.environmentWidth, status.environmentHeight);
    const ImVec2 size = ImGui::CalcTextSize(text);
    const ImVec2 at(viewOrigin.x + (viewSize.x - size.x) * 0.5f, viewOrigin.y + 12.0f);
    ImDrawList* draw = ImGui::GetBackgroundDrawList();
    draw->AddRectFilled(ImVec2(at.x - 6, at.y - 3), ImVec2(at.x + size.x + 6, at.y + size.y + 3), IM_COL32(0, 0, 0, 170), 4.0f);
    draw->AddText(at, IM_COL32(255, 220, 120, 255), text);
}

void drawSplitDivider(const FrameSettings& settings, int column, glm::vec2 viewOrigin, glm::vec2 viewSize)
{
    ImDrawList* draw = ImGui::GetBackgroundDrawList();
    const float x = viewOrigin.x + float(column);
    draw->AddLine(ImVec2(x, viewOrigin.y), ImVec2(x, viewOrigin.y + viewSize.y), IM_COL32(0, 0, 0, 200), 3.0f);
    draw->AddLine(ImVec2(x, viewOrigin.y), ImVec2(x, viewOrigin.y + viewSize.y), IM_COL32(255, 255, 255, 230), 1.0f);
    const std::string a = "A: " + samplingSummary(settings.sampling);
    const std::string b = "B: " + samplingSummary(settings.view.compare);
    const ImU32 background = IM_COL32(0, 0, 0, 170), text = IM_COL32(255, 255, 255, 255);
    const ImVec2 aSize = ImGui::CalcTextSize(a.c_str()), bSize = ImGui::CalcTextSize(b.c_str());
    // Each label beside the divider on its own side, but kept inside the view; when the
    // divider is so near an edge that they would overlap, B moves one line down.
    const float top = viewOrigin.y + 36.0f;
    const float aX = std::max(x - aSize.x - 10.0f, viewOrigin.x + 6.0f);
    const float bX = std::min(x + 10.0f, viewOrigin.x + viewSize.x - bSize.x - 6.0f);
    const bool overlap = aX + aSize.x + 8.0f > bX;
    const ImVec2 aAt(aX, top), bAt(bX, overlap ? top + aSize.y + 8.0f : top);
    draw->AddRectFilled(ImVec2(aAt.x - 4, aAt.y - 2), ImVec2(aAt.x + aSize.x + 4, aAt.y + aSize.y + 2), background, 3.0f);
    draw->AddText(aAt, text, a.c_str());
    draw->AddRectFilled(ImVec2(bAt.x - 4, bAt.y - 2), ImVec2(bAt.x + bSize.x + 4, bAt.y + bSize.y + 2), background, 3.0f);
    draw->AddText(bAt, text, b.c_str());
}

void drawStudyPanel(PanelState& state, UiRequests& requests)
{
    if (!ImGui::CollapsingHeader("Study")) return;
    StudyState& study = state.study;
    ImGui::TextWrapped("Speed against accuracy on the current environment and scene: the quick sweep of `iblab bench` (split-sum prefilter "
                       "samples, runtime N, diffuse sources), each point baked, timed and compared with the reference.");
    if (!study.running) {
        if (ImGui::Button("Run quick sweep")) requests.startStudy = true;
        if (!study.charts.empty() && !study.chartOpen) {
            ImGui::SameLine();
            if (ImGui::Button("Show chart")) study.chartOpen = true;
        }
    } else {
        if (ImGui::Button("Stop")) requests.stopStudy = true;
        ImGui::SameLine();
        ImGui::ProgressBar(study.progress, ImVec2(-1.0f, 0.0f));
        ImGui::TextDisabled("%s", study.activity.c_str());
    }
    drawStatus(study.status);

    ImGui::Separator();
    ImGui::TextUnformatted("Auto quality");
    AutoQualityState& autoQuality = study.autoQuality;
    ImGui::TextWrapped("The cheapest settings whose 99th-percentile error after tone mapping stays within the target, measured on this "
                       "environment and scene.");
    ImGui::SliderFloat("Target", &autoQuality.targetSteps, 0.25f, 64.0f, "p99 %.2f 8-bit steps", ImGuiSliderFlags_Logarithmic);
    ImGui::BeginDisabled(study.running);
    if (ImGui::Button("Choose")) requests.startAutoQuality = true;
    ImGui::EndDisabled();
    if (autoQuality.haveChoice) {
        ImGui::SameLine();
        ImGui::BeginDisabled(study.running);
        if (ImGui::Button("Apply")) requests.applyAutoQuality = true;
        ImGui::EndDisabled();
        if (autoQuality.meetsTarget) ImGui::TextColored(ImVec4(0.5f, 0.9f, 0.5f, 1.0f), "Chosen (within the target):");
        else ImGui::TextColored(ImVec4(1.0f, 0.6f, 0.3f, 1.0f), "Target out of reach; the most accurate:");
        ImGui::TextWrapped("%s", autoQuality.chosen.c_str());
        ImGui::TextWrapped("%s", autoQuality.numbers.c_str());
        ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
        for (const std::string& preset : autoQuality.presets) ImGui::TextWrapped("%s", preset.c_str());
        ImGui::PopStyleColor();
        if (ImGui::TreeNodeEx("Why", ImGuiTreeNodeFlags_DefaultOpen)) {
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
    if (!ImGui::Begin("Study: speed against accuracy", &study.chartOpen)) {
        ImGui::End();
        return;
    }
    for (std::size_t i = 0; i < study.charts.size(); ++i) {
        const ParetoChart& chart = study.charts[i];
        const ImVec2 size(std::max(ImGui::GetContentRegionAvail().x, 420.0f), std::max(ImGui::GetContentRegionAvail().y, 260.0f));
        const ImVec2 origin = ImGui::GetCursorScreenPos();
        ImGui::PushID(int(i));
        ImGui::InvisibleButton("##chart", size);
        const bool hovered = ImGui::IsItemHovered();
        ImGui::PopID();
        const ChartHover hover = drawParetoChart(*ImGui::GetWindowDrawList(), chart, origin, size,
                                                 hovered ? std::optional<ImVec2>(ImGui::GetIO().MousePos) : std::nullopt);
        if (hover.valid()) ImGui::SetTooltip("%s", chart.series[std::size_t(hover.series)].points[std::size_t(hover.point)].tooltip.c_str());
    }
    ImGui::End();
}

void drawControlWindow(FrameSettings& settings, PanelState& state, const FrameStats& stats, UiRequests& requests)
{
    if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Tab)) && !ImGui::GetIO().WantTextInput) state.showPanels = !state.showPanels;
    if (!state.showPanels) return;
    // Docked at the left, full height; only its width is the user's to drag.
    ImGui::SetNextWindowPos(ImVec2(0, 0));
    ImGui::SetNextWindowSize(ImVec2(state.panelWidth, ImGui::GetIO().DisplaySize.y));
    ImGui::SetNextWindowSizeConstraints(ImVec2(260, ImGui::GetIO().DisplaySize.y), ImVec2(900, ImGui::GetIO().DisplaySize.y));
    ImGui::Begin("iblab", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoTitleBar);
    state.panelWidth = ImGui::GetWindowWidth();
    drawStatsOverlay(stats);
    drawEnvironmentPanel(settings.environment, state, requests);
    drawScenePanel(settings.scene, state, requests);
    drawMaterialPanel(settings.material, settings.scene);
    drawSamplingPanel(settings.sampling);
    drawConventionPanel(state, requests);
    drawToneMapPanel(settings.toneMap);
    drawViewPanel(settings.view);
    drawComparePanel(settings.view, settings.sampling, state.compare, smoothestRoughness(settings));
    drawCameraPanel(settings.camera, requests);
    drawCapturePanel(state, requests);
    drawPresetPanel(state, requests);
    drawStudyPanel(state, requests);
    ImGui::End();
    drawStudyChartWindow(state.study);
}

} // namespace iblab::ui
