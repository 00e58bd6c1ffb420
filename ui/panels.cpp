#include "ui/panels.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>

#include <imgui.h>

#include "frame/conventions.hpp"
#include "ibl/error_metrics.hpp"
#include "ibl/tonemap.hpp"
#include "ui/field_widgets.hpp"
#include "ui/help_window.hpp"
#include "ui/overlays.hpp"
#include "ui/status_area.hpp"
#include "ui/widgets.hpp"

namespace iblab::ui {
namespace {

// A warning in amber, wrapped at the panel's edge.
void drawWarning(const char* text)
{
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.75f, 0.3f, 1.0f));
    ImGui::TextWrapped("%s", text);
    ImGui::PopStyleColor();
}

// A path field and the button beside it: Enter in the field does what the button does. The
// typed path, when either asks for it (an empty field asks for nothing).
std::optional<std::string> pathField(const char* id, const char* hint, char* path, std::size_t size, const char* buttonLabel)
{
    const bool entered = inputTextWithHint(id, hint, path, size, ImGuiInputTextFlags_EnterReturnsTrue);
    ImGui::SameLine();
    const bool clicked = button(buttonLabel);
    if ((entered || clicked) && path[0] != '\0') return std::string(path);
    return std::nullopt;
}

// The live curve: displayed value (after sRGB encoding, what lands on screen) against
// scene luminance in stops around mid grey, evaluated by the very function the shader
// runs. Drawn by hand for the numbered axes, the mid-grey marker and the hover readout.
void drawToneCurve(const ToneMapSettings& settings)
{
    constexpr float kMinStops = -8.0f, kMaxStops = 8.0f, kMidGrey = 0.18f;
    const float lineHeight = ImGui::GetTextLineHeight();
    const float axisWidth = ImGui::CalcTextSize("0.75").x + 6.0f; // the y axis' numbers
    const ImVec2 size(ImGui::GetContentRegionAvail().x, 130.0f + lineHeight);
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    canvas("##tonecurve", size, "canvas");
    ImDrawList* draw = ImGui::GetWindowDrawList();
    const ImVec2 plot0(origin.x + axisWidth, origin.y + 2.0f), plot1(origin.x + size.x - 4.0f, origin.y + size.y - lineHeight - 4.0f);
    draw->AddRectFilled(plot0, plot1, ImGui::GetColorU32(ImGuiCol_FrameBg));
    auto toScreen = [&](float stops, float value) {
        return ImVec2(plot0.x + (stops - kMinStops) / (kMaxStops - kMinStops) * (plot1.x - plot0.x), plot1.y - value * (plot1.y - plot0.y));
    };
    const ImU32 gridColour = ImGui::GetColorU32(ImGuiCol_Border), labelColour = ImGui::GetColorU32(ImGuiCol_TextDisabled);
    for (float stops = kMinStops; stops <= kMaxStops; stops += 2.0f) {
        draw->AddLine(toScreen(stops, 0.0f), toScreen(stops, 1.0f), gridColour);
        if (int(stops) % 4 != 0) continue;
        char label[8];
        std::snprintf(label, sizeof label, "%+.0f", stops);
        const ImVec2 at = toScreen(stops, 0.0f);
        draw->AddText(ImVec2(at.x - 0.5f * ImGui::CalcTextSize(label).x, at.y + 2.0f), labelColour, stops == 0.0f ? "0" : label);
    }
    for (float value : {0.0f, 0.25f, 0.5f, 0.75f, 1.0f}) {
        draw->AddLine(toScreen(kMinStops, value), toScreen(kMaxStops, value), gridColour);
        char label[16];
        std::snprintf(label, sizeof label, "%g", value);
        const ImVec2 at = toScreen(kMinStops, value);
        draw->AddText(ImVec2(origin.x + axisWidth - 4.0f - ImGui::CalcTextSize(label).x, at.y - 0.5f * lineHeight), labelColour, label);
    }
    draw->AddLine(toScreen(0.0f, 0.0f), toScreen(0.0f, 1.0f), labelColour, 2.0f);

    auto displayed = [&](float stops) { return displayEncode(glm::vec3(kMidGrey * std::exp2(stops)), settings.exposureEv, settings.op).g; };
    constexpr int kPoints = 160;
    ImVec2 points[kPoints];
    for (int i = 0; i < kPoints; ++i) {
        const float stops = kMinStops + (kMaxStops - kMinStops) * float(i) / float(kPoints - 1);
        points[i] = toScreen(stops, displayed(stops));
    }
    draw->AddPolyline(points, kPoints, ImGui::GetColorU32(ImGuiCol_PlotLines), ImDrawFlags_None, 2.0f);
    if (ImGui::IsItemHovered()) {
        const float stops = std::clamp(kMinStops + (ImGui::GetIO().MousePos.x - plot0.x) / (plot1.x - plot0.x) * (kMaxStops - kMinStops), kMinStops, kMaxStops);
        draw->AddCircleFilled(toScreen(stops, displayed(stops)), 4.0f, ImGui::GetColorU32(ImGuiCol_PlotLinesHovered));
        ImGui::SetTooltip("scene %.4g (%+.1f stops from mid grey) -> display %.3f (8-bit %d)", kMidGrey * std::exp2(stops), stops,
                          displayed(stops), int(displayed(stops) * 255.0f + 0.5f));
    }
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("x: scene luminance in stops from mid grey (0.18); y: display value after sRGB encoding; line at mid grey");
    ImGui::PopStyleColor();
}

