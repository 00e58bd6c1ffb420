#include "bake/exact_tiles.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "ibl/conventions.hpp"
#include "ibl/luminance.hpp"
#include "ibl/prefilter_lod.hpp"

namespace iblab::bake {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Past this spread every group that does not overlap a tile's cone is one of the 6 faces'.
constexpr double kMaxSpread = 64.0;

double angleBetween(const glm::dvec3& a, const glm::dvec3& b) { return std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0)); }

glm::dvec3 faceUvDirection(int face, double s, double t) { return glm::dvec3(cubeFaceUvToDirection(face, glm::vec2(float(s), float(t)))); }

// The largest angle between the direction at the centre of face region [s0, s1] x [t0, t1] and
// its corners: a cone around that centre holds the region, whose edges bulge outwards by
// less than the corners reach.
double regionRadius(int face, double s0, double s1, double t0, double t1, const glm::dvec3& centre)
{
    double radius = 0.0;
    for (double s : {s0, s1})
        for (double t : {t0, t1})
            radius = std::max(radius, angleBetween(centre, glm::normalize(faceUvDirection(face, s, t))));
    return radius;
}

// One texel of the source, or a square group of them within a face: its entry as the shader
// sums it, and the cone around its centre that holds it.
struct Group {
    glm::dvec3 flux{0.0};
    double solidAngle = 0.0;
    glm::dvec3 luminanceMoment{0.0}; // sum of luminance x solid angle x direction
    glm::vec3 direction{0.0f};       // the entry's: the texel's centre, a group's flux centre
    glm::dvec3 centre{0.0};
    double radius = 0.0;
};

// Level k of the pyramid has faces of source.size >> k groups per edge, each the 2 x 2 of
// level k - 1 below it; level 0 is the source's texels, entered as exactSumTexels enters them.
std::vector<std::vector<Group>> buildPyramid(const CubeImage& source)
{
    std::vector<std::vector<Group>> levels;
    const int size = source.size;
    std::vector<Group>& texels = levels.emplace_back(std::size_t(6) * std::size_t(size) * std::size_t(size));
    for (int face = 0; face < 6; ++face)
        for (int row = 0; row < size; ++row)
            for (int x = 0; x < size; ++x) {
                Group& g = texels[source.index(face, x, row)];
                const ExactSumEntry entry = exactSumEntry(source, face, x, row);
                g.direction = entry.direction;
                g.centre = glm::dvec3(g.direction);
                g.solidAngle = double(entry.solidAngle);
                g.flux = glm::dvec3(entry.flux);
                g.luminanceMoment = luminance(g.flux) * g.centre;
                g.radius = regionRadius(face, double(x) / size, double(x + 1) / size, double(row) / size, double(row + 1) / size, g.centre);
            }
    for (int s = size / 2; s >= 1; s /= 2) {
        const std::vector<Group>& finer = levels.back();
        std::vector<Group> coarser(std::size_t(6) * std::size_t(s) * std::size_t(s));
        for (int face = 0; face < 6; ++face)
            for (int row = 0; row < s; ++row)
                for (int x = 0; x < s; ++x) {
                    Group& g = coarser[(std::size_t(face) * std::size_t(s) + std::size_t(row)) * std::size_t(s) + std::size_t(x)];
                    glm::dvec3 geometric(0.0);
                    for (int dy = 0; dy < 2; ++dy)
                        for (int dx = 0; dx < 2; ++dx) {
                            const Group& c = finer[(std::size_t(face) * std::size_t(2 * s) + std::size_t(2 * row + dy)) * std::size_t(2 * s) + std::size_t(2 * x + dx)];
                            g.flux += c.flux;
                            g.solidAngle += c.solidAngle;
                            g.luminanceMoment += c.luminanceMoment;
                            geometric += c.solidAngle * c.centre;
                        }
                    g.centre = glm::normalize(geometric);
                    const double luminanceFlux = glm::length(g.luminanceMoment);
                    g.direction = glm::vec3(luminanceFlux > 0.0 ? g.luminanceMoment / luminanceFlux : g.centre);
                    g.radius = regionRadius(face, double(x) / s, double(x + 1) / s, double(row) / s, double(row + 1) / s, g.centre);
                }
        levels.push_back(std::move(coarser));
    }
    return levels;
}

struct Tile {
    glm::dvec3 centre;
    double radius;
};

