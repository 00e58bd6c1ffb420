#include "gl/pass_timer.hpp"

#include <cstring>

namespace iblab::gl {

bool isSoftwareRenderer()
{
    const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    if (!renderer) return false;
    for (const char* name : {"llvmpipe", "softpipe", "SwiftShader"})
        if (std::strstr(renderer, name)) return true;
    return false;
}

PassTimer::PassTimer() : usesQueries_(!isSoftwareRenderer())
{
    if (usesQueries_)
        for (Query& query : queries_) query = createQuery(GL_TIME_ELAPSED);
}

void PassTimer::begin()
{
    if (!usesQueries_) {
        started_ = std::chrono::steady_clock::now();
        return;
    }
    // A query still in flight in this slot is dropped rather than waited for.
    pending_[next_] = false;
    glBeginQuery(GL_TIME_ELAPSED, queries_[next_].id());
}

void PassTimer::end()
{
    if (!usesQueries_) {
        glFinish();
        latest_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started_).count();
        return;
    }
    glEndQuery(GL_TIME_ELAPSED);
    pending_[next_] = true;
    next_ = (next_ + 1) % queries_.size();
}

std::optional<double> PassTimer::latestMilliseconds()
{
    if (!usesQueries_) return latest_;
    // Oldest first, so that the newest available result wins.
    for (std::size_t i = 0; i < queries_.size(); ++i) {
        const std::size_t slot = (next_ + i) % queries_.size();
        if (!pending_[slot]) continue;
        GLint available = 0;
        glGetQueryObjectiv(queries_[slot].id(), GL_QUERY_RESULT_AVAILABLE, &available);
        if (!available) continue;
        GLuint64 nanoseconds = 0;
        glGetQueryObjectui64v(queries_[slot].id(), GL_QUERY_RESULT, &nanoseconds);
        latest_ = double(nanoseconds) * 1e-6;
        pending_[slot] = false;
    }
    return latest_;
}

} // namespace iblab::gl