std::string displayName(const std::string& source)
{
    if (source.rfind("builtin:", 0) == 0) return source;
    return std::filesystem::path(source).filename().string();
}

} // namespace

std::string StatusLine::joined() const
{
    std::string all = text;
    for (const std::string& note : notes) all += (all.empty() ? "" : "; ") + note;
    return all;
}

namespace {

void tooltip(const char* text)
{
    if (tooltipWanted()) ImGui::SetTooltip("%s", text);
}

} // namespace

void drawEnvironmentPanel(EnvironmentSettings& settings, PanelState& state, UiRequests& requests)
{
    Section section("Environment", true);
    if (!section) return;
    // Tall enough for the bundled maps and every builtin without scrolling. Its entries are
    // the catalogue's (a choice is a load request), its label and tooltip the setting's.
    const auto& sourceRow = settingRow<&EnvironmentSettings::source>();
    if (Combo combo(fieldLabel(sourceRow).c_str(), displayName(settings.source).c_str(), ImGuiComboFlags_HeightLargest); combo) {
        ImGui::TextDisabled("Bundled (CC0)");
        for (const auto& path : state.catalog.gallery)
            if (combo.entry(displayName(path).c_str(), path == settings.source)) requests.loadEnvironment = path;
        ImGui::Separator();
        ImGui::TextDisabled("Procedural");
        for (const auto& name : state.catalog.builtins)
            if (combo.entry(name.c_str(), name == settings.source)) requests.loadEnvironment = name;
    }
    noteField(sourceRow, "combo");
    fieldTooltip(sourceRow.help);
    if (auto path = pathField("##envpath", "map or bake path, or builtin:NAME", state.environmentPath, sizeof state.environmentPath, "Load"))
        requests.loadEnvironment = std::move(*path);
    fieldSlider<&EnvironmentSettings::yawDegrees>(settings);
    fieldSlider<&EnvironmentSettings::intensityEv>(settings);
    static const char* const engines[] = {"filament", "khronos", "bevy"};
    ImGui::SetNextItemWidth(90.0f);
    if (Combo combo("##engine", engines[state.bakeExportFormat]); combo)
        for (int i = 0; i < 3; ++i)
            if (combo.entry(engines[i], i == state.bakeExportFormat)) state.bakeExportFormat = i;
    ImGui::SameLine();
    inputText("##bakeexport", state.bakeExportPath, sizeof state.bakeExportPath);
    ImGui::SameLine();
    if (button("Export")) requests.exportBake = engines[state.bakeExportFormat];
    tooltip("Write the current bake as that engine loads it into the directory (docs/engine-export.md)");
    // The map's line and notes, the load or bake under way, the bake's line.
    drawStatusArea("##environment status", {&state.environmentStatus, &state.bakeStatus}, 6, &state.activity);
}

