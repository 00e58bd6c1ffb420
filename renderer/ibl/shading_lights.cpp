#include "ibl/shading_lights.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "ibl/brdf.hpp"
#include "ibl/conventions.hpp"
#include "ibl/equirect.hpp"
#include "ibl/luminance.hpp"
#include "ibl/parallel_rows.hpp"
#include "ibl/reference.hpp"

namespace iblab {
namespace {

// The grid cell on a face of `cells` x `cells` that direction d falls in, as an index
// [(face * cells + row) * cells + x], and where in the cell (0..1 each way).
struct GridCell {
    std::uint32_t index;
    glm::vec2 within;
};

GridCell gridCellOf(glm::vec3 d, int cells)
{
    const glm::vec3 fst = directionToCubeFaceUv(d);
    const int face = std::clamp(int(fst.x + 0.5f), 0, 5);
    const float s = fst.y * float(cells), t = fst.z * float(cells);
    const int x = std::clamp(int(s), 0, cells - 1), row = std::clamp(int(t), 0, cells - 1);
    return {std::uint32_t((face * cells + row) * cells + x), glm::clamp(glm::vec2(s - float(x), t - float(row)), 0.0f, 0.999f)};
}

// The directions of an equirect's texel centres (equirectUvToDirection's formula) from one
// sine and cosine per row and per column.
class EquirectDirections {
public:
    EquirectDirections(int width, int height)
    {
        for (int x = 0; x < width; ++x) {
            const float phi = ((float(x) + 0.5f) / float(width) - 0.5f) * (2.0f * float(kPi));
            columns_.emplace_back(std::sin(phi), std::cos(phi));
        }
        for (int y = 0; y < height; ++y) {
            const float theta = (float(y) + 0.5f) / float(height) * float(kPi);
            rows_.emplace_back(std::sin(theta), std::cos(theta));
        }
    }
    glm::vec3 at(int x, int y) const
    {
        const glm::vec2 c = columns_[std::size_t(x)], r = rows_[std::size_t(y)];
        return {r.x * c.x, r.y, -r.x * c.y};
    }

private:
    std::vector<glm::vec2> columns_, rows_; // (sin, cos) of phi and of theta
};

struct GroupSum {
    double luminanceFlux = 0.0; // luminance x solid angle
    double solidAngle = 0.0;
    double mean() const { return solidAngle > 0.0 ? luminanceFlux / solidAngle : 0.0; }
};

// The lights' excess as flux and flux-weighted direction sums, turned into centroids.
struct Accumulator {
    glm::dvec3 flux{0.0}, centroid{0.0};
    void add(glm::dvec3 excess, glm::dvec3 direction)
    {
        flux += excess;
        centroid += double(luminance(glm::vec3(excess))) * direction;
    }
    ShadingLight light() const { return {glm::vec3(glm::normalize(centroid)), glm::vec3(flux)}; }
    bool empty() const { return !(glm::length(centroid) > 0.0); }
};

} // namespace

float ShadingLights::minAlpha() const
{
    // GGX's highlight is 2.57 alpha across at half its peak (D ~ 1 / (alpha^2 + theta_h^2)^2,
    // theta_l = 2 theta_h): that width equals a group's (at a face's centre) at this alpha.
    return float(0.5 * kPi / double(grid) / 2.57);
}

std::vector<ShadingLight> ShadingLights::lights() const
{
    std::vector<ShadingLight> out;
    for (const ShadingLightGroup& g : groups) out.push_back(g.light);
    return out;
}

ShadingLights findShadingLights(const ImageRGB32F& source, int maxLights, int grid)
{
    ShadingLights result;
    result.grid = std::max(grid, 1);
    if (source.empty() || maxLights <= 0) return result;
    // The map in blocks of edge x edge texels, each about a quarter of a group across (0.35 degrees
    // at the default grid) and placed at its centre: fine enough to find the groups and place
    // their flux, and a 4096-wide map costs one read of its texels, no copy of it.
    const int w = source.width, h = source.height;
    const int edge = std::max(1, w / (16 * result.grid));
    const int blocksW = (w + edge - 1) / edge, blocksH = (h + edge - 1) / edge;
    const EquirectDirections directions(blocksW, blocksH);
    std::vector<double> rowSolidAngle(static_cast<std::size_t>(h));
    for (int y = 0; y < h; ++y) rowSolidAngle[std::size_t(y)] = equirectTexelSolidAngle(y, w, h);
    // A block's radiance x solid angle (RGB), and its solid angle.
    auto blockFlux = [&](int bx, int by, double& solidAngle) {
        glm::dvec3 flux(0.0);
        solidAngle = 0.0;
        for (int y = by * edge; y < std::min(h, (by + 1) * edge); ++y)
            for (int x = bx * edge; x < std::min(w, (bx + 1) * edge); ++x) {
                const glm::vec3 c = source.at(x, y);
                if (!std::isfinite(luminance(c))) continue;
                flux += glm::dvec3(c) * rowSolidAngle[std::size_t(y)];
                solidAngle += rowSolidAngle[std::size_t(y)];
            }
        return flux;
    };
    std::vector<GroupSum> groups(std::size_t(6) * std::size_t(result.grid) * std::size_t(result.grid));
    std::vector<std::uint32_t> groupOfBlock(std::size_t(blocksW) * std::size_t(blocksH));
    std::vector<GroupSum> blockSums(groupOfBlock.size());
    // Blocks in parallel; the sums into groups in block order, so that they do not depend on
    // the thread count.
    parallelRows(blocksH, [&](int begin, int end) {
        for (int by = begin; by < end; ++by)
            for (int bx = 0; bx < blocksW; ++bx) {
                const std::size_t block = std::size_t(by) * std::size_t(blocksW) + std::size_t(bx);
                groupOfBlock[block] = gridCellOf(directions.at(bx, by), result.grid).index;
                GroupSum& sum = blockSums[block];
                sum.luminanceFlux = double(luminance(glm::vec3(blockFlux(bx, by, sum.solidAngle))));
            }
    });
    double mapFlux = 0.0;
    for (std::size_t block = 0; block < blockSums.size(); ++block) {
        GroupSum& g = groups[groupOfBlock[block]];
        g.luminanceFlux += blockSums[block].luminanceFlux;
        g.solidAngle += blockSums[block].solidAngle;
        mapFlux += blockSums[block].luminanceFlux;
    }

    std::vector<std::uint32_t> order(groups.size());
    std::iota(order.begin(), order.end(), 0u);
    const std::size_t lights = std::min(std::size_t(maxLights), groups.size() - 1);
    std::partial_sort(order.begin(), order.begin() + std::ptrdiff_t(lights + 1), order.end(), [&](std::uint32_t a, std::uint32_t b) {
        return groups[a].mean() != groups[b].mean() ? groups[a].mean() > groups[b].mean() : a < b;
    });
    const double threshold = groups[order[lights]].mean();
    std::vector<int> lightOfGroup(groups.size(), -1);
    std::vector<float> keep;
    for (std::size_t i = 0; i < lights; ++i) {
        const double mean = groups[order[i]].mean();
        if (!(mean > threshold)) break;
        lightOfGroup[order[i]] = int(keep.size());
        keep.push_back(float(threshold / mean));
    }

    const int k = kShadingLightPointsPerEdge;
    std::vector<Accumulator> lightSums(keep.size()), pointSums(keep.size() * std::size_t(k * k));
    for (int by = 0; by < blocksH; ++by)
        for (int bx = 0; bx < blocksW; ++bx) {
            const int light = lightOfGroup[groupOfBlock[std::size_t(by) * std::size_t(blocksW) + std::size_t(bx)]];
            if (light < 0) continue;
            const glm::vec3 d = directions.at(bx, by);
            const GridCell cell = gridCellOf(d, result.grid);
            double solidAngle = 0.0;
            const glm::dvec3 excess = blockFlux(bx, by, solidAngle) * double(1.0f - keep[std::size_t(light)]);
            lightSums[std::size_t(light)].add(excess, glm::dvec3(d));
            const int point = int(cell.within.y * float(k)) * k + int(cell.within.x * float(k));
            pointSums[std::size_t(light) * std::size_t(k * k) + std::size_t(point)].add(excess, glm::dvec3(d));
        }
    for (std::size_t i = 0; i < lights && lightOfGroup[order[i]] >= 0; ++i) {
        const std::size_t light = std::size_t(lightOfGroup[order[i]]);
        const Accumulator& sum = lightSums[light];
        if (sum.empty() || double(luminance(glm::vec3(sum.flux))) < kMinShadingLightShare * mapFlux) continue;
        ShadingLightGroup g;
        g.light = sum.light();
        g.face = int(order[i] / std::uint32_t(result.grid * result.grid));
        g.row = int(order[i] / std::uint32_t(result.grid) % std::uint32_t(result.grid));
        g.x = int(order[i] % std::uint32_t(result.grid));
        g.keep = keep[light];
        for (int p = 0; p < k * k; ++p)
            if (!pointSums[light * std::size_t(k * k) + std::size_t(p)].empty()) g.points.push_back(pointSums[light * std::size_t(k * k) + std::size_t(p)].light());
        result.groups.push_back(std::move(g));
    }
    return result;
}

namespace {

glm::vec3 cubeTexelDirection(int size, int face, int x, int row)
{
    return cubeFaceUvToDirection(face, glm::vec2((float(x) + 0.5f) / float(size), (float(row) + 0.5f) / float(size)));
}

} // namespace

ShadingLightKernel shadingLightKernel(double roughness, int grid)
{
    const double alpha = roughness * roughness;
    ShadingLightKernel k;
    k.alpha2 = alpha * alpha;
    k.scale = k.alpha2 / (kPi * ggxPrefilterNormalization(roughness));
    // Beyond this angle from a light its group's spread changes the kernel by about
    // (spread / angle)^2 < 1/64 of its value: the centroid stands for the group there.
    const double groupAngle = 0.5 * kPi / double(grid);
    k.cosNear = std::cos(std::min(0.5 * kPi, 8.0 * (alpha + groupAngle)));
    return k;
}

void subtractShadingLights(CubeLevelRgb& mip, double roughness, const ShadingLights& lights)
{
    const ShadingLightKernel kernel = shadingLightKernel(roughness, lights.grid);
    const double a2 = kernel.alpha2, scale = kernel.scale, cosNear = kernel.cosNear;
    auto term = [a2](double c) { return ggxPrefilterWeight(c, 1.0 - c, a2); };
    // Rows of all six faces, face-major: each texel is its own, so the bands need no merging.
    parallelRows(6 * mip.size, [&](int firstRow, int endRow) {
        for (int faceRow = firstRow; faceRow < endRow; ++faceRow)
            for (int x = 0; x < mip.size; ++x) {
                const int face = faceRow / mip.size, row = faceRow % mip.size;
                const glm::dvec3 n(cubeTexelDirection(mip.size, face, x, row));
                glm::dvec3 sum(0.0);
                for (const ShadingLightGroup& g : lights.groups) {
                    const double c = glm::dot(n, glm::dvec3(g.light.direction));
                    if (c > cosNear)
                        for (const ShadingLight& p : g.points) sum += glm::dvec3(p.flux) * term(glm::dot(n, glm::dvec3(p.direction)));
                    else if (c > 0.0)
                        sum += glm::dvec3(g.light.flux) * term(c);
                }
                glm::vec3& texel = mip.texels[std::size_t(faceRow) * std::size_t(mip.size) + std::size_t(x)];
                texel = glm::max(glm::vec3(glm::dvec3(texel) - scale * sum), glm::vec3(0.0f));
            }
    });
}

MirrorBlock mirrorBlock(const ShadingLightGroup& group, int grid, int size)
{
    if (grid <= 0 || size % grid != 0)
        throw std::invalid_argument("shading lights on a grid of " + std::to_string(grid) + " over a mirror of " + std::to_string(size) + " texels");
    const int texels = size / grid;
    return {group.face, group.x * texels, group.row * texels, texels};
}

void keepInMirror(CubeLevelRgb& mip0, const ShadingLights& lights)
{
    for (const ShadingLightGroup& g : lights.groups) {
        const MirrorBlock b = mirrorBlock(g, lights.grid, mip0.size);
        for (int row = b.row; row < b.row + b.texels; ++row)
            for (int x = b.x; x < b.x + b.texels; ++x)
                mip0.texels[(std::size_t(b.face) * std::size_t(mip0.size) + std::size_t(row)) * std::size_t(mip0.size) + std::size_t(x)] *= g.keep;
    }
}

glm::dvec3 shadingLightsIrradiance(const std::vector<ShadingLight>& lights, glm::dvec3 n)
{
    glm::dvec3 sum(0.0);
    for (const ShadingLight& light : lights) sum += glm::dvec3(light.flux) * std::max(0.0, glm::dot(n, glm::dvec3(light.direction)));
    return sum;
}

void subtractShadingLightsIrradiance(CubeLevelRgb& cube, const std::vector<ShadingLight>& lights)
{
    for (int face = 0; face < 6; ++face)
        for (int row = 0; row < cube.size; ++row)
            for (int x = 0; x < cube.size; ++x) {
                glm::vec3& texel = cube.texels[(std::size_t(face) * std::size_t(cube.size) + std::size_t(row)) * std::size_t(cube.size) + std::size_t(x)];
                const glm::dvec3 lit = shadingLightsIrradiance(lights, glm::dvec3(cubeTexelDirection(cube.size, face, x, row)));
                texel = glm::max(glm::vec3(glm::dvec3(texel) - lit), glm::vec3(0.0f));
            }
}

SH9Color shadingLightsShIrradiance(const std::vector<ShadingLight>& lights)
{
    SH9Color radiance;
    for (const ShadingLight& light : lights) {
        const std::array<double, kSh9Count> basis = sh9Basis(glm::dvec3(light.direction));
        for (int i = 0; i < kSh9Count; ++i) radiance.c[std::size_t(i)] += glm::dvec3(light.flux) * basis[std::size_t(i)];
    }
    return convolveWithCosineLobe(radiance);
}

std::vector<CubeLevelRgb> shadingLightResidual(std::vector<CubeLevelRgb> chain, const std::vector<double>& mipRoughness, const ShadingLights& lights)
{
    if (chain.size() != mipRoughness.size())
        throw std::invalid_argument("shadingLightResidual: " + std::to_string(chain.size()) + " levels and " + std::to_string(mipRoughness.size()) +
                                    " roughnesses");
    for (const CubeLevelRgb& level : chain)
        if (level.size <= 0 || level.texels.size() != std::size_t(6) * std::size_t(level.size) * std::size_t(level.size))
            throw std::invalid_argument("shadingLightResidual: a level of size " + std::to_string(level.size) + " holds " +
                                        std::to_string(level.texels.size()) + " texels");
    if (lights.groups.empty()) return chain;
    for (std::size_t m = 0; m < chain.size(); ++m) {
        if (mipRoughness[m] > 0.0) subtractShadingLights(chain[m], mipRoughness[m], lights);
        else keepInMirror(chain[m], lights);
    }
    return chain;
}

} // namespace iblab
