#include "frame/debug_layout.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ibl/brdf.hpp"

namespace iblab {
namespace {

// Room above each tile for its label.
constexpr float kLabelHeight = 22.0f;
constexpr float kMargin = 12.0f;

// n tiles of aspect (width / height) in a grid that uses the frame best.
std::vector<glm::vec4> grid(int n, float aspect, int width, int height)
{
    float bestSize = 0.0f;
    int bestColumns = 1;
    for (int columns = 1; columns <= n; ++columns) {
        const int rows = (n + columns - 1) / columns;
        const float cellWidth = (float(width) - kMargin) / float(columns) - kMargin;
        const float cellHeight = (float(height) - kMargin) / float(rows) - kMargin - kLabelHeight;
        const float tileWidth = std::min(cellWidth, cellHeight * aspect);
        if (tileWidth > bestSize) {
            bestSize = tileWidth;
            bestColumns = columns;
        }
    }
    std::vector<glm::vec4> rects;
    const float tileWidth = std::max(bestSize, 1.0f);
    const float tileHeight = tileWidth / aspect;
    const int rows = (n + bestColumns - 1) / bestColumns;
    const float totalWidth = float(bestColumns) * (tileWidth + kMargin) - kMargin;
    const float totalHeight = float(rows) * (tileHeight + kMargin + kLabelHeight) - kMargin;
    const float left = std::floor((float(width) - totalWidth) * 0.5f);
    const float top = std::floor(float(height) - (float(height) - totalHeight) * 0.5f); // y up
    for (int i = 0; i < n; ++i) {
        const int column = i % bestColumns, row = i / bestColumns;
        const float x0 = std::floor(left + float(column) * (tileWidth + kMargin));
        const float y1 = std::floor(top - kLabelHeight - float(row) * (tileHeight + kMargin + kLabelHeight));
        rects.emplace_back(x0, std::floor(y1 - tileHeight), std::floor(x0 + tileWidth), y1);
    }
    return rects;
}

} // namespace

std::vector<DebugTile> debugTiles(ViewMode mode, const std::vector<float>& mipRoughness, int width, int height)
{
    std::vector<DebugTile> tiles;
    if (mode == ViewMode::PrefilterMips) {
        const int levels = std::clamp(int(mipRoughness.size()), 1, 16);
        const auto rects = grid(levels, 4.0f / 3.0f, width, height);
        for (int m = 0; m < levels; ++m) {
            char label[64];
            const float roughness = std::size_t(m) < mipRoughness.size() ? mipRoughness[std::size_t(m)] : 0.0f;
            std::snprintf(label, sizeof label, "mip %d: roughness %.2f", m, roughness);
            char shortLabel[32];
            std::snprintf(shortLabel, sizeof shortLabel, "mip %d r %.2f", m, roughness);
            tiles.push_back({rects[std::size_t(m)], label, shortLabel, m});
        }
    } else if (mode == ViewMode::Lut) {
        // Inset for the axis ticks the UI draws left of and below each square.
        auto rects = grid(2, 1.0f, width, height);
        for (glm::vec4& r : rects) r += glm::vec4(44.0f, 22.0f, 0.0f, 0.0f) * glm::vec4(1.0f, 1.0f, 0.0f, 0.0f);
        for (glm::vec4& r : rects) {
            const float side = std::min(r.z - r.x, r.w - r.y);
            r.z = r.x + side;
            r.w = r.y + side;
        }
        tiles.push_back({rects[0], "Schlick-GGX, k = alpha/2 (x: n.v, y: roughness)", "Schlick-GGX", int(GeometryTerm::SchlickGGX)});
        tiles.push_back({rects[1], "height-correlated Smith (x: n.v, y: roughness)", "height-correlated Smith",
                         int(GeometryTerm::HeightCorrelatedSmith)});
    }
    return tiles;
}

int debugTileAt(const std::vector<DebugTile>& tiles, float x, float y)
{
    for (std::size_t i = 0; i < tiles.size(); ++i) {
        const glm::vec4& r = tiles[i].rect;
        if (x >= r.x && y >= r.y && x < r.z && y < r.w) return int(i);
    }
    return -1;
}

} // namespace iblab
