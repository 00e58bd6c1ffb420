#include "bake/tile_lights.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <unordered_map>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "bake/bright_texels.hpp"
#include "ibl/conventions.hpp"
#include "ibl/luminance.hpp"
#include "ibl/parallel_rows.hpp"

namespace iblab::bake {
namespace {

// The tree's coarsest cells: an 8 face (cells of 11 degrees), whose nodes every tile visits.
constexpr int kCoarsestFace = 8;
// The candidates whose tree the threshold's search builds first (then four times as many).
constexpr std::size_t kFirstTreeCandidates = 1024;
// A tile's walk takes a few microseconds: at most a thread per this many tiles (1536 tiles at
// mip 1: 3 threads). Not tuned; the thread starts were not measured on their own.
constexpr int kTilesPerThread = 512;
// A node is summed as one light at its flux centre where its cell's diagonal is at most this
// share of its distance from the tile: the point's error is then about 0.4 (1/4)^2, 3% of
// the node's contribution (the lobe's tail falls as theta^-4), and far less near the peak,
// where only the finest cells (alpha / 2) are summed.
constexpr double kMergeRatio = 0.25;
// Where a tile's list would not fit its cap even with every candidate lit at kMergeRatio (a
// lattice of one-texel stars or lines converging at a pole), planTileLights may double the
// tile's ratio up to this: a point's error then grows to about 0.4 of the merged node's
// contribution, where the alternative, a threshold above the field, left all of it to the
// samples (docs/bake.md, "Lines and lattices").
constexpr double kCoarsestMergeRatio = 1.0;
// And past that, sum whole the nodes up to this level however near (cells of alpha, twice the
// finest: a cell full of light at the lobe's peak is then summed about 8% low, against 2%),
// before the threshold rises.
constexpr int kCoarsestFinestLevel = 1;

// A tile of output texels: its centre, the angle to its farthest corner, the share of its
// distance a node's cell may span for the tile to sum it whole, and the level up to which it
// sums every node whole.
struct Tile {
    glm::dvec3 centre;
    double radius = 0.0;
    double mergeRatio = kMergeRatio;
    int finestLevel = 0; // nodes of this level and finer are summed whole
};

glm::dvec3 faceDirection(int face, double u, double v)
{
    return glm::normalize(glm::dvec3(cubeFaceUvToDirection(face, glm::vec2(float(u), float(v)))));
}

double angleBetween(const glm::dvec3& a, const glm::dvec3& b) { return std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0)); }

std::vector<Tile> outputTiles(int tilesPerEdge)
{
    std::vector<Tile> tiles;
    tiles.reserve(6 * std::size_t(tilesPerEdge) * std::size_t(tilesPerEdge));
    const double step = 1.0 / double(tilesPerEdge);
    for (int face = 0; face < 6; ++face)
        for (int row = 0; row < tilesPerEdge; ++row)
            for (int column = 0; column < tilesPerEdge; ++column) {
                const double u0 = column * step, v0 = row * step;
                Tile tile{faceDirection(face, u0 + 0.5 * step, v0 + 0.5 * step)};
                for (double u : {u0, u0 + step})
                    for (double v : {v0, v0 + step})
                        tile.radius = std::max(tile.radius, angleBetween(tile.centre, faceDirection(face, u, v)));
                tiles.push_back(tile);
            }
    return tiles;
}

// A cell of a size^2 cube, (face, row, column) row-major as brightCellOf numbers it.
struct Cell {
    int face, row, column;
};
Cell cellAt(std::uint64_t key, int size)
{
    const auto s = std::uint64_t(size);
    return {int(key / (s * s)), int(key / s % s), int(key % s)};
}
std::uint64_t cellKey(Cell c, int size) { return (std::uint64_t(c.face) * std::uint64_t(size) + std::uint64_t(c.row)) * std::uint64_t(size) + std::uint64_t(c.column); }

// Every candidate in a quadtree of cube cells: level 0 the finest (the level's merge cells),
// each next level a face half as large. A node's firstCandidate is the brightest candidate in
// it (the smallest index), so the lights of a threshold that keeps the first p candidates are
// the nodes with firstCandidate < p. How a tile sums a node depends only on where the node
// is (nodeUse), so the search for the threshold and the lists share one tree.
struct LightTree {
    struct Node {
        glm::dvec3 centre{0.0}; // the cell's
        glm::dvec3 weightedDirection{0.0};
        glm::dvec3 flux{0.0};
        std::uint32_t firstCandidate = 0;
        int level = 0;
        int parent = -1;
        std::array<int, 4> children{-1, -1, -1, -1};
    };
    std::vector<int> faceSizes;
    std::vector<Node> nodes;
    std::vector<int> roots; // the coarsest level's, in cell order
    std::vector<int> finestNode; // per candidate
};

