#pragma once
// A GL fence sync object, owned: placed after commands, it tells when the GPU has finished
// them without stalling the CPU the way glFinish does (a real GPU runs frames behind the
// CPU; glFinish drains that queue and idles both sides).

#include <epoxy/gl.h>

namespace iblab::gl {

class Fence {
public:
    Fence() = default;
    ~Fence() { reset(); }
    Fence(const Fence&) = delete;
    Fence& operator=(const Fence&) = delete;
    Fence(Fence&& other) noexcept;
    Fence& operator=(Fence&& other) noexcept;

    // A fence after every command issued so far in this context (flushed, so that waiting on
    // it from this context cannot deadlock).
    static Fence afterIssuedCommands();

    explicit operator bool() const { return sync_ != nullptr; }
    // True once the GPU has finished the commands before the fence (true for an empty fence).
    bool signalled() const;
    // Blocks until signalled (a GL error, e.g. a lost context, ends the wait too).
    void wait() const;
    void reset();

private:
    GLsync sync_ = nullptr;
};

} // namespace iblab::gl
