#include "ui/status_area.hpp"

#include <string>

#include <imgui.h>

namespace iblab::ui {

void drawStatus(const StatusLine& status)
{
    if (status.text.empty()) return;
    const ImVec4 colour = status.isError ? ImVec4(1.0f, 0.45f, 0.4f, 1.0f) : ImVec4(0.6f, 0.85f, 0.6f, 1.0f);
    ImGui::PushStyleColor(ImGuiCol_Text, colour);
    ImGui::TextWrapped("%s", status.text.c_str());
    ImGui::PopStyleColor();
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    for (const std::string& note : status.notes) ImGui::TextWrapped("note: %s", note.c_str());
    ImGui::PopStyleColor();
}

void drawStatusArea(const char* id, std::initializer_list<const StatusLine*> statuses, int lines, const Activity* activity)
{
    const float height = float(lines) * ImGui::GetTextLineHeightWithSpacing();
    // No scrolling with the wheel inside: it goes on to the panel, which a user scrolls over
    // this area as over any other.
    ImGui::BeginChild(id, ImVec2(-1.0f, height), false, ImGuiWindowFlags_NoScrollWithMouse);
    if (activity && !activity->text.empty()) ImGui::ProgressBar(activity->progress, ImVec2(-1.0f, 0.0f), activity->text.c_str());
    for (const StatusLine* status : statuses) drawStatus(*status);
    const bool overflows = ImGui::GetCursorPosY() > height + 1.0f;
    ImGui::EndChild();
    if (overflows && ImGui::IsItemHovered()) {
        ImGui::BeginTooltip();
        ImGui::PushTextWrapPos(ImGui::GetFontSize() * 40.0f);
        for (const StatusLine* status : statuses) drawStatus(*status);
        ImGui::PopTextWrapPos();
        ImGui::EndTooltip();
    }
}

} // namespace iblab::ui
