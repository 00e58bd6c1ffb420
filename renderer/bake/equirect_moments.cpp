#include "bake/equirect_moments.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <utility>

#include <glm/vec3.hpp>

#include "ibl/conventions.hpp"
#include "ibl/equirect.hpp"
#include "ibl/luminance.hpp"
#include "ibl/parallel_rows.hpp"

namespace iblab::bake {
namespace {

// A group's sums before they are normalised, in double.
struct GroupSums {
    glm::dvec3 flux{0.0};
    std::array<glm::dvec3, 3> moment{}; // per channel: sum of L_c omega w
    double fluxY = 0.0;
    glm::dvec3 momentY{0.0};
    glm::dvec3 secondDiagonal{0.0}; // xx, yy, zz
    glm::dvec3 secondOff{0.0};      // xy, xz, yz

    void add(const GroupSums& o)
    {
        flux += o.flux;
        for (int c = 0; c < 3; ++c) moment[std::size_t(c)] += o.moment[std::size_t(c)];
        fluxY += o.fluxY;
        momentY += o.momentY;
        secondDiagonal += o.secondDiagonal;
        secondOff += o.secondOff;
    }
};

constexpr int kGroupStride = 8;

// The longitude's terms of one column: a row's texels share theta, so w = (sin theta sin phi,
// cos theta, -sin theta cos phi), and a run's moments are its sums over these, scaled once.
struct Column {
    double sinPhi = 0.0, cosPhi = 0.0;
};

// A run of one row's texels in one group: sums over the run of L_c, L_c sin phi and L_c
// cos phi per channel, and of the luminance y (with its floor) times 1, sin phi, cos phi,
// sin^2 phi, cos^2 phi and sin phi cos phi.
struct Run {
    std::array<double, 9> channel{};
    std::array<double, 6> luminance{};

    void add(const float* texel, const Column& col)
    {
        for (int c = 0; c < 3; ++c) {
            channel[std::size_t(3 * c)] += texel[c];
            channel[std::size_t(3 * c + 1)] += texel[c] * col.sinPhi;
            channel[std::size_t(3 * c + 2)] += texel[c] * col.cosPhi;
        }
        // Rec. 709 luminance; the 1e-6 floor gives a black group the spread of its texels'
        // directions, so that irradiance_moments.comp's lobe width stays that of the group.
        const double y = iblab::luminance(glm::dvec3(texel[0], texel[1], texel[2])) + 1e-6;
        luminance[0] += y;
        luminance[1] += y * col.sinPhi;
        luminance[2] += y * col.cosPhi;
        luminance[3] += y * col.sinPhi * col.sinPhi;
        luminance[4] += y * col.cosPhi * col.cosPhi;
        luminance[5] += y * col.sinPhi * col.cosPhi;
    }

