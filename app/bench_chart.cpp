#include "bench_chart.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>

#include "io/image_writer.hpp"
#include "gl/render_target.hpp"
#include "view_overlays.hpp"

namespace iblab::app {

std::vector<ui::ParetoChart> benchCharts(const bench::BenchReport& report, ChartError error, double targetSteps)
{
    const bool display = error == ChartError::DisplayP99;
    std::vector<bench::BenchPoint> points = report.points;
    if (display) bench::markDominated(points, [](const bench::BenchPoint& p) { return p.display.p99Steps; });

    std::vector<std::string> seriesOrder;
    for (const bench::SweepPoint& p : report.options.points)
        if (std::find(seriesOrder.begin(), seriesOrder.end(), p.series) == seriesOrder.end()) seriesOrder.push_back(p.series);

    std::vector<ui::ParetoChart> charts;
    for (const bench::BenchEnvironment& e : report.options.environments) {
        ui::ParetoChart chart;
        chart.title = e.name + " (" + std::string(enumName(report.options.frame.scene.kind)) + ", " + std::to_string(report.options.width) + "x" +
                      std::to_string(report.options.height) + ")";
        chart.xLabel = "cost, ms: bake + " + std::to_string(report.options.costFrames) + " frame" + (report.options.costFrames == 1 ? "" : "s") + " (log)";
        chart.yLabel = display ? "display error against the reference: 99th percentile, 8-bit steps (log)" : "relative RMSE against the reference (log)";
        if (display && targetSteps > 0.0) chart.yMarker = {targetSteps, "target"};
        for (const std::string& name : seriesOrder) {
            const auto member = std::find_if(report.options.points.begin(), report.options.points.end(), [&](const bench::SweepPoint& p) { return p.series == name; });
            chart.series.push_back({name, {}, !member->scatter});
        }
        bool any = false;
        for (const bench::BenchPoint& p : points) {
            // A point without an error has no place on the error axis; the report says why
            // (bench::unmeasuredEnvironments).
            if (p.environment != e.name || !bench::measured(p)) continue;
            any = true;
            const std::size_t index = std::size_t(std::find(seriesOrder.begin(), seriesOrder.end(), p.setting.series) - seriesOrder.begin());
            char text[512];
            std::snprintf(text, sizeof text, "\ncost %.1f ms (bake %.1f ms, frame %.2f ms)\nrelative RMSE %.4g, p99 %.3g, fireflies %zu%s", p.costMilliseconds,
                          p.bakeMilliseconds, p.frameMilliseconds, p.error.relativeRmse, p.error.p99Relative, p.error.fireflies,
                          p.dominated ? "\ndominated: another setting is cheaper and more accurate" : "");
            std::snprintf(text + std::strlen(text), sizeof text - std::strlen(text), "\ndisplay error: p99 %.3g, RMS %.3g 8-bit steps%s", p.display.p99Steps,
                          p.display.rmsSteps, p.chosen ? "\nthe auto quality mode's choice" : "");
            chart.series[index].points.push_back(
                {p.costMilliseconds, display ? p.display.p99Steps : p.error.relativeRmse, p.dominated, p.setting.label + text, p.chosen ? std::string("auto") : p.setting.mark});
        }
        if (any) charts.push_back(std::move(chart));
    }
    return charts;
}

void writeChartsPng(const std::string& path, const std::vector<ui::ParetoChart>& charts, int chartWidth, int chartHeight, int columns)
{
    const int count = std::max<int>(int(charts.size()), 1);
    columns = std::clamp(columns, 1, count);
    const int rows = (count + columns - 1) / columns;
    const int width = chartWidth * columns, height = chartHeight * rows;
    gl::RenderTarget target;
    target.ensure(GL_RGBA8, width, height);
    glClearNamedFramebufferfv(target.framebuffer(), GL_COLOR, 0, std::array<float, 4>{0.0f, 0.0f, 0.0f, 1.0f}.data());
    OffscreenOverlay imgui;
    imgui.drawFrame(
        width, height,
        [&] {
            for (std::size_t i = 0; i < charts.size(); ++i) {
                const ImVec2 origin(float(int(i) % columns * chartWidth), float(int(i) / columns * chartHeight));
                ui::drawParetoChart(*ImGui::GetBackgroundDrawList(), charts[i], origin, ImVec2(float(chartWidth), float(chartHeight)));
            }
        },
        [&] {
            glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer());
            glViewport(0, 0, width, height);
        });
    std::vector<std::uint8_t> rgb(std::size_t(width) * std::size_t(height) * 3);
    glPixelStorei(GL_PACK_ALIGNMENT, 1); // tightly packed RGB rows
    glGetTextureImage(target.texture(), 0, GL_RGB, GL_UNSIGNED_BYTE, GLsizei(rgb.size()), rgb.data());
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    ImageWriteOptions options;
    options.bottomUp = true; // GL's row 0 is the bottom
    writePng8(path, width, height, 3, rgb, options);
}

} // namespace iblab::app
