#pragma once
// A PNG of equal panels in rows and columns, each a frame the renderer displayed (with its
// overlays): the side-by-side figures of `iblab conventions` and `iblab compare`.
#include <cstdint>
#include <string>
#include <vector>

#include "frame/readback.hpp"

namespace iblab::app {

class PanelGrid {
public:
    PanelGrid(int columns, int rows, int panelWidth, int panelHeight);
    // Copies a display read-back (bottom row first, panelWidth x panelHeight) into the cell.
    void place(const DisplayReadback& panel, int column, int row);
    // An 8-bit RGBA PNG; `settingsJson` goes into its metadata, as `render` does.
    void writePng(const std::string& path, const std::string& settingsJson) const;

private:
    int columns_, rows_, panelWidth_, panelHeight_;
    std::vector<std::uint8_t> rgba_; // top row first
};

} // namespace iblab::app
