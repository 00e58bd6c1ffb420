#include "ui/pareto_chart.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

namespace iblab::ui {
namespace {

// Fixed colours rather than the style's, so that the PNG and the window look the same.
constexpr ImU32 kBackground = IM_COL32(24, 26, 30, 255);
constexpr ImU32 kPlotBackground = IM_COL32(34, 37, 43, 255);
constexpr ImU32 kGrid = IM_COL32(70, 75, 85, 255);
constexpr ImU32 kAxis = IM_COL32(160, 165, 175, 255);
constexpr ImU32 kText = IM_COL32(225, 228, 235, 255);
constexpr ImU32 kFront = IM_COL32(255, 255, 255, 150);
constexpr float kRadius = 4.0f; // of a point

ImU32 seriesColour(std::size_t index, int alpha = 255)
{
    // Distinguishable hues, none of them the front line's white or the grid's grey.
    static constexpr std::array<std::array<int, 3>, 16> kPalette{{{78, 161, 237},
                                                                  {255, 148, 46},
                                                                  {80, 200, 100},
                                                                  {236, 80, 80},
                                                                  {176, 130, 225},
                                                                  {190, 140, 110},
                                                                  {240, 130, 200},
                                                                  {0, 170, 150},
                                                                  {210, 210, 60},
                                                                  {60, 210, 220},
                                                                  {160, 200, 255},
                                                                  {255, 200, 140},
                                                                  {160, 230, 150},
                                                                  {255, 160, 160},
                                                                  {215, 190, 240},
                                                                  {230, 200, 170}}};
    const auto& c = kPalette[index % kPalette.size()];
    return IM_COL32(c[0], c[1], c[2], alpha);
}

std::string tickLabel(double v)
{
    char text[24];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

struct LogAxis {
    double lo = 1.0, hi = 10.0; // data range, padded
    float from = 0.0f, to = 1.0f; // pixels
    float at(double v) const { return from + float((std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo))) * (to - from); }
};

void fitRange(double& lo, double& hi)
{
    if (!(lo > 0.0) || !(hi > 0.0) || !std::isfinite(lo) || !std::isfinite(hi)) {
        lo = 1.0;
        hi = 10.0;
    }
    if (hi <= lo * 1.0001) {
        lo /= 2.0;
        hi *= 2.0;
    }
    const double pad = std::pow(hi / lo, 0.06); // 6% of the span in log space on each side
    lo /= pad;
    hi *= pad;
}

// The grid lines, ticks and their labels, the plot's frame and the x axis' name.
void drawAxes(ImDrawList& draw, const ParetoChart& chart, const LogAxis& x, const LogAxis& y, ImVec2 plot0, ImVec2 plot1)
{
    for (double t : logTicks(x.lo, x.hi)) {
        const float px = x.at(t);
        draw.AddLine(ImVec2(px, plot0.y), ImVec2(px, plot1.y), kGrid);
        draw.AddLine(ImVec2(px, plot1.y), ImVec2(px, plot1.y + 4.0f), kAxis);
        const std::string label = tickLabel(t);
        draw.AddText(ImVec2(px - ImGui::CalcTextSize(label.c_str()).x * 0.5f, plot1.y + 6.0f), kText, label.c_str());
    }
    for (double t : logTicks(y.lo, y.hi)) {
        const float py = y.at(t);
        draw.AddLine(ImVec2(plot0.x, py), ImVec2(plot1.x, py), kGrid);
        draw.AddLine(ImVec2(plot0.x - 4.0f, py), ImVec2(plot0.x, py), kAxis);
        const std::string label = tickLabel(t);
        const ImVec2 textSize = ImGui::CalcTextSize(label.c_str());
        draw.AddText(ImVec2(plot0.x - 7.0f - textSize.x, py - textSize.y * 0.5f), kText, label.c_str());
    }
    draw.AddRect(plot0, plot1, kAxis);
    const ImVec2 xLabelSize = ImGui::CalcTextSize(chart.xLabel.c_str());
    draw.AddText(ImVec2(0.5f * (plot0.x + plot1.x - xLabelSize.x), plot1.y + 22.0f), kAxis, chart.xLabel.c_str());
}

// The legend, right of the plot: a row per series, then what hollow points and the line mean.
void drawLegend(ImDrawList& draw, const ParetoChart& chart, ImVec2 plot0, ImVec2 plot1)
{
    float ly = plot0.y;
    const float lx = plot1.x + 14.0f;
    for (std::size_t si = 0; si < chart.series.size(); ++si, ly += 16.0f) {
        draw.AddCircleFilled(ImVec2(lx + 5.0f, ly + 7.0f), kRadius, seriesColour(si), 12);
        draw.AddText(ImVec2(lx + 16.0f, ly), kText, chart.series[si].name.c_str());
    }
    ly += 8.0f;
    draw.AddCircle(ImVec2(lx + 5.0f, ly + 7.0f), kRadius, kText, 12, 1.5f);
    draw.AddText(ImVec2(lx + 16.0f, ly), kAxis, "hollow: dominated");
    ly += 16.0f;
    draw.AddLine(ImVec2(lx, ly + 7.0f), ImVec2(lx + 11.0f, ly + 7.0f), kFront, 1.5f);
    draw.AddText(ImVec2(lx + 16.0f, ly), kAxis, "front: nothing cheaper");
    draw.AddText(ImVec2(lx + 16.0f, ly + 14.0f), kAxis, "is more accurate");
}

} // namespace

std::vector<double> logTicks(double lo, double hi)
{
    // The coarsest of decades, 1-2-5 and 1..9 per decade that puts three ticks in the range.
    const auto ticks = [&](std::initializer_list<double> mantissas) {
        std::vector<double> list;
        for (int k = int(std::floor(std::log10(lo))); k <= int(std::ceil(std::log10(hi))); ++k)
            for (double m : mantissas) {
                const double v = m * std::pow(10.0, k);
                if (v >= lo && v <= hi) list.push_back(v);
            }
        return list;
    };
    std::vector<double> list = ticks({1.0});
    if (list.size() < 3) list = ticks({1.0, 2.0, 5.0});
    if (list.size() < 3) list = ticks({1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0});
    return list;
}

ChartHover drawParetoChart(ImDrawList& draw, const ParetoChart& chart, ImVec2 origin, ImVec2 size, std::optional<ImVec2> mouse)
{
    constexpr float kLeft = 62.0f, kBottom = 42.0f, kTop = 40.0f;
    const ImVec2 end(origin.x + size.x, origin.y + size.y);
    // The legend takes what its longest line needs, up to half the chart.
    float legendWidth = ImGui::CalcTextSize("front: nothing cheaper").x;
    for (const ChartSeries& s : chart.series) legendWidth = std::max(legendWidth, ImGui::CalcTextSize(s.name.c_str()).x);
    legendWidth = std::min(legendWidth + 36.0f, 0.5f * size.x);
    draw.AddRectFilled(origin, end, kBackground);
    const ImVec2 plot0(origin.x + kLeft, origin.y + kTop);
    const ImVec2 plot1(std::max(plot0.x + 40.0f, end.x - legendWidth), std::max(plot0.y + 40.0f, end.y - kBottom));
    draw.AddRectFilled(plot0, plot1, kPlotBackground);
    draw.AddText(ImVec2(origin.x + 8.0f, origin.y + 6.0f), kText, chart.title.c_str());
    draw.AddText(ImVec2(origin.x + 8.0f, origin.y + 22.0f), kAxis, chart.yLabel.c_str());

    double xlo = std::numeric_limits<double>::infinity(), xhi = 0.0, ylo = xlo, yhi = 0.0;
    for (const ChartSeries& s : chart.series)
        for (const ChartPoint& p : s.points) {
            if (!(p.x > 0.0) || !(p.y > 0.0)) continue; // a log axis has no place for them
            xlo = std::min(xlo, p.x), xhi = std::max(xhi, p.x), ylo = std::min(ylo, p.y), yhi = std::max(yhi, p.y);
        }
    if (chart.yMarker.y > 0.0) ylo = std::min(ylo, chart.yMarker.y), yhi = std::max(yhi, chart.yMarker.y);
    fitRange(xlo, xhi);
    fitRange(ylo, yhi);
    const LogAxis x{xlo, xhi, plot0.x, plot1.x};
    const LogAxis y{ylo, yhi, plot1.y, plot0.y};

    drawAxes(draw, chart, x, y, plot0, plot1);

    const auto screen = [&](const ChartPoint& p) { return ImVec2(x.at(p.x), y.at(p.y)); };
    const auto drawable = [](const ChartPoint& p) { return p.x > 0.0 && p.y > 0.0 && std::isfinite(p.x) && std::isfinite(p.y); };

    draw.PushClipRect(plot0, plot1, true);
    if (chart.yMarker.y > 0.0) {
        const float py = y.at(chart.yMarker.y);
        draw.AddLine(ImVec2(plot0.x, py), ImVec2(plot1.x, py), kText, 1.0f);
        draw.AddText(ImVec2(plot0.x + 4.0f, py - 15.0f), kText, chart.yMarker.label.c_str());
    }
    // The front: every point nothing beats, joined in order of cost.
    std::vector<ImVec2> front;
    for (const ChartSeries& s : chart.series)
        for (const ChartPoint& p : s.points)
            if (!p.dominated && drawable(p)) front.push_back(screen(p));
    std::sort(front.begin(), front.end(), [](ImVec2 a, ImVec2 b) { return a.x < b.x; });
    if (front.size() > 1) draw.AddPolyline(front.data(), int(front.size()), kFront, ImDrawFlags_None, 1.5f);

    ChartHover hover;
    float nearest = 7.0f;
    for (std::size_t si = 0; si < chart.series.size(); ++si) {
        const ChartSeries& s = chart.series[si];
        std::vector<ImVec2> curve;
        for (const ChartPoint& p : s.points)
            if (drawable(p)) curve.push_back(screen(p));
        if (s.joined && curve.size() > 1) draw.AddPolyline(curve.data(), int(curve.size()), seriesColour(si, 150), ImDrawFlags_None, 1.5f);
        for (std::size_t pi = 0; pi < s.points.size(); ++pi) {
            const ChartPoint& p = s.points[pi];
            if (!drawable(p)) continue;
            const ImVec2 at = screen(p);
            if (p.dominated) draw.AddCircle(at, kRadius, seriesColour(si), 12, 1.5f);
            else {
                draw.AddCircleFilled(at, kRadius + 0.5f, seriesColour(si), 12);
                draw.AddCircle(at, kRadius + 1.5f, kFront, 12, 1.0f);
            }
            if (!p.mark.empty()) {
                draw.AddCircle(at, kRadius + 4.5f, kText, 16, 2.0f);
                // Right of the point, or left of it where the plot ends.
                const float width = ImGui::CalcTextSize(p.mark.c_str()).x;
                const float tx = at.x + kRadius + 7.0f + width <= plot1.x ? at.x + kRadius + 7.0f : at.x - kRadius - 7.0f - width;
                draw.AddText(ImVec2(tx, at.y - 7.0f), kText, p.mark.c_str());
            }
            if (mouse) {
                const float d = std::hypot(mouse->x - at.x, mouse->y - at.y);
                if (d < nearest) nearest = d, hover = {int(si), int(pi)};
            }
        }
    }
    if (hover.valid()) draw.AddCircle(screen(chart.series[std::size_t(hover.series)].points[std::size_t(hover.point)]), 8.0f, kText, 16, 2.0f);
    draw.PopClipRect();

    drawLegend(draw, chart, plot0, plot1);
    return hover;
}

} // namespace iblab::ui