LightTree lightTree(const BrightCandidates& candidates, std::size_t count, int finestFace)
{
    LightTree tree;
    for (int size = finestFace; size >= kCoarsestFace; size /= 2)
        tree.faceSizes.push_back(size);
    if (tree.faceSizes.empty())
        tree.faceSizes.push_back(finestFace);
    const int levels = int(tree.faceSizes.size());
    std::vector<std::unordered_map<std::uint64_t, int>> byKey(static_cast<std::size_t>(levels));
    for (auto& level : byKey)
        level.reserve(count);
    tree.nodes.reserve(2 * count);
    std::map<std::uint64_t, int> roots;
    tree.finestNode.reserve(count);
    for (std::size_t i = 0; i < count; ++i) {
        Cell cell = cellAt(brightCellOf(candidates.texels[i].direction, finestFace), finestFace);
        int below = -1;  // the node just made one level finer
        int quarter = 0; // its quarter of this level's cell
        for (int level = 0; level < levels; ++level) {
            const int size = tree.faceSizes[std::size_t(level)];
            const auto [it, created] = byKey[std::size_t(level)].try_emplace(cellKey(cell, size), int(tree.nodes.size()));
            const int index = it->second;
            if (created) {
                LightTree::Node node;
                node.centre = faceDirection(cell.face, (cell.column + 0.5) / size, (cell.row + 0.5) / size);
                node.firstCandidate = std::uint32_t(i);
                node.level = level;
                tree.nodes.push_back(node);
                if (level == levels - 1)
                    roots.emplace(cellKey(cell, size), index);
            }
            if (level == 0)
                tree.finestNode.push_back(index);
            if (below >= 0) {
                tree.nodes[std::size_t(index)].children[std::size_t(quarter)] = below;
                tree.nodes[std::size_t(below)].parent = index;
            }
            if (!created)
                break; // its ancestors exist already
            below = index;
            quarter = (cell.row % 2) * 2 + cell.column % 2;
            cell = {cell.face, cell.row / 2, cell.column / 2};
        }
    }
    for (const auto& [key, node] : roots)
        tree.roots.push_back(node);
    return tree;
}

// How a tile treats the nodes of each level, by the cosine of the angle to the node's centre:
// below skip, none of its lights comes within reach of a texel of the tile; at most whole,
// it is far enough to be summed as one light (kMergeRatio); in between it is opened.
struct TileReach {
    std::vector<double> skip, whole;
};

TileReach tileReach(const LightTree& tree, const Tile& tile, double reach)
{
    TileReach r;
    for (int size : tree.faceSizes) {
        // A cell of a size-S face spans at most 2 / S radians a side: its lights lie within
        // 1.5 / S of its centre.
        const double halfDiagonal = 1.5 / size;
        r.skip.push_back(std::cos(std::min(kPi, reach + tile.radius + halfDiagonal)));
        r.whole.push_back(std::cos(std::min(kPi, 2.0 * halfDiagonal / tile.mergeRatio + tile.radius + halfDiagonal)));
    }
    return r;
}

// What a tile does with a node: one beyond reach is left out (its band's tail), one far
// enough or at the finest level is summed whole, and any other is opened.
enum class NodeUse { Skip, Sum, Open };
NodeUse nodeUse(const Tile& tile, const TileReach& reach, const LightTree::Node& node)
{
    const double c = glm::dot(tile.centre, node.centre);
    if (c < reach.skip[std::size_t(node.level)])
        return NodeUse::Skip;
    return node.level <= tile.finestLevel || c <= reach.whole[std::size_t(node.level)] ? NodeUse::Sum : NodeUse::Open;
}

// A tile's list: the nodes it sums among those of the first `lit` candidates, two entries
// each, (flux centre, 0), (flux, 0), in a fixed order (roots in cell order, depth first).
std::vector<glm::vec4> tileLights(const LightTree& tree, const Tile& tile, double reach, std::size_t lit)
{
    const TileReach r = tileReach(tree, tile, reach);
    std::vector<glm::vec4> lights;
    std::vector<int> stack;
    for (auto root = tree.roots.rbegin(); root != tree.roots.rend(); ++root)
        if (nodeUse(tile, r, tree.nodes[std::size_t(*root)]) != NodeUse::Skip)
            stack.push_back(*root);
    while (!stack.empty()) {
        const LightTree::Node& node = tree.nodes[std::size_t(stack.back())];
        stack.pop_back();
        if (node.firstCandidate >= lit) // nothing under it is lit
            continue;
        switch (nodeUse(tile, r, node)) {
        case NodeUse::Skip: break;
        case NodeUse::Sum:
            lights.emplace_back(glm::vec3(glm::normalize(node.weightedDirection)), 0.0f);
            lights.emplace_back(glm::vec3(node.flux), 0.0f);
            break;
        case NodeUse::Open:
            for (auto child = node.children.rbegin(); child != node.children.rend(); ++child)
                if (*child >= 0)
                    stack.push_back(*child);
            break;
        }
    }
    return lights;
}

