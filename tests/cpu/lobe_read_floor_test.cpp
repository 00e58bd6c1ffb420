// The fitted lobe's read floor (renderer/lab/accuracy_study/read_floor.hpp, `accuracy_study
// fit --read-floor`): how sharp a read of the prefiltered cube may be for the lobe it stands
// for. The committed table is not fitted with it (docs/accuracy-study.md, "Texel noise").
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "ibl/prefilter_lod.hpp"
#include "read_floor.hpp"

namespace iblab::accuracy {
namespace {

constexpr GeometryTerm kTerm = GeometryTerm::HeightCorrelatedSmith;

TEST(LobeReadFloor, ReadsWidenWithRoughness)
{
    double previous = 0.0;
    for (double r = 0.02; r <= 1.0; r += 0.02) {
        const double omega = prefilterReadSolidAngle(r);
        EXPECT_GT(omega, previous) << r;
        previous = omega;
    }
    // At a mip's own roughness the read is that mip's lobe alone. A narrow GGX lobe in l: D's
    // half maximum at tan^2(theta_h) = (sqrt 2 - 1) alpha^2, doubled by the reflection; its
    // effective solid angle is of order pi (2 alpha)^2, within a factor 3.
    const ReadChain chain;
    for (int mip = 1; mip <= 3; ++mip) {
        const double r = prefilterRoughnessFromMip(float(mip), float(chain.levels), chain.layout);
        const double alpha = r * r, scale = kPi * 4.0 * alpha * alpha;
        EXPECT_GT(prefilterReadSolidAngle(r), scale / 3.0) << r;
        EXPECT_LT(prefilterReadSolidAngle(r), scale * 3.0) << r;
    }
}

TEST(LobeReadFloor, FacingTheViewTheFloorIsTheCellsRoughness)
{
    // At n.v = 1 the A term's lobe over l is the prefilter's own (N = V = R) but for the
    // visibility and Fresnel factors, which barely bend a narrow lobe: the floor is the
    // cell's roughness, as the split sum reads it.
    for (double r : {0.2, 0.35, 0.5}) EXPECT_NEAR(readRoughnessFloor(0.999, r, kTerm).a, r, 0.1 * r) << r;
}

TEST(LobeReadFloor, GrazingLobesAllowSharperReads)
{
    // Towards grazing the true lobe is squeezed across the plane of N and V and cut by the
    // horizon, so a sharper read passes no more detail than it. Never wider than the cell.
    for (double r : {0.2, 0.35, 0.5}) {
        for (double nv : {0.97, 0.75, 0.5, 0.25, 0.05}) {
            const ReadRoughnessFloor floor = readRoughnessFloor(nv, r, kTerm);
            EXPECT_LE(floor.a, r + 1e-9);
            EXPECT_LE(floor.b, r + 1e-9);
        }
        EXPECT_LT(readRoughnessFloor(0.25, r, kTerm).a, 0.9 * r) << r;
        EXPECT_LT(readRoughnessFloor(0.25, r, kTerm).b, 0.85 * r) << r;
    }
}

} // namespace
} // namespace iblab::accuracy
