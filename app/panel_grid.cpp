#include "panel_grid.hpp"

#include <cstring>
#include <stdexcept>

#include "io/image_writer.hpp"

namespace iblab::app {

PanelGrid::PanelGrid(int columns, int rows, int panelWidth, int panelHeight)
    : columns_(columns), rows_(rows), panelWidth_(panelWidth), panelHeight_(panelHeight),
      rgba_(std::size_t(columns) * std::size_t(panelWidth) * std::size_t(rows) * std::size_t(panelHeight) * 4, 0)
{
}

void PanelGrid::place(const DisplayReadback& panel, int column, int row)
{
    if (panel.width != panelWidth_ || panel.height != panelHeight_ || column < 0 || column >= columns_ || row < 0 || row >= rows_)
        throw std::logic_error("PanelGrid::place: a panel of another size, or outside the grid");
    const std::size_t stride = std::size_t(columns_) * std::size_t(panelWidth_) * 4;
    for (int y = 0; y < panelHeight_; ++y) {
        const std::uint8_t* from = &panel.rgba[std::size_t(panelHeight_ - 1 - y) * std::size_t(panelWidth_) * 4];
        const std::size_t toRow = std::size_t(row) * std::size_t(panelHeight_) + std::size_t(y);
        std::memcpy(&rgba_[toRow * stride + std::size_t(column) * std::size_t(panelWidth_) * 4], from, std::size_t(panelWidth_) * 4);
    }
}

void PanelGrid::writePng(const std::string& path, const std::string& settingsJson) const
{
    writePng8(path, columns_ * panelWidth_, rows_ * panelHeight_, 4, rgba_, {.settingsJson = settingsJson});
}

} // namespace iblab::app