// How many nodes among those of the first `lit` candidates a tile sums, counted up to limit + 1.
int countTileLights(const LightTree& tree, const Tile& tile, double reach, std::size_t lit, int limit)
{
    const TileReach r = tileReach(tree, tile, reach);
    std::vector<int> stack(tree.roots.begin(), tree.roots.end());
    int count = 0;
    while (!stack.empty() && count <= limit) {
        const LightTree::Node& node = tree.nodes[std::size_t(stack.back())];
        stack.pop_back();
        if (node.firstCandidate >= lit)
            continue;
        switch (nodeUse(tile, r, node)) {
        case NodeUse::Skip: break;
        case NodeUse::Sum: ++count; break;
        case NodeUse::Open:
            for (int child : node.children)
                if (child >= 0)
                    stack.push_back(child);
            break;
        }
    }
    return count;
}

// Each tile whose list with the first `lit` candidates lit exceeds the cap merges coarser:
// its ratio doubled up to kCoarsestMergeRatio, then its finest level raised up to
// kCoarsestFinestLevel, until the list fits. Whether every list then fits.
bool coarsenOverfullTiles(const LightTree& tree, std::vector<Tile>& tiles, double reach, int cap, std::size_t lit)
{
    std::atomic<bool> allFit{true};
    parallelRows(int(tiles.size()), [&](int first, int end) {
        for (int t = first; t < end; ++t) {
            Tile& tile = tiles[std::size_t(t)];
            for (;;) {
                if (countTileLights(tree, tile, reach, lit, cap) <= cap)
                    break;
                if (tile.mergeRatio < kCoarsestMergeRatio) {
                    tile.mergeRatio = std::min(2.0 * tile.mergeRatio, kCoarsestMergeRatio);
                } else if (tile.finestLevel < kCoarsestFinestLevel && tile.finestLevel + 1 < int(tree.faceSizes.size())) {
                    ++tile.finestLevel;
                } else {
                    allFit = false;
                    break;
                }
            }
        }
    }, kTilesPerThread);
    return allFit;
}

// The most candidates (a prefix) whose nodes every tile sums in at most cap lights: per tile
// the (cap + 1)-th smallest firstCandidate among the nodes it would sum with every candidate
// lit, and the least of those. The nodes are visited smallest firstCandidate first (a node's
// children have at least its own), so the nodes a tile sums come in that order too: its walk
// stops at the cap, or once past the least limit found so far (it cannot lower it), and
// every walk stops once that is below floorPrefix (the candidates above the upper threshold:
// there is no band then, whatever the least is).
std::size_t longestFittingPrefix(const LightTree& tree, const std::vector<Tile>& tiles, double reach, int cap, std::size_t candidates,
                                 std::size_t floorPrefix)
{
    std::atomic<std::size_t> least{candidates};
    parallelRows(int(tiles.size()), [&](int first, int end) {
        auto later = [&](int a, int b) { return tree.nodes[std::size_t(a)].firstCandidate > tree.nodes[std::size_t(b)].firstCandidate; };
        std::vector<int> queue;
        for (int t = first; t < end && least.load(std::memory_order_relaxed) >= floorPrefix; ++t) {
            const Tile& tile = tiles[std::size_t(t)];
            const TileReach r = tileReach(tree, tile, reach);
            queue.clear();
            for (int root : tree.roots)
                if (nodeUse(tile, r, tree.nodes[std::size_t(root)]) != NodeUse::Skip)
                    queue.push_back(root);
            std::make_heap(queue.begin(), queue.end(), later);
            int summed = 0;
            while (!queue.empty()) {
                std::pop_heap(queue.begin(), queue.end(), later);
                const LightTree::Node& node = tree.nodes[std::size_t(queue.back())];
                queue.pop_back();
                std::size_t known = least.load(std::memory_order_relaxed);
                if (node.firstCandidate >= known)
                    break;
                const NodeUse use = nodeUse(tile, r, node);
                if (use == NodeUse::Sum && ++summed > cap) {
                    while (node.firstCandidate < known && !least.compare_exchange_weak(known, node.firstCandidate)) {
                    }
                    break;
                }
                if (use == NodeUse::Open)
                    for (int child : node.children)
                        if (child >= 0) {
                            queue.push_back(child);
                            std::push_heap(queue.begin(), queue.end(), later);
                        }
            }
        }
    }, kTilesPerThread);
    return least;
}

} // namespace

double bandReach(double roughness)
{
    // GGX's half vectors: the share of D(h) n.h beyond theta_h is alpha^2 / (alpha^2 +
    // tan^2 theta_h), and l is at twice theta_h; weighting by n.l instead only lowers the tail.
    const double alpha = std::max(roughness * roughness, 1e-6);
    return 2.0 * std::atan(alpha * std::sqrt((1.0 - kBandTailWeight) / kBandTailWeight));
}

