#include "bake/near_lights.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>

#include "ibl/conventions.hpp"
#include "ibl/equirect.hpp"

namespace iblab::bake {
namespace {

// Each face's marks widened by radius texels along rows, then columns (a square max filter).
void dilateFaces(std::vector<std::uint8_t>& mask, int faceSize, int radius)
{
    std::vector<std::uint8_t> line(static_cast<std::size_t>(faceSize));
    for (int face = 0; face < 6; ++face) {
        std::uint8_t* texels = &mask[std::size_t(face) * std::size_t(faceSize) * std::size_t(faceSize)];
        for (int pass = 0; pass < 2; ++pass)
            for (int i = 0; i < faceSize; ++i) {
                // pass 0: row i; pass 1: column i.
                auto at = [&](int j) -> std::uint8_t& { return pass == 0 ? texels[i * faceSize + j] : texels[j * faceSize + i]; };
                for (int j = 0; j < faceSize; ++j)
                    line[std::size_t(j)] = at(j);
                // A running count of the marks in [j - radius, j + radius].
                int inWindow = 0;
                for (int k = 0; k < std::min(radius, faceSize); ++k)
                    inWindow += line[std::size_t(k)];
                for (int j = 0; j < faceSize; ++j) {
                    if (j + radius < faceSize)
                        inWindow += line[std::size_t(j + radius)];
                    if (j - radius - 1 >= 0)
                        inWindow -= line[std::size_t(j - radius - 1)];
                    at(j) = inWindow > 0 ? 1 : 0;
                }
            }
    }
}

} // namespace

std::vector<std::uint32_t> brightEdgeTexels(const BrightCandidates& candidates, float firstThreshold, float secondThreshold)
{
    const int width = candidates.sourceWidth, height = candidates.sourceHeight;
    if (width <= 0 || height <= 0)
        return {};
    const float lower = std::min(firstThreshold, secondThreshold), upper = std::max(firstThreshold, secondThreshold);
    // Every texel above either threshold is a candidate (the thresholds are at least the floor).
    std::vector<std::uint8_t> level(std::size_t(width) * std::size_t(height), 0); // 0: under both, 1: over the lower, 2: over both
    for (const BrightTexel& t : candidates.texels)
        if (t.luminance > lower && t.sourceIndex < level.size())
            level[t.sourceIndex] = t.luminance > upper ? 2 : 1;
    std::vector<std::uint32_t> edges;
    for (const BrightTexel& t : candidates.texels) {
        if (t.luminance <= lower || t.sourceIndex >= level.size())
            continue;
        const int x = int(t.sourceIndex % std::uint32_t(width)), y = int(t.sourceIndex / std::uint32_t(width));
        const std::uint8_t own = level[t.sourceIndex];
        bool edge = false;
        for (int dy = -kEdgeReach; dy <= kEdgeReach && !edge; ++dy)
            for (int dx = -kEdgeReach; dx <= kEdgeReach && !edge; ++dx) {
                const int nx = ((x + dx) % width + width) % width, ny = std::clamp(y + dy, 0, height - 1);
                edge = level[std::size_t(ny) * std::size_t(width) + std::size_t(nx)] < own;
            }
        if (edge)
            edges.push_back(t.sourceIndex);
    }
    return edges;
}

int nearLightsRadius(const BrightSplitPlan& plan, int faceSize)
{
    const double mapTexelInCubeTexels = (2.0 * kPi / double(std::max(plan.sourceWidth, 1))) / (2.0 / double(std::max(faceSize, 1)));
    return std::clamp(int(std::ceil(0.5 + 1.5 * mapTexelInCubeTexels)), 1, 8);
}

std::vector<std::uint8_t> nearLightsMarks(const BrightSplitPlan& plan, int faceSize)
{
    if (plan.sourceWidth <= 0 || plan.sourceHeight <= 0 || plan.edgeTexels.empty() || faceSize <= 0)
        return {};
    const int radius = nearLightsRadius(plan, faceSize);
    std::vector<std::uint8_t> mask(6 * std::size_t(faceSize) * std::size_t(faceSize), 0);
    auto mark = [&](const glm::dvec3& direction) {
        const glm::vec3 faceUv = directionToCubeFaceUv(glm::vec3(glm::normalize(direction)));
        const int face = int(faceUv.x);
        const int x = std::clamp(int(faceUv.y * float(faceSize)), 0, faceSize - 1);
        const int y = std::clamp(int(faceUv.z * float(faceSize)), 0, faceSize - 1);
        mask[(std::size_t(face) * std::size_t(faceSize) + std::size_t(y)) * std::size_t(faceSize) + std::size_t(x)] = 1;
    };
    // The texel's own cube texel, and four directions radius cube texels away diagonally: where
    // the reach crosses a face edge they mark the next face, which the dilation then fills in.
    const double reach = double(radius) * 2.0 / double(faceSize);
    const auto width = std::uint32_t(plan.sourceWidth);
    for (std::uint32_t index : plan.edgeTexels) {
        const glm::dvec3 d = equirectTexelDirection(int(index % width), int(index / width), plan.sourceWidth, plan.sourceHeight);
        const glm::dvec3 u = glm::normalize(glm::cross(d, std::abs(d.y) < 0.9 ? glm::dvec3(0.0, 1.0, 0.0) : glm::dvec3(1.0, 0.0, 0.0)));
        const glm::dvec3 v = glm::cross(d, u);
        mark(d);
        for (double a : {-1.0, 1.0})
            for (double b : {-1.0, 1.0})
                mark(d + reach * (a * u + b * v));
    }
    dilateFaces(mask, faceSize, radius);
    return mask;
}

std::vector<glm::ivec4> nearLightsBaseTexels(const std::vector<std::uint8_t>& marks, int faceSize, int step)
{
    std::vector<glm::ivec4> texels;
    if (step <= 0 || faceSize <= 0 || marks.size() != 6 * std::size_t(faceSize) * std::size_t(faceSize))
        return texels;
    const int baseSize = faceSize / step;
    for (int face = 0; face < 6; ++face)
        for (int y = 0; y < baseSize; ++y)
            for (int x = 0; x < baseSize; ++x) {
                bool marked = false;
                for (int dy = 0; dy < step && !marked; ++dy)
                    for (int dx = 0; dx < step && !marked; ++dx)
                        marked = marks[(std::size_t(face) * std::size_t(faceSize) + std::size_t(y * step + dy)) * std::size_t(faceSize) +
                                       std::size_t(x * step + dx)] != 0;
                if (marked)
                    texels.emplace_back(x, y, face, 0);
            }
    return texels;
}

} // namespace iblab::bake
