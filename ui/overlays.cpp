#include "ui/overlays.hpp"

#include <algorithm>
#include <cstdio>
#include <string>

#include <imgui.h>

#include "ibl/error_metrics.hpp"
#include "ibl/luminance.hpp"
#include "ui/widgets.hpp"

namespace iblab::ui {

namespace {

std::vector<OverlayText>& texts()
{
    static std::vector<OverlayText> drawn;
    return drawn;
}

void addText(ImDrawList* draw, ImVec2 at, ImU32 colour, const char* text)
{
    draw->AddText(at, colour, text);
    const ImVec2 size = ImGui::CalcTextSize(text);
    texts().push_back({text, at.x, at.y, at.x + size.x, at.y + size.y});
}

} // namespace

const std::vector<OverlayText>& overlayTexts() { return texts(); }
void clearOverlayTexts() { texts().clear(); }
namespace {

std::string samplingSummary(const SamplingSettings& s)
{
    std::string text(enumName(s.method));
    if (s.method == ShadingMethod::Sampled) text += " N=" + std::to_string(s.samples) + (s.pdfMipFiltering ? "" : " mip0");
    if (s.forcedMip >= 0) text += " mip " + std::to_string(s.forcedMip);
    text += ", " + std::string(enumName(s.geometry));
    if (s.multiscatter) text += s.multiscatterModel == MultiscatterModel::FdezAguera ? ", ms fdez-aguera" : ", ms";
    if (s.roughFresnelOnLut && readsPrefilteredCube(s.method)) text += ", F_r on LUT";
    if (s.specularDirection != SpecularDirection::Reflection && s.method == ShadingMethod::SplitSum) text += ", " + std::string(enumName(s.specularDirection)) + " dir";
    return text;
}

} // namespace

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
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("%s", stats.renderer.c_str());
    ImGui::PopStyleColor();
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
        // A title wider than its tile ran into the next tile's or past the view's edge (both
        // LUT titles in a view under about 350 px): such a tile shows its short title.
        const bool fits = ImGui::CalcTextSize(tile.label.c_str()).x <= right - left;
        addText(draw, ImVec2(left, top - 18.0f), text, (fits ? tile.label : tile.shortLabel).c_str());
        if (!axes) continue;
        // Unit axes on both edges: x = n.v along the bottom, y = roughness up the left side.
        // Every tick is drawn, but a small tile labels only every second one (or the ends),
        // as far apart as the labels need: five of them ran into each other under ~150 px.
        // An end label is aligned to its tick's outer side and the next one centred on its
        // tick, so two ticks carry both labels when they are 1.5 labels apart (plus a gap).
        const float labelWidth = 1.5f * ImGui::CalcTextSize("0.00").x + 6.0f, labelHeight = 1.5f * ImGui::GetTextLineHeight() + 4.0f;
        const auto labelStep = [](float span, float need) { return span / 4.0f >= need ? 1 : span / 2.0f >= need ? 2 : 4; };
        const int xStep = labelStep(right - left, labelWidth), yStep = labelStep(bottom - top, labelHeight);
        for (int i = 0; i <= 4; ++i) {
            const float t = float(i) / 4.0f;
            char value[8];
            std::snprintf(value, sizeof value, "%.2f", t);
            const float x = left + t * (right - left), y = bottom - t * (bottom - top);
            // The end labels stay within the tile's span: centred on its tick, the last x label
            // reached past the view's right edge and the top y label into the tile's title.
            const ImVec2 size = ImGui::CalcTextSize(value);
            const float labelX = i == 0 ? x : i == 4 ? x - size.x : x - 0.5f * size.x;
            const float labelY = i == 0 ? y - size.y : i == 4 ? y : y - 0.5f * size.y;
            draw->AddLine(ImVec2(x, bottom), ImVec2(x, bottom + 5.0f), text);
            if (i % xStep == 0) addText(draw, ImVec2(labelX, bottom + 6.0f), text, value);
            draw->AddLine(ImVec2(left - 5.0f, y), ImVec2(left, y), text);
            if (i % yStep == 0) addText(draw, ImVec2(left - 8.0f - size.x, labelY), text, value);
        }
    }
    if (!probeText.empty() && !ImGui::GetIO().WantCaptureMouse) ImGui::SetTooltip("%s", probeText.c_str());
}

