#pragma once
// The bench's measurements as Pareto charts (one per environment), shared by `iblab bench`
// (pareto.png, drawn offscreen) and the GUI's Study panel (drawn live).
#include <string>
#include <vector>

#include "lab/bench_sweep.hpp"
#include "ui/pareto_chart.hpp"

namespace iblab::app {

// One chart per environment that has points, series in sweep order (so a series keeps its
// colour from chart to chart and while points arrive).
// Upwards: the bench's relative RMSE, or the display error the auto quality target is set in
// (its 99th percentile in 8-bit steps, dominance judged by it, the target drawn across).
enum class ChartError { RelativeRmse, DisplayP99 };
std::vector<ui::ParetoChart> benchCharts(const bench::BenchReport& report, ChartError error = ChartError::RelativeRmse, double targetSteps = 0.0);

// The charts in a grid of `columns`, each chartWidth x chartHeight, rendered by Dear ImGui
// into an offscreen framebuffer and written as an 8-bit RGB PNG. Needs a current GL context.
void writeChartsPng(const std::string& path, const std::vector<ui::ParetoChart>& charts, int chartWidth, int chartHeight, int columns);

} // namespace iblab::app
