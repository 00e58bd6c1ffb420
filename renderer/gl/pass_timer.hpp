#pragma once
// GPU time of a pass, without stalling a real GPU: there a GL_TIME_ELAPSED query is read back
// a frame or two later, when its result is available. Software renderers (llvmpipe) get
// glFinish and a steady clock instead, because their timer queries time the command
// submission, not the deferred rasterisation.
#include <array>
#include <chrono>
#include <optional>

#include "gl/handles.hpp"

namespace iblab::gl {

class PassTimer {
public:
    // Needs a current context; decides the method from the renderer's name.
    PassTimer();
    void begin();
    void end();
    // The newest measurement that has become available (on llvmpipe: the pass just ended).
    std::optional<double> latestMilliseconds();
    bool usesQueries() const { return usesQueries_; }

private:
    bool usesQueries_ = false;
    std::chrono::steady_clock::time_point started_;
    std::optional<double> latest_;
    // A small ring, so that a new pass can start while older results are in flight.
    std::array<Query, 3> queries_;
    std::array<bool, 3> pending_{};
    std::size_t next_ = 0;
};

// True for renderers that rasterise on the CPU (llvmpipe, softpipe, SwiftShader).
bool isSoftwareRenderer();

} // namespace iblab::gl
