#include "view_overlays.hpp"

#include <algorithm>

#include <epoxy/gl.h>
#include <imgui.h>
#include <imgui_impl_opengl3.h>

#include "frame/debug_layout.hpp"
#include "frame/split_view.hpp"
#include "ui/overlays.hpp"
#include "ui/panels.hpp"

namespace iblab::app {

void drawViewOverlays(const Renderer& renderer, const FrameSettings& settings, int width, int height, glm::vec2 viewOrigin,
                      const std::vector<SphereReading>& furnaceReadings, std::optional<glm::vec2> mouseInView)
{
    ui::clearOverlayTexts();
    if (!furnaceReadings.empty()) ui::drawSphereReadings(furnaceReadings, viewOrigin, float(height));
    const bool sceneView = settings.view.mode != ViewMode::PrefilterMips && settings.view.mode != ViewMode::Lut;
    const glm::vec2 viewSize{float(width), float(height)};
    if (settings.view.mode == ViewMode::Final || settings.view.mode == ViewMode::Furnace || settings.view.mode == ViewMode::Error)
        ui::drawSceneLabels(renderer.sceneLabels(settings, width, height), viewOrigin, float(height));
    if (sceneView && settings.view.split) ui::drawSplitDivider(settings, splitColumn(settings.view, width), viewOrigin, viewSize);
    if (showsReference(settings)) {
        const ReferenceStatus reference = renderer.referenceStatus(settings, width, height);
        if (reference.complete && settings.view.mode == ViewMode::Error) ui::drawErrorLegend(settings.view, viewOrigin, viewSize);
        else if (reference.current && !reference.complete)
            ui::drawReferenceProgress(reference, referenceMethodSide(settings) ? "split sum where tiles have not finished" : "showing the frame until it completes",
                                      viewOrigin, viewSize);
    }
    if (settings.view.mode == ViewMode::PrefilterMips || settings.view.mode == ViewMode::Lut) {
        const TexelProbe probe = mouseInView ? renderer.probe(settings, width, height, mouseInView->x, mouseInView->y) : TexelProbe{};
        ui::drawDebugOverlay(debugTiles(settings.view.mode, renderer.prefilterMipRoughness(), width, height), settings.view.mode == ViewMode::Lut,
                             viewOrigin, float(height), probe.text);
    }
}

OffscreenOverlay::OffscreenOverlay() : context_(ImGui::CreateContext())
{
    ImGui::GetIO().IniFilename = nullptr;
    ImGui::StyleColorsDark();
    ImGui_ImplOpenGL3_Init("#version 450");
}

OffscreenOverlay::~OffscreenOverlay()
{
    ImGui_ImplOpenGL3_Shutdown();
    ImGui::DestroyContext(context_);
}

void OffscreenOverlay::drawOver(Renderer& renderer, const FrameSettings& settings, int width, int height, const std::vector<std::string>& caption)
{
    const std::vector<SphereReading> readings = settings.view.mode == ViewMode::Furnace ? renderer.measureSpheres(settings) : std::vector<SphereReading>{};
    drawFrame(
        width, height,
        [&] {
            drawViewOverlays(renderer, settings, width, height, glm::vec2(0.0f), readings, std::nullopt);
            if (caption.empty()) return;
            ImDrawList* draw = ImGui::GetForegroundDrawList();
            const float lineHeight = ImGui::GetTextLineHeightWithSpacing();
            float widest = 0.0f;
            for (const std::string& line : caption) widest = std::max(widest, ImGui::CalcTextSize(line.c_str()).x);
            draw->AddRectFilled(ImVec2(0.0f, 0.0f), ImVec2(widest + 12.0f, lineHeight * float(caption.size()) + 8.0f), IM_COL32(0, 0, 0, 170));
            for (std::size_t i = 0; i < caption.size(); ++i)
                draw->AddText(ImVec2(6.0f, 4.0f + lineHeight * float(i)), i == 0 ? IM_COL32(255, 255, 255, 255) : IM_COL32(210, 210, 210, 255),
                              caption[i].c_str());
        },
        [&] { renderer.bindDisplayFramebuffer(); });
}

void OffscreenOverlay::drawFrame(int width, int height, const std::function<void()>& build, const std::function<void()>& bindTarget)
{
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(float(width), float(height));
    io.DeltaTime = 1.0f / 60.0f;
    ImGui_ImplOpenGL3_NewFrame();
    ImGui::NewFrame();
    build();
    ImGui::Render();
    bindTarget();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

} // namespace iblab::app