    GroupSums sums(double omega, double sinTheta, double cosTheta) const
    {
        GroupSums g;
        for (int c = 0; c < 3; ++c) {
            const double l = channel[std::size_t(3 * c)], ls = channel[std::size_t(3 * c + 1)], lc = channel[std::size_t(3 * c + 2)];
            g.flux[c] = omega * l;
            g.moment[std::size_t(c)] = omega * glm::dvec3(sinTheta * ls, cosTheta * l, -sinTheta * lc);
        }
        const auto [y, ys, yc, yss, ycc, ysc] = luminance;
        g.fluxY = omega * y;
        g.momentY = omega * glm::dvec3(sinTheta * ys, cosTheta * y, -sinTheta * yc);
        const double s2 = sinTheta * sinTheta;
        g.secondDiagonal = omega * glm::dvec3(s2 * yss, cosTheta * cosTheta * y, s2 * ycc);
        g.secondOff = omega * glm::dvec3(sinTheta * cosTheta * ys, -s2 * ysc, -sinTheta * cosTheta * yc);
        return g;
    }
};

// The group, a texel of a groupsPerEdge^2 cube, that direction d falls in, where the GPU's
// cube lookup places it.
int groupOf(const glm::vec3& d, int groupsPerEdge)
{
    const glm::vec3 faceUv = directionToCubeFaceUv(d);
    const float edge = float(groupsPerEdge);
    const int column = std::clamp(int(faceUv.y * edge), 0, groupsPerEdge - 1);
    const int row = std::clamp(int(faceUv.z * edge), 0, groupsPerEdge - 1);
    return (int(faceUv.x) * groupsPerEdge + row) * groupsPerEdge + column;
}

} // namespace

std::vector<glm::vec4> equirectMomentTexels(const ImageRGB32F& map, int groupsPerEdge)
{
    const std::size_t groups = std::size_t(6) * std::size_t(groupsPerEdge) * std::size_t(groupsPerEdge);
    // conventions.glsl's equirectUvToDirection at the texel centres, in double.
    std::vector<Column> columns(std::size_t(map.width));
    for (int x = 0; x < map.width; ++x) {
        const double phi = ((double(x) + 0.5) / double(map.width) - 0.5) * 2.0 * kPi;
        columns[std::size_t(x)] = {std::sin(phi), std::cos(phi)};
    }
    // Each band of rows sums into its own groups, and the bands are added in order: the bands
    // are fixed by the map's height, not by the thread count, so neither is the result. Eight
    // of them: each band's sums are fresh memory, whose pages cost about 10 us each to fault in
    // on this project's 2-core VMs (32 bands, 2 MB, took 6 ms of a 9 ms call).
    const int bands = std::min(map.height, 8);
    const int bandRows = (map.height + bands - 1) / bands;
    std::vector<GroupSums> bandSums(std::size_t(bands) * groups);
    parallelRows(bands, [&](int firstBand, int endBand) {
        for (int band = firstBand; band < endBand; ++band) {
            GroupSums* sums = &bandSums[std::size_t(band) * groups];
            for (int y = band * bandRows; y < std::min(map.height, (band + 1) * bandRows); ++y) {
                const double omega = equirectTexelSolidAngle(y, map.width, map.height);
                const double theta = (double(y) + 0.5) / double(map.height) * kPi;
                const double sinTheta = std::sin(theta), cosTheta = std::cos(theta);
                // A row crosses each group in one or two runs of texels. The group is found
                // every kGroupStride texels, and texel by texel only where it changes: a run
                // shorter than that, a corner of a group, is then summed with its neighbour,
                // which moves its light by a fraction of a group and none of it out of the sum.
                auto group = [&](int x) {
                    const Column& col = columns[std::size_t(x)];
                    return groupOf(glm::vec3(float(sinTheta * col.sinPhi), float(cosTheta), float(-sinTheta * col.cosPhi)), groupsPerEdge);
                };
                Run run;
                int runGroup = group(0);
                const float* row = &map.texels[map.offset(0, y)];
                for (int x = 0; x < map.width; x += kGroupStride) {
                    const int end = std::min(x + kGroupStride, map.width);
                    const bool changes = group(end - 1) != runGroup;
                    for (int i = x; i < end; ++i) {
                        if (changes) {
                            const int g = group(i);
                            if (g != runGroup) {
                                sums[runGroup].add(run.sums(omega, sinTheta, cosTheta));
                                run = {};
                                runGroup = g;
                            }
                        }
                        run.add(row + 3 * std::size_t(i), columns[std::size_t(i)]);
                    }
                }
                sums[runGroup].add(run.sums(omega, sinTheta, cosTheta));
            }
        }
    });
    std::vector<GroupSums> total(groups);
    for (int band = 0; band < bands; ++band)
        for (std::size_t g = 0; g < groups; ++g) total[g].add(bandSums[std::size_t(band) * groups + g]);
    std::vector<glm::vec4> out;
    out.reserve(groups * 6);
    for (const GroupSums& s : total) {
        // A black channel contributes nothing; its moment only has to be finite.
        const glm::dvec3 safe = glm::max(s.flux, glm::dvec3(1e-30));
        const double fluxY = std::max(s.fluxY, 1e-30);
        const glm::dvec3 sDiagonal = s.secondDiagonal / fluxY, sOff = s.secondOff / fluxY;
        out.emplace_back(glm::vec3(s.flux), 0.0f);
        out.emplace_back(glm::vec3(s.moment[0] / safe.x), float(sDiagonal.x));
        out.emplace_back(glm::vec3(s.moment[1] / safe.y), float(sDiagonal.y));
        out.emplace_back(glm::vec3(s.moment[2] / safe.z), float(sDiagonal.z));
        out.emplace_back(glm::vec3(s.momentY / fluxY), float(sOff.x));
        out.emplace_back(float(sOff.y), float(sOff.z), 0.0f, 0.0f);
    }
    return out;
}

} // namespace iblab::bake