void drawToneMapPanel(ToneMapSettings& settings)
{
    Section section("Tone mapping", true);
    if (!section) return;
    fieldCombo<&ToneMapSettings::op>(settings, allToneMapOperators(), toneMapOperatorLabel);
    fieldSlider<&ToneMapSettings::exposureEv>(settings);
    ImGui::SameLine();
    if (smallButton("0")) settings.exposureEv = 0.0f;
    tooltip("Exposure back to 0 EV");
    drawToneCurve(settings);
}

void drawCameraPanel(CameraSettings& settings, UiRequests& requests)
{
    Section section("Camera");
    if (!section) return;
    fieldSlider<&CameraSettings::yawDegrees>(settings);
    fieldSlider<&CameraSettings::pitchDegrees>(settings);
    fieldSlider<&CameraSettings::fovDegrees>(settings);
    fieldSlider<&CameraSettings::distance>(settings);
    if (button("Frame")) requests.frameScene = true;
    tooltip("Fit the scene in the view (F, or double-click the view)");
    ImGui::SameLine();
    if (button("Reset")) requests.resetCamera = true;
    tooltip("Default orientation and field of view, then frame (R or Home)");
    ImGui::SameLine();
    if (button("Front")) requests.axisView = CameraAxisView::Front;
    tooltip("Look down -Z (1)");
    ImGui::SameLine();
    if (button("Side")) requests.axisView = CameraAxisView::Side;
    tooltip("Look down -X (3)");
    ImGui::SameLine();
    if (button("Top")) requests.axisView = CameraAxisView::Top;
    tooltip("Look down -Y (7)");
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("Left drag: orbit. Right or middle drag, or Shift + left drag: pan. Wheel: zoom. Double-click: frame.");
    ImGui::PopStyleColor();
}

void drawMaterialPanel(MaterialSettings& settings, const SceneSettings& scene)
{
    Section section("Material", true);
    if (!section) return;
    using M = MaterialSettings;
    if (scene.kind == SceneKind::Model) fieldCheckbox<&M::overrideModel>(settings);
    fieldColour<&M::baseColor>(settings);
    if (scene.kind == SceneKind::Grid) ImGui::TextDisabled("The grid sets metallic (rows) and roughness (columns).");
    fieldSlider<&M::metallic>(settings);
    fieldSlider<&M::roughness>(settings);
    fieldSlider<&M::ambientOcclusion>(settings);
    fieldSlider<&M::specular>(settings);
}