TileLights planTileLights(const BrightCandidates& candidates, float upperThreshold, double roughness, int faceSize, int capPerTile,
                          double reach, float lowestThreshold, bool coarsenOverfull)
{
    TileLights out;
    out.threshold = upperThreshold;
    const std::size_t n = candidates.texels.size();
    if (capPerTile <= 0 || faceSize <= 0 || n == 0 || !(std::max(candidates.floorThreshold, lowestThreshold) < upperThreshold))
        return out;
    const int tilesPerEdge = std::max(1, faceSize / kTileLightsTile);
    std::vector<Tile> tiles = outputTiles(tilesPerEdge);

    // The threshold: the luminance of the first candidate past the longest prefix that fits
    // (the floor where all do), or lowestThreshold where that is higher; the lights are the
    // candidates strictly above it. Only below upperThreshold is there a band.
    const std::size_t aboveUpper = std::size_t(std::partition_point(candidates.texels.begin(), candidates.texels.end(),
                                                                    [&](const BrightTexel& t) { return t.luminance > upperThreshold; }) -
                                               candidates.texels.begin());
    LightTree tree;
    std::size_t prefix = 0;
    if (coarsenOverfull) {
        // The candidates that may be lit, each tile that cannot list them all merging coarser:
        // the search runs only where some tile overflows even so.
        const std::size_t litAtMost = std::size_t(std::partition_point(candidates.texels.begin(), candidates.texels.end(),
                                                                       [&](const BrightTexel& t) { return t.luminance > lowestThreshold; }) -
                                                  candidates.texels.begin());
        tree = lightTree(candidates, n, brightCellFaceSize(roughness));
        prefix = coarsenOverfullTiles(tree, tiles, reach, capPerTile, litAtMost) ? litAtMost
                                                                                 : longestFittingPrefix(tree, tiles, reach, capPerTile, litAtMost, aboveUpper);
    } else {
        // The tree of the first `built` candidates holds every node of a longer prefix whose
        // firstCandidate is below `built`, so a prefix it finds shorter than that is the prefix
        // of all of them: on a map with large bright areas the tiles fill within the first
        // thousand candidates of 16384, and building the tree of all of them took 20 ms.
        std::size_t built = std::min(n, std::max<std::size_t>(kFirstTreeCandidates, 2 * aboveUpper));
        for (;;) {
            tree = lightTree(candidates, built, brightCellFaceSize(roughness));
            prefix = longestFittingPrefix(tree, tiles, reach, capPerTile, built, aboveUpper);
            if (prefix < built || built == n)
                break;
            built = std::min(n, 4 * built);
        }
    }
    out.threshold = std::min(std::max(prefix < n ? candidates.texels[prefix].luminance : candidates.floorThreshold, lowestThreshold), upperThreshold);
    if (!(out.threshold < upperThreshold))
        return out;

    // The band's flux, from each lit candidate's finest node up to its root.
    std::size_t lit = 0;
    for (; lit < n && candidates.texels[lit].luminance > out.threshold; ++lit) {
        const BrightTexel& t = candidates.texels[lit];
        const double band = std::min(double(t.luminance), double(upperThreshold)) - double(out.threshold);
        const glm::dvec3 flux = t.radiance * (band / double(t.luminance)) * t.solidAngle;
        for (int node = tree.finestNode[lit]; node >= 0; node = tree.nodes[std::size_t(node)].parent) {
            tree.nodes[std::size_t(node)].flux += flux;
            tree.nodes[std::size_t(node)].weightedDirection += t.direction * luminance(flux);
        }
    }
    for (const LightTree::Node& node : tree.nodes)
        out.lights += node.level == 0 && node.firstCandidate < lit ? 1 : 0;
    std::vector<std::vector<glm::vec4>> lists(tiles.size());
    parallelRows(int(tiles.size()), [&](int first, int end) {
        for (int t = first; t < end; ++t)
            lists[std::size_t(t)] = tileLights(tree, tiles[std::size_t(t)], reach, lit);
    }, kTilesPerThread);
    out.tilesPerEdge = tilesPerEdge;
    std::size_t next = tiles.size();
    out.buffer.reserve(tiles.size());
    for (const std::vector<glm::vec4>& list : lists) {
        out.buffer.emplace_back(float(next), float(list.size() / 2), 0.0f, 0.0f);
        next += list.size();
        out.longestList = std::max(out.longestList, int(list.size() / 2));
    }
    for (const std::vector<glm::vec4>& list : lists)
        out.buffer.insert(out.buffer.end(), list.begin(), list.end());
    return out;
}

} // namespace iblab::bake