void drawSceneLabels(const std::vector<ScreenLabel>& labels, glm::vec2 viewOrigin, float viewHeight)
{
    ImDrawList* draw = ImGui::GetBackgroundDrawList();
    for (const ScreenLabel& label : labels) {
        const ImVec2 size = ImGui::CalcTextSize(label.text.c_str());
        const ImU32 colour = label.title ? IM_COL32(255, 255, 255, 255) : IM_COL32(225, 225, 225, 255);
        const ImVec2 at(viewOrigin.x + label.pixel.x - size.x * 0.5f, viewOrigin.y + viewHeight - label.pixel.y - size.y * 0.5f);
        // A dark backing keeps labels readable over a bright sky.
        draw->AddRectFilled(ImVec2(at.x - 3.0f, at.y - 1.0f), ImVec2(at.x + size.x + 3.0f, at.y + size.y + 1.0f), IM_COL32(0, 0, 0, 150), 3.0f);
        addText(draw, at, colour, label.text.c_str());
    }
}

void drawSphereReadings(const std::vector<SphereReading>& readings, glm::vec2 viewOrigin, float viewHeight)
{
    ImDrawList* draw = ImGui::GetBackgroundDrawList();
    // What the numbers are: a bare number over each sphere said nothing to a newcomer.
    if (!readings.empty()) {
        const char* caption = "Furnace: share of white light reflected (1 = all)";
        const ImVec2 size = ImGui::CalcTextSize(caption);
        const ImVec2 at(viewOrigin.x + 10.0f, viewOrigin.y + viewHeight - size.y - 10.0f);
        draw->AddRectFilled(ImVec2(at.x - 4, at.y - 2), ImVec2(at.x + size.x + 4, at.y + size.y + 2), IM_COL32(0, 0, 0, 160));
        addText(draw, at, IM_COL32(255, 255, 255, 255), caption);
    }
    for (const SphereReading& r : readings) {
        char text[32];
        std::snprintf(text, sizeof text, "%.3f", luminance(r.radiance));
        const ImVec2 size = ImGui::CalcTextSize(text);
        const ImVec2 at(viewOrigin.x + r.pixel.x - size.x * 0.5f, viewOrigin.y + viewHeight - r.pixel.y - size.y * 0.5f);
        draw->AddRectFilled(ImVec2(at.x - 2, at.y - 1), ImVec2(at.x + size.x + 2, at.y + size.y + 1), IM_COL32(0, 0, 0, 160));
        addText(draw, at, IM_COL32(255, 255, 255, 255), text);
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
        addText(draw, ImVec2(x - ImGui::CalcTextSize(label).x * 0.5f, origin.y + kBarHeight + 4.0f), text, label);
    }
    const std::string title = std::string("relative error, ") + (view.errorSpace == ErrorSpace::Linear ? "linear HDR" : "display");
    addText(draw, ImVec2(origin.x, origin.y - 18.0f), text, title.c_str());
}

void drawReferenceProgress(const ReferenceStatus& status, const char* meanwhile, glm::vec2 viewOrigin, glm::vec2 viewSize)
{
    char text[160];
    std::snprintf(text, sizeof text, "reference %.0f%% (%dx%d texels): %s", 100.0 * status.progress, status.environmentWidth,
                  status.environmentHeight, meanwhile);
    const ImVec2 size = ImGui::CalcTextSize(text);
    const ImVec2 at(viewOrigin.x + (viewSize.x - size.x) * 0.5f, viewOrigin.y + 12.0f);
    ImDrawList* draw = ImGui::GetBackgroundDrawList();
    draw->AddRectFilled(ImVec2(at.x - 6, at.y - 3), ImVec2(at.x + size.x + 6, at.y + size.y + 3), IM_COL32(0, 0, 0, 170), 4.0f);
    addText(draw, at, IM_COL32(255, 220, 120, 255), text);
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
    addText(draw, aAt, text, a.c_str());
    draw->AddRectFilled(ImVec2(bAt.x - 4, bAt.y - 2), ImVec2(bAt.x + bSize.x + 4, bAt.y + bSize.y + 2), background, 3.0f);
    addText(draw, bAt, text, b.c_str());
}

} // namespace iblab::ui