namespace {

// The reference map's widths the Compare panel offers.
constexpr std::array kReferenceWidths{32, 64, 128, 256, 512};

// "reference 37% (256x128)": how far the reference is, over the bar that shows it.
std::string referenceProgressText(const ReferenceStatus& r)
{
    char text[96];
    std::snprintf(text, sizeof text, "reference %.0f%% (%dx%d)", 100.0 * r.progress, r.environmentWidth, r.environmentHeight);
    return text;
}

// The estimator's controls; the frame's own (A) and the split view's B use the same.
// `reference`: the status of the reference the frame shows, for the reference method's bar.
void drawSamplingControls(SamplingSettings& settings, bool exactCountForced, const ReferenceStatus& reference)
{
    using S = SamplingSettings;
    fieldCombo<&S::method>(settings);
    if (settings.method == ShadingMethod::Reference) {
        if (reference.current) progressBar("Reference progress", reference.progress, referenceProgressText(reference).c_str());
        // Wrapped and greyed: the panel is narrower than the sentence.
        ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
        ImGui::TextWrapped("%s", reference.complete ? "The full integral over the map's texels (Compare: reference map)"
                                                    : "Tiles show the full integral as they finish, the split sum until then");
        ImGui::PopStyleColor();
    }
    if (settings.method == ShadingMethod::Sampled) {
        // N is counted in ones for the N = 1..k check: typed (Ctrl+click), stepped with the
        // buttons or the +/- keys, or dragged on a logarithmic scale.
        const float stepWidth = ImGui::GetFrameHeight();
        ImGui::SetNextItemWidth(ImGui::CalcItemWidth() - 2.0f * (stepWidth + ImGui::GetStyle().ItemInnerSpacing.x));
        fieldSlider<&S::samples>(settings, ImGuiSliderFlags_AlwaysClamp, /*hideLabel=*/true);
        ImGui::SameLine(0.0f, ImGui::GetStyle().ItemInnerSpacing.x);
        if (button("-", ImVec2(stepWidth, 0.0f))) settings.samples = std::max(1, settings.samples - 1);
        ImGui::SameLine(0.0f, ImGui::GetStyle().ItemInnerSpacing.x);
        if (button("+", ImVec2(stepWidth, 0.0f))) settings.samples = std::min(kMaxSampleCount, settings.samples + 1);
        ImGui::SameLine(0.0f, ImGui::GetStyle().ItemInnerSpacing.x);
        ImGui::TextUnformatted("N samples");
        // Shown on and locked where the scene keeps exactly N whatever the setting says.
        const auto& freezeRow = settingRow<&S::freezeSampleSet>();
        bool frozen = settings.freezeSampleSet || exactCountForced;
        ImGui::BeginDisabled(exactCountForced);
        if (checkbox(fieldLabel(freezeRow).c_str(), &frozen)) settings.freezeSampleSet = frozen;
        noteField(freezeRow, "checkbox");
        ImGui::EndDisabled();
        if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
            ImGui::SetTooltip("%s", exactCountForced ? "The counting strip always keeps exactly N samples per pixel" : std::string(freezeRow.help).c_str());
        fieldCheckbox<&S::pdfMipFiltering>(settings);
        if (settings.pdfMipFiltering) fieldSlider<&S::mipBias>(settings);
        fieldCheckbox<&S::cosineSampledDiffuse>(settings);
        fieldCheckbox<&S::normalizeByAccepted>(settings);
    }
    // The reference reads no mip and no baked diffuse: of these it shares only the BRDF
    // (geometry term, energy compensation).
    if (settings.method != ShadingMethod::Reference) {
        // Auto is the forced mip's special value, -1 (its row's range says so).
        const auto& forcedRow = settingRow<&S::forcedMip>();
        bool automatic = settings.forcedMip < 0;
        if (checkbox("Auto mip", &automatic)) settings.forcedMip = automatic ? -1 : 0;
        noteField(forcedRow, "checkbox");
        fieldTooltip(forcedRow.range.specialMeaning);
        if (!automatic) fieldSlider<&S::forcedMip>(settings);
    }
    fieldCombo<&S::geometry>(settings);
    if (settings.method != ShadingMethod::Reference) fieldCombo<&S::diffuse>(settings);
    fieldCheckbox<&S::multiscatter>(settings);
    if (settings.multiscatter) fieldCombo<&S::multiscatterModel>(settings);
    if (settings.method == ShadingMethod::FittedLobe) fieldCheckbox<&S::shadingLights>(settings);
    if (readsPrefilteredCube(settings.method)) fieldCheckbox<&S::roughFresnelOnLut>(settings);
    if (settings.method == ShadingMethod::SplitSum) fieldCombo<&S::specularDirection>(settings);
}

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

// The error view's numbers for one side. Without metrics (being computed) the rows stay,
// each with "...": the table vanishing for those frames made the panel shorter, and a panel
// scrolled to its end (where the Compare section usually is) jumped under the mouse after
// every change and stayed moved.
void drawMetricsTable(const char* id, const ErrorMetrics* metrics)
{
    if (!ImGui::BeginTable(id, 2, ImGuiTableFlags_SizingStretchProp)) return;
    auto row = [pending = metrics == nullptr](const char* name, const char* format, double value) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(name);
        ImGui::TableNextColumn();
        if (pending)
            ImGui::TextDisabled("...");
        else
            ImGui::Text(format, value);
    };
    const ErrorMetrics m = metrics ? *metrics : ErrorMetrics{};
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
    Section section("Conventions");
    if (!section) return;
    ImGui::TextWrapped("Bake and shade as another viewer does; the Compare section's A/B split and error view show what it changes.");
    for (const ConventionPreset& convention : conventionPresets()) {
        const bool current = state.convention == convention.name;
        if (radioButton(std::string(convention.title).c_str(), current) && !current) requests.applyConvention = std::string(convention.name);
        if (ImGui::IsItemHovered()) {
            ImGui::BeginTooltip();
            for (const auto& [aspect, choice] : conventionChoices(convention)) ImGui::Text("%-20s %s", aspect.c_str(), choice.c_str());
            ImGui::EndTooltip();
        }
    }
}