// The cut of one tile at `spread`: the groups it lists, or more than maxEntries of them.
std::vector<const Group*> cutFor(const std::vector<std::vector<Group>>& pyramid, int sourceSize, const Tile& tile, double spread, int maxEntries)
{
    struct Node {
        int level, face, x, row;
    };
    std::vector<const Group*> cut;
    std::vector<Node> stack;
    const int top = int(pyramid.size()) - 1;
    for (int face = 5; face >= 0; --face)
        stack.push_back({top, face, 0, 0});
    while (!stack.empty() && int(cut.size()) <= maxEntries) {
        const Node node = stack.back();
        stack.pop_back();
        const int s = sourceSize >> node.level;
        const Group& g = pyramid[std::size_t(node.level)][(std::size_t(node.face) * std::size_t(s) + std::size_t(node.row)) * std::size_t(s) + std::size_t(node.x)];
        const double distance = angleBetween(g.centre, tile.centre) - tile.radius - g.radius;
        if (distance >= 0.5 * kPi)
            continue; // below the horizon of every texel of the tile
        if (node.level == 0 || 2.0 * g.radius <= spread * distance) {
            cut.push_back(&g);
            continue;
        }
        for (int dy = 1; dy >= 0; --dy)
            for (int dx = 1; dx >= 0; --dx)
                stack.push_back({node.level - 1, node.face, 2 * node.x + dx, 2 * node.row + dy});
    }
    return cut;
}

} // namespace

ExactSumEntry exactSumEntry(const CubeImage& level, int face, int x, int row)
{
    const glm::vec3 direction = level.texelDirection(face, x, row);
    const float solidAngle = cubeTexelSolidAngle(direction, float(level.size));
    return {direction, level.rgb(face, x, row) * solidAngle, solidAngle};
}

ExactTiles exactSumTiles(const CubeImage& source, int outputFaceSize, int maxEntries, int alignmentVec4, int padVec4, double spread)
{
    ExactTiles tiles;
    if (source.size <= 0 || outputFaceSize <= 0 || maxEntries <= 0)
        return tiles;
    const std::vector<std::vector<Group>> pyramid = buildPyramid(source);
    tiles.tilesPerEdge = (outputFaceSize + kExactTileTexels - 1) / kExactTileTexels;
    const int alignment = std::max(alignmentVec4, 1);
    for (int face = 0; face < 6; ++face)
        for (int ty = 0; ty < tiles.tilesPerEdge; ++ty)
            for (int tx = 0; tx < tiles.tilesPerEdge; ++tx) {
                const double s0 = double(tx * kExactTileTexels) / outputFaceSize;
                const double s1 = double(std::min((tx + 1) * kExactTileTexels, outputFaceSize)) / outputFaceSize;
                const double t0 = double(ty * kExactTileTexels) / outputFaceSize;
                const double t1 = double(std::min((ty + 1) * kExactTileTexels, outputFaceSize)) / outputFaceSize;
                Tile tile;
                tile.centre = glm::normalize(faceUvDirection(face, 0.5 * (s0 + s1), 0.5 * (t0 + t1)));
                tile.radius = regionRadius(face, s0, s1, t0, t1, tile.centre);
                // A tile whose cut does not fit is cut coarser: its far groups widen first. The
                // texels that overlap the tile's cone stay texels, so a block too small for
                // them gets no tiles at all (the mip is then sampled).
                std::vector<const Group*> cut;
                for (double tileSpread = spread; tileSpread <= kMaxSpread; tileSpread *= 1.25) {
                    cut = cutFor(pyramid, source.size, tile, tileSpread, maxEntries);
                    if (int(cut.size()) <= maxEntries)
                        break;
                }
                if (int(cut.size()) > maxEntries)
                    return {};
                tiles.buffer.resize((tiles.buffer.size() + std::size_t(alignment) - 1) / std::size_t(alignment) * std::size_t(alignment), glm::vec4(0.0f));
                tiles.first.push_back(int(tiles.buffer.size()));
                tiles.count.push_back(int(cut.size()));
                tiles.largest = std::max(tiles.largest, int(cut.size()));
                for (const Group* g : cut) {
                    tiles.buffer.emplace_back(g->direction, 0.0f);
                    tiles.buffer.emplace_back(glm::vec3(g->flux), float(g->solidAngle));
                }
            }
    tiles.buffer.resize(tiles.buffer.size() + std::size_t(std::max(padVec4, 0)), glm::vec4(0.0f));
    return tiles;
}

} // namespace iblab::bake
