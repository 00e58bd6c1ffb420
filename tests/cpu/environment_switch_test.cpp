// The environment switch's phases (app/environment_switch.hpp) without GL: which phases hold
// the view's last image, when the switch is busy (a recent map waiting for the next pump
// included), and that its timing runs from the request through the decode and the bake to the
// first frame presented.
#include <chrono>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "environment_switch.hpp"

namespace iblab::app {
namespace {

using Phase = EnvironmentSwitch::Phase;
using Clock = EnvironmentSwitch::Clock;

TEST(EnvironmentSwitch, HoldsTheLastImageUntilItsOwnBakeIsShown)
{
    EnvironmentSwitch s;
    EXPECT_EQ(s.phase(), Phase::Idle);
    EXPECT_FALSE(s.holdsLastImage());
    EXPECT_FALSE(s.busy());

    s.timeFrom("builtin:sky?width=64");
    s.begin("builtin:sky?width=64");
    s.startDecode();
    EXPECT_EQ(s.phase(), Phase::Decoding);
    EXPECT_TRUE(s.holdsLastImage());
    EXPECT_TRUE(s.busy());
    EXPECT_TRUE(s.loading());
    s.waitForDecode(std::chrono::minutes(1));
    ASSERT_TRUE(s.decodeReady());
    EXPECT_EQ(s.takeDecoded().image.width, 64);
    s.baking();
    EXPECT_TRUE(s.holdsLastImage()) << "the new sky never shows with the old lighting";
    EXPECT_FALSE(s.loading());

    s.bakeShown(/*fromCache=*/false);
    EXPECT_EQ(s.phase(), Phase::AwaitingFrame);
    EXPECT_FALSE(s.holdsLastImage());
    EXPECT_FALSE(s.busy());
    EXPECT_TRUE(s.awaitsFrame());
    EXPECT_FALSE(s.lastSwitch());
    s.frameDrawn(Clock::now());
    EXPECT_EQ(s.phase(), Phase::Idle);
    ASSERT_TRUE(s.lastSwitch());
    EXPECT_EQ(s.lastSwitch()->environment, "builtin:sky?width=64");
    EXPECT_GT(s.lastSwitch()->loadMs, 0.0);
    EXPECT_GE(s.lastSwitch()->bakeMs, s.lastSwitch()->loadMs);
    EXPECT_GE(s.lastSwitch()->firstFrameMs, s.lastSwitch()->bakeMs);
}

// A bake read early from the cache is shown before the file decodes: the view draws it, and
// the decode that confirms it comes after its first frame.
TEST(EnvironmentSwitch, ARecentMapWaitsForTheNextPumpWithoutChangingThePhase)
{
    EnvironmentSwitch s;
    s.timeFrom("a.exr");
    s.showRecentNext("a.exr");
    EXPECT_TRUE(s.busy()) << "the pump that shows it is still to come";
    EXPECT_EQ(s.phase(), Phase::Idle) << "the view shows what it showed until that pump";
    EXPECT_FALSE(s.loading());
    s.showRecentNext("b.exr"); // a later request replaces it
    EXPECT_EQ(s.takeRecentNext(), std::optional<std::string>("b.exr"));
    EXPECT_FALSE(s.takeRecentNext()) << "shown once";
    EXPECT_FALSE(s.busy());

    s.showRecentNext("a.exr");
    s.dropRecentNext(); // a switch to a map that is not recent
    EXPECT_FALSE(s.takeRecentNext());
    EXPECT_FALSE(s.busy());
}

TEST(EnvironmentSwitch, AnEarlyBakeIsDrawnAndTheDecodeFollowsItsFirstFrame)
{
    EnvironmentSwitch s;
    s.timeFrom("builtin:sun?width=64");
    s.begin("builtin:sun?width=64");
    s.beginEarlyBake(/*contentHash=*/42, /*previous=*/nullptr);
    EXPECT_EQ(s.phase(), Phase::EarlyBake);
    EXPECT_TRUE(s.holdsLastImage());
    EXPECT_FALSE(s.decodeWaits()) << "the decode waits for the early bake";

    s.earlyBakeShown("baked in 5 ms (from cache)", /*fromCache=*/true);
    EXPECT_EQ(s.phase(), Phase::EarlyBakeShown);
    EXPECT_FALSE(s.holdsLastImage());
    EXPECT_TRUE(s.busy()) << "the file still has to decode";
    EXPECT_TRUE(s.awaitsFrame());
    s.frameDrawn(Clock::now());
    ASSERT_TRUE(s.lastSwitch());
    EXPECT_TRUE(s.lastSwitch()->fromCache);
    EXPECT_EQ(s.lastSwitch()->loadMs, 0.0) << "not decoded yet";
    EXPECT_FALSE(s.awaitsFrame());

    ASSERT_TRUE(s.decodeWaits());
    s.startDecode();
    s.waitForDecode(std::chrono::minutes(1));
    s.takeDecoded();
    EXPECT_GT(s.lastSwitch()->loadMs, 0.0) << "the decode's time, after the first frame";
    s.earlyBakeConfirmed();
    EXPECT_EQ(s.phase(), Phase::Idle);
    EXPECT_FALSE(s.busy());
}

TEST(EnvironmentSwitch, AQueuedRequestIsWhatLoadsAndAFailureEndsTheHold)
{
    EnvironmentSwitch s;
    s.timeFrom("a.exr");
    s.begin("a.exr");
    s.timeFrom("b.exr");
    s.queue("b.exr");
    s.timeFrom("c.exr");
    s.queue("c.exr");
    EXPECT_EQ(s.shownAsLoading(), "c.exr") << "the newest request replaces the queued one";
    EXPECT_EQ(s.takeQueued(), "c.exr");
    EXPECT_FALSE(s.hasQueued());

    s.failed();
    EXPECT_EQ(s.phase(), Phase::Idle);
    EXPECT_FALSE(s.holdsLastImage()) << "what stays is drawn again";

    // A failed early bake lets the decode go on, without holding the view.
    s.timeFrom("d.exr");
    s.begin("d.exr");
    s.beginEarlyBake(7, nullptr);
    s.earlyBakeDropped();
    s.bakeFailed();
    EXPECT_EQ(s.phase(), Phase::Decoding);
    EXPECT_TRUE(s.decodeWaits());
    EXPECT_FALSE(s.holdsLastImage());
}

} // namespace
} // namespace iblab::app