void drawSamplingPanel(SamplingSettings& settings, bool exactCountForced, const ReferenceStatus& reference)
{
    Section section("Sampling", true);
    if (!section) return;
    drawSamplingControls(settings, exactCountForced, reference);
}

void drawComparePanel(ViewSettings& view, const SamplingSettings& frameSampling, const CompareState& state, std::optional<float> sceneMinRoughness)
{
    Section section("Compare");
    if (!section) return;
    // A shortcut to one value of the view mode (the View panel's combo has them all).
    bool errorView = view.mode == ViewMode::Error;
    if (checkbox("Error against the reference", &errorView)) view.mode = errorView ? ViewMode::Error : ViewMode::Final;
    noteField(settingRow<&ViewSettings::mode>(), "checkbox");
    tooltip("The full integral over the environment's texels: no split sum, no N = V = R");
    if (errorView) {
        fieldCombo<&ViewSettings::errorSpace>(view);
        fieldSlider<&ViewSettings::errorScale>(view);
    }
    // The reference's map and progress, for the error view and for the reference method.
    const bool referenceMethod = frameSampling.method == ShadingMethod::Reference || (view.split && view.compare.method == ShadingMethod::Reference);
    if (errorView || referenceMethod) {
        // The widths worth a choice, inside the row's range (tests/cpu/panel_fields_test.cpp).
        const auto& widthRow = settingRow<&ViewSettings::referenceWidth>();
        if (Combo combo(fieldLabel(widthRow).c_str(), (std::to_string(view.referenceWidth) + " x " + std::to_string(view.referenceWidth / 2)).c_str());
            combo)
            for (int w : kReferenceWidths)
                if (combo.entry((std::to_string(w) + " x " + std::to_string(w / 2)).c_str(), w == view.referenceWidth)) view.referenceWidth = w;
        noteField(widthRow, "combo", kReferenceWidths.front(), kReferenceWidths.back());
        fieldTooltip(widthRow.help);
        const ReferenceStatus& r = state.reference;
        if (r.current) {
            progressBar("Reference progress", r.progress, referenceProgressText(r).c_str());
            ImGui::TextDisabled("texel %.2f deg: converged for roughness >= %.2f", r.texelDegrees, r.minResolvedRoughness);
            if (sceneMinRoughness && *sceneMinRoughness < r.minResolvedRoughness) {
                char warning[256];
                std::snprintf(warning, sizeof warning,
                              "Roughness %.2f is below that: there the reference shows the map's texels, not the converged integral "
                              "(and the heatmap measures them, not the method). Use a wider reference map.",
                              *sceneMinRoughness);
                drawWarning(warning);
            }
        }
    }
    if (errorView) {
        ImGui::TextUnformatted(view.split ? "A (left)" : "Frame");
        drawMetricsTable("##errorA", state.error.valid ? &state.error.left : nullptr);
        if (view.split) {
            ImGui::TextUnformatted("B (right)");
            drawMetricsTable("##errorB", state.error.valid && state.error.right ? &*state.error.right : nullptr);
        }
    }
    ImGui::Separator();
    fieldCheckbox<&ViewSettings::split>(view);
    if (!view.split) return;
    fieldSlider<&ViewSettings::splitPosition>(view);
    tooltip("Or drag the line in the view");
    if (button("Copy A's sampling to B")) view.compare = frameSampling;
    ImGui::TextDisabled("B, right of the divider:");
    ImGui::PushID("B");
    itemRegistry().pushScope("B");
    drawSamplingControls(view.compare, false, state.reference);
    itemRegistry().popScope();
    ImGui::PopID();
}

