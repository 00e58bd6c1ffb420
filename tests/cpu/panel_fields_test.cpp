// Every panel control that edits a setting is bound to its table row (ui/field_widgets.hpp),
// and shows the row's label and the row's span: the test draws the whole control window
// without GL, in states that between them show every conditional control, then walks what
// the item registry recorded and the settings tables. A slider written by hand
// (sliderFloat("Field of view", ..., 10, 120)) edits no row and fails here, as does a row's
// slider span that leaves its valid range.
#include <cmath>
#include <map>
#include <set>
#include <string>

#include <gtest/gtest.h>
#include <imgui.h>

#include "frame/settings.hpp"
#include "ui/panels.hpp"
#include "ui/widgets.hpp"

namespace iblab {
namespace {

// Controls that edit no settings row: the bake export's engine (a request's argument) and
// the auto quality's target (a study's parameter, lab/auto_quality.hpp).
const std::set<std::string> kNotSettings{"Environment/engine", "Study/Target"};

struct Row {
    std::string label;
    FieldRange range;
};

// Every row the panels may bind, by the key a control records (the sampling and material
// tables' own keys, the frame table's for the rest).
std::map<std::string, Row> allRows()
{
    std::map<std::string, Row> rows;
    for (const auto& f : samplingSettingsFields()) rows[f.key] = {std::string(f.label), f.range};
    for (const auto& f : materialSettingsFields()) rows[f.key] = {std::string(f.label), f.range};
    for (const auto& f : frameSettingsFields())
        if (!f.key.starts_with("sampling.") && !f.key.starts_with("material.") && !f.key.starts_with("view.compare."))
            rows[f.key] = {std::string(f.label), f.range}; // the nested tables' rows are recorded by their own keys
    return rows;
}

class PanelFields : public ::testing::Test {
protected:
    void SetUp() override
    {
        context_ = ImGui::CreateContext();
        ImGuiIO& io = ImGui::GetIO();
        io.DisplaySize = ImVec2(1600.0f, 4000.0f); // tall enough for every section open
        io.DeltaTime = 1.0f / 60.0f;
        io.IniFilename = nullptr;
        unsigned char* pixels = nullptr;
        int width = 0, height = 0;
        io.Fonts->GetTexDataAsRGBA32(&pixels, &width, &height);
        for (const char* section : {"Environment", "Scene", "Material", "Sampling", "Conventions", "Tone mapping", "View", "Compare",
                                    "Camera", "Capture", "Preset", "Study"})
            ui::sectionStates()[section] = true;
    }
    void TearDown() override { ImGui::DestroyContext(context_); }

    // Draws the control window twice (sections open on the first frame) and keeps what the
    // second recorded.
    void draw(FrameSettings settings)
    {
        ui::PanelState state;
        ui::FrameStats stats;
        for (int frame = 0; frame < 2; ++frame) {
            ui::UiRequests requests;
            ImGui::NewFrame();
            ui::itemRegistry().beginFrame();
            ui::drawControlWindow(settings, state, stats, requests);
            ui::itemRegistry().endFrame();
            ImGui::Render();
        }
        for (const ui::TrackedItem& item : ui::itemRegistry().items()) items_[item.path] = item;
    }

    ImGuiContext* context_ = nullptr;
    std::map<std::string, ui::TrackedItem> items_;
};

TEST_F(PanelFields, EveryControlShowsItsRowsLabelAndSpan)
{
    FrameSettings a; // the sampled method's controls, the counting strip, the error view, the split
    a.scene.kind = SceneKind::Counting;
    a.sampling.method = ShadingMethod::Sampled;
    a.sampling.forcedMip = 2;
    a.view.mode = ViewMode::Error;
    a.view.background = BackgroundMode::PrefilterMip;
    a.view.split = true;
    a.view.compare.method = ShadingMethod::Sampled;
    draw(a);
    FrameSettings b; // a model's override, the split sum's controls, the solid background
    b.scene.kind = SceneKind::Model;
    b.scene.modelPath = "model.glb";
    b.sampling.method = ShadingMethod::SplitSum;
    b.view.background = BackgroundMode::SolidColour;
    draw(b);

    const std::map<std::string, Row> rows = allRows();
    std::set<std::string> drawnRows;
    int bound = 0;
    for (const auto& [path, item] : items_) {
        if (item.kind != "slider" && item.kind != "checkbox" && item.kind != "combo" && item.kind != "colour") continue;
        if (kNotSettings.count(path)) continue;
        SCOPED_TRACE(path);
        ASSERT_FALSE(item.field.empty()) << "edits no settings row: bind it with ui/field_widgets.hpp";
        const auto row = rows.find(item.field);
        ASSERT_NE(row, rows.end()) << item.field;
        drawnRows.insert(item.field);
        ++bound;
        const FieldRange& range = row->second.range;
        if (item.kind == "slider") {
            EXPECT_EQ(path.substr(path.rfind('/') + 1), row->second.label);
            EXPECT_EQ(item.fieldMin, sliderMin(range));
            EXPECT_EQ(item.fieldMax, sliderMax(range));
        }
        if (!std::isnan(item.fieldMin)) {
            EXPECT_GE(item.fieldMin, range.min) << "the control reaches below the row's range";
            EXPECT_LE(item.fieldMax, range.max) << "the control reaches above the row's range";
        }
    }
    EXPECT_GT(bound, 30);
    // A row's slider span or format is only worth having where a panel draws the row.
    for (const auto& [key, row] : rows)
        if (!std::isnan(row.range.ui.min) || !std::isnan(row.range.ui.max) || !row.range.ui.format.empty()) {
            EXPECT_TRUE(drawnRows.count(key)) << key << " has a slider span or format, but no panel draws it";
        }
}

// The check can fail: a slider drawn by hand records no row.
TEST_F(PanelFields, AHandWrittenSliderEditsNoRow)
{
    ImGui::NewFrame();
    ui::itemRegistry().beginFrame();
    ImGui::Begin("test");
    float fov = 45.0f;
    ui::sliderFloat("Field of view", &fov, 10.0f, 120.0f);
    ImGui::End();
    ui::itemRegistry().endFrame();
    ImGui::Render();
    const ui::TrackedItem* item = ui::itemRegistry().find("Field of view");
    ASSERT_NE(item, nullptr);
    EXPECT_TRUE(item->field.empty());
}

} // namespace
} // namespace iblab
