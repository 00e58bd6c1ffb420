#include "ui/help_window.hpp"

#include <imgui.h>

#include "ui/widgets.hpp"

namespace iblab::ui {
namespace {

struct HelpRow {
    const char* what;
    const char* does;
};

void drawRows(const char* id, std::initializer_list<HelpRow> rows)
{
    if (!ImGui::BeginTable(id, 2, ImGuiTableFlags_SizingFixedFit)) return;
    for (const HelpRow& row : rows) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(row.what);
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(row.does);
    }
    ImGui::EndTable();
}

} // namespace

void drawHelpWindow(bool& open)
{
    if (!open) return;
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(display.x * 0.5f, display.y * 0.5f), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowSizeConstraints(ImVec2(0.0f, 0.0f), ImVec2(display.x - 20.0f, display.y - 20.0f));
    if (!ImGui::Begin("Help", &open, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse)) {
        ImGui::End();
        return;
    }
    ImGui::TextDisabled("Mouse, on the view");
    drawRows("##mouse", {{"left drag", "orbit the camera"},
                         {"right or middle drag, Shift + left drag", "pan"},
                         {"wheel", "zoom"},
                         {"double-click", "frame the scene"},
                         {"drag the divider", "move the split view's A | B line"},
                         {"drop a file", ".exr / .hdr map, .gltf / .glb model, .json preset"}});
    ImGui::Separator();
    ImGui::TextDisabled("Keys (not while typing in a field)");
    drawRows("##keys", {{"F1", "this help"},
                        {"Esc", "close a list, a dialog or this help (never quits)"},
                        {"Tab", "hide or show the panel"},
                        {"+  -", "the sampled method's N"},
                        {"R, Home", "reset the camera"},
                        {"F", "frame the scene"},
                        {"1  3  7", "front, side, top view"},
                        {"F12", "screenshot into the Capture folder"},
                        {"Ctrl+S", "save the preset"},
                        {"Ctrl+Q", "quit (asks when the settings changed)"},
                        {"Ctrl+click a slider", "type a value"}});
    ImGui::Separator();
    ImGui::TextDisabled("The panel, top to bottom");
    drawRows("##sections", {{"Environment", "the map: bundled, procedural (builtin:) or a file; its yaw and intensity"},
                            {"Scene", "sphere, grid, counting strip, roughness sweep or a glTF model"},
                            {"Material", "base colour, metallic, roughness"},
                            {"Sampling", "the method: split sum, fitted lobe, sampled (N), reference"},
                            {"Convention", "bake and shade as LearnOpenGL, Filament or the glTF viewer do"},
                            {"Tone map", "exposure and curve"},
                            {"View", "final image, prefiltered mips, LUT, furnace, irradiance, error"},
                            {"Compare", "the split view A | B and the error against the reference"},
                            {"Camera", "distance, angles, field of view"},
                            {"Capture", "screenshots (.png, .exr)"},
                            {"Preset", "save and load every setting as JSON"},
                            {"Study", "speed against accuracy; auto quality"}});
    ImGui::End();
}

} // namespace iblab::ui