void drawScenePanel(SceneSettings& settings, ShadingMethod method, PanelState& state, UiRequests& requests)
{
    Section section("Scene", true);
    if (!section) return;
    const std::array kinds{SceneKind::Sphere, SceneKind::Grid, SceneKind::Counting, SceneKind::Sweep, SceneKind::Model, SceneKind::None};
    if (fieldCombo<&SceneSettings::kind>(settings, kinds)) requests.sceneChanged = true;
    if (settings.kind == SceneKind::Counting || settings.kind == SceneKind::Sweep) {
        if (fieldSlider<&SceneSettings::countingSpheres>(settings)) requests.sceneChanged = true;
        // Only the sampled method counts samples: under any other every counting sphere is the
        // same, whatever its label says.
        if (settings.kind == SceneKind::Counting) {
            if (button("Set up for counting")) requests.countingSetup = true;
            tooltip("One point light (builtin:lights), the sampled method at mip 0 on a metal, seen close from the front: "
                    "sphere i shows exactly i reflections");
        }
        if (settings.kind == SceneKind::Counting && method != ShadingMethod::Sampled) {
            drawWarning("Only the sampled method counts samples: choose Method sampled to see N = 1..k (try builtin:lights, "
                        "forced mip 0, metallic 1).");
        } else {
            ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
            ImGui::TextWrapped(settings.kind == SceneKind::Counting ? "Sampled method, N = 1..k: try builtin:lights, forced mip 0, metallic 1."
                                                                    : "Sampled method at the Sampling panel's N; try builtin:lights.");
            ImGui::PopStyleColor();
        }
    }
    if (auto path = pathField("##model", ".gltf / .glb path", state.modelPath, sizeof state.modelPath, "Load model"))
        requests.loadModel = std::move(*path);
    if (settings.kind == SceneKind::Model && !settings.modelPath.empty()) {
        inputText("##export", state.exportPath, sizeof state.exportPath);
        ImGui::SameLine();
        if (button("Export glTF")) requests.exportModel = std::string(state.exportPath);
        tooltip("A copy of the model with the material sliders' factors (.glb or .gltf)");
    }
    drawStatusArea("##scene status", {&state.sceneStatus}, 3);
}

void drawViewPanel(ViewSettings& settings)
{
    Section section("View");
    if (!section) return;
    fieldCombo<&ViewSettings::mode>(settings);
    fieldCombo<&ViewSettings::background>(settings);
    if (settings.background == BackgroundMode::PrefilterMip) fieldSlider<&ViewSettings::backgroundMip>(settings);
    if (settings.background == BackgroundMode::SolidColour) fieldColour<&ViewSettings::solidColour>(settings);
}

void drawPresetPanel(PanelState& state, UiRequests& requests)
{
    Section section("Preset");
    if (!section) return;
    inputText("##preset", state.presetPath, sizeof state.presetPath);
    ImGui::SameLine();
    if (button("Save")) requests.savePreset = std::string(state.presetPath);
    tooltip("Ctrl+S");
    ImGui::SameLine();
    if (button("Load")) requests.loadPreset = std::string(state.presetPath);
    if (state.unsavedChanges) {
        ImGui::SameLine();
        ImGui::TextDisabled("unsaved changes");
    }
    drawStatusArea("##preset status", {&state.presetStatus}, 2);
}

void drawCapturePanel(PanelState& state, UiRequests& requests)
{
    Section section("Capture", true);
    if (!section) return;
    inputText("Folder", state.capture.directory, sizeof state.capture.directory);
    inputTextWithHint("File", "automatic: iblab-<map>-<date>-<time>.png", state.capture.file, sizeof state.capture.file);
    if (button("Save screenshot (F12)")) requests.capture = CaptureRequest{state.capture.file};
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped(".png: tone-mapped sRGB; .exr: linear HDR. A capture never replaces a file: a taken name gets -2, -3, ...; F12 names "
                       "it automatically.");
    ImGui::PopStyleColor();
    drawStatusArea("##capture status", {&state.captureStatus}, 2);
}

