#pragma once
// The speed-against-accuracy chart: log cost across, log error up, one curve per series,
// points another point beats on both axes drawn hollow, the front joined by a line. Drawn
// with an ImDrawList only, so that the Study panel (a window) and `iblab bench` (the same
// draw list rendered offscreen to pareto.png) show the very same picture. No GL here.
#include <optional>
#include <string>
#include <vector>

#include <imgui.h>

namespace iblab::ui {

struct ChartPoint {
    double x = 0.0; // > 0 (log axis)
    double y = 0.0; // > 0
    bool dominated = false;
    std::string tooltip;
    std::string mark; // drawn beside the point with a ring around it ("auto", a preset's name); "" for none
};

struct ChartSeries {
    std::string name;
    std::vector<ChartPoint> points; // in the order the curve joins them
    bool joined = true;             // false: points of several settings at once, which no curve orders
};

// A value drawn across the plot (a target), kept inside the y range.
struct ChartMarker {
    double y = 0.0; // > 0; none when 0
    std::string label;
};

struct ParetoChart {
    std::string title;
    std::string xLabel;
    std::string yLabel;
    std::vector<ChartSeries> series;
    ChartMarker yMarker;
};

struct ChartHover {
    int series = -1;
    int point = -1;
    bool valid() const { return series >= 0; }
};

// Draws the chart filling the rectangle [origin, origin + size) (legend at its right) and
// returns the point within a few pixels of `mouse`, if any.
ChartHover drawParetoChart(ImDrawList& draw, const ParetoChart& chart, ImVec2 origin, ImVec2 size, std::optional<ImVec2> mouse = std::nullopt);

// Log-axis ticks for [lo, hi]: the decades inside it, or 1-2-5 or 1..9 per decade when
// fewer than three would fit (a chart with one tick says nothing).
std::vector<double> logTicks(double lo, double hi);

} // namespace iblab::ui
