#include "environment_switch.hpp"

#include <utility>

namespace iblab::app {

EnvironmentSwitch::~EnvironmentSwitch()
{
    if (decode_.valid()) decode_.wait(); // the worker only reads files; let it finish
}

double EnvironmentSwitch::msSinceRequest(Clock::time_point now) const
{
    return std::chrono::duration<double, std::milli>(now - requested_).count();
}

void EnvironmentSwitch::begin(const std::string& spec)
{
    spec_ = spec;
    phase_ = Phase::Decoding;
    earlyContentHash_ = 0;
    previous_.reset();
    earlyBakeStatus_.clear();
    earlyFrameDrawn_ = false;
}

void EnvironmentSwitch::startDecode()
{
    decode_ = std::async(std::launch::async, [spec = spec_] { return iblab::loadEnvironment(spec); });
}

Environment EnvironmentSwitch::takeDecoded()
{
    Environment loaded = decode_.get(); // consumes decode_, also when it throws
    const double loadMs = msSinceRequest();
    if (timing_) timing_->loadMs = loadMs;
    else if (last_ && last_->environment == spec_ && last_->loadMs == 0.0) last_->loadMs = loadMs; // shown early
    return loaded;
}

void EnvironmentSwitch::beginEarlyBake(std::uint64_t contentHash, std::shared_ptr<const bake::BakeResult> previous)
{
    phase_ = Phase::EarlyBake;
    earlyContentHash_ = contentHash;
    previous_ = std::move(previous);
}

void EnvironmentSwitch::earlyBakeShown(const std::string& bakeStatus, bool fromCache)
{
    phase_ = Phase::EarlyBakeShown;
    earlyBakeStatus_ = bakeStatus;
    if (timing_) {
        timing_->bakeMs = msSinceRequest();
        timing_->fromCache = fromCache;
    }
}

void EnvironmentSwitch::earlyBakeDropped()
{
    if (phase_ == Phase::EarlyBake || phase_ == Phase::EarlyBakeShown) phase_ = Phase::Decoding;
    previous_.reset();
}

void EnvironmentSwitch::bakeShown(bool fromCache)
{
    phase_ = Phase::AwaitingFrame;
    if (timing_) {
        timing_->bakeMs = msSinceRequest();
        timing_->fromCache = fromCache;
    }
}

void EnvironmentSwitch::recentShown()
{
    phase_ = Phase::AwaitingFrame;
    queued_.reset();
    if (timing_) {
        timing_->loadMs = timing_->bakeMs = msSinceRequest();
        timing_->fromCache = true;
    }
}

void EnvironmentSwitch::failed()
{
    phase_ = Phase::Idle;
    timing_.reset();
}

void EnvironmentSwitch::bakeFailed()
{
    timing_.reset();
    if (phase_ != Phase::Decoding) phase_ = Phase::Idle;
}

void EnvironmentSwitch::frameDrawn(Clock::time_point presented)
{
    if (!awaitsFrame()) {
        if (phase_ == Phase::AwaitingFrame) phase_ = Phase::Idle;
        return;
    }
    timing_->firstFrameMs = msSinceRequest(presented);
    last_ = std::exchange(timing_, std::nullopt);
    if (phase_ == Phase::AwaitingFrame) phase_ = Phase::Idle;
    else earlyFrameDrawn_ = true;
}

// Out of line: inlined into a caller, GCC 12 reports the moved-from string as maybe
// uninitialised (-Wmaybe-uninitialized, a false positive of std::optional's move).
std::optional<std::string> EnvironmentSwitch::takeRecentNext()
{
    std::optional<std::string> next = std::move(recentNext_);
    recentNext_.reset();
    return next;
}

} // namespace iblab::app