void drawQuitDialog(PanelState& state, UiRequests& requests)
{
    constexpr const char* kTitle = "Quit iblab?";
    if (state.quitDialog.open && !ImGui::IsPopupOpen(kTitle)) ImGui::OpenPopup(kTitle);
    ImGui::SetNextWindowPos(ImGui::GetMainViewport()->GetCenter(), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
    if (!ImGui::BeginPopupModal(kTitle, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
    itemRegistry().pushScope(kTitle);
    ImGui::TextUnformatted("The settings changed since they were last saved as a preset.");
    if (button("Save preset and quit")) requests.quit = QuitChoice::SaveAndQuit;
    tooltip(state.presetPath);
    ImGui::SameLine();
    if (button("Quit without saving")) requests.quit = QuitChoice::Quit;
    ImGui::SameLine();
    if (button("Cancel") || !state.quitDialog.open) requests.quit = QuitChoice::Cancel;
    if (requests.quit) ImGui::CloseCurrentPopup();
    itemRegistry().popScope();
    ImGui::EndPopup();
}

constexpr float kMinPanelWidth = 260.0f;

void drawControlWindow(FrameSettings& settings, PanelState& state, const FrameStats& stats, UiRequests& requests)
{
    if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Tab)) && !ImGui::GetIO().WantTextInput) state.showPanels = !state.showPanels;
    if (!state.showPanels) return;
    // Docked at the left, full height; only its width is the user's to drag.
    // A small window keeps most of its width for the view: the panel takes at most 45% of it
    // (a fixed 420 px left 220 px of a 640 px window), and its preferred width returns when
    // the window grows again.
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    const float maxWidth = std::min(900.0f, std::max(kMinPanelWidth, 0.45f * display.x));
    const float setWidth = std::clamp(state.preferredPanelWidth, kMinPanelWidth, maxWidth);
    ImGui::SetNextWindowPos(ImVec2(0, 0));
    ImGui::SetNextWindowSize(ImVec2(setWidth, display.y));
    ImGui::SetNextWindowSizeConstraints(ImVec2(kMinPanelWidth, display.y), ImVec2(maxWidth, display.y));
    ImGui::Begin("iblab", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoTitleBar);
    state.panelWidth = ImGui::GetWindowWidth();
    if (state.panelWidth != setWidth) state.preferredPanelWidth = state.panelWidth; // dragged by the user
    // Controls take a little over half the width and their labels the rest, so that labels
    // stay inside the panel at its default width.
    ImGui::PushItemWidth(std::floor(ImGui::GetWindowWidth() * 0.55f));
    if (state.firstRunHint) {
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.85f, 0.4f, 1.0f));
        ImGui::TextWrapped("%s", kFirstRunHint);
        ImGui::PopStyleColor();
        state.hintHeight = ImGui::GetItemRectSize().y;
    } else if (state.hintHeight > 0.0f) {
        // Gone at the user's first click or key: its space stays this session, so that what
        // was clicked does not move up under the mouse.
        ImGui::Dummy(ImVec2(0.0f, state.hintHeight));
    }
    drawStatsOverlay(stats);
    drawEnvironmentPanel(settings.environment, state, requests);
    drawScenePanel(settings.scene, settings.sampling.method, state, requests);
    drawMaterialPanel(settings.material, settings.scene);
    drawSamplingPanel(settings.sampling, sceneDemandsExactSampleCount(settings.scene), state.compare.reference);
    drawConventionPanel(state, requests);
    drawToneMapPanel(settings.toneMap);
    drawViewPanel(settings.view);
    drawComparePanel(settings.view, settings.sampling, state.compare, smoothestRoughness(settings));
    drawCameraPanel(settings.camera, requests);
    drawCapturePanel(state, requests);
    drawPresetPanel(state, requests);
    drawStudyPanel(state, requests);
    ImGui::PopItemWidth();
    ImGui::End();
    drawStudyChartWindow(state.study);
}

} // namespace iblab::ui
