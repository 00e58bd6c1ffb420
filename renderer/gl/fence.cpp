#include "gl/fence.hpp"

#include <utility>

namespace iblab::gl {

Fence::Fence(Fence&& other) noexcept : sync_(std::exchange(other.sync_, nullptr)) {}

Fence& Fence::operator=(Fence&& other) noexcept
{
    if (this != &other) {
        reset();
        sync_ = std::exchange(other.sync_, nullptr);
    }
    return *this;
}

Fence Fence::afterIssuedCommands()
{
    Fence fence;
    fence.sync_ = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    glFlush();
    return fence;
}

bool Fence::signalled() const
{
    if (!sync_) return true;
    const GLenum status = glClientWaitSync(sync_, 0, 0);
    return status == GL_ALREADY_SIGNALED || status == GL_CONDITION_SATISFIED || status == GL_WAIT_FAILED;
}

void Fence::wait() const
{
    if (!sync_) return;
    constexpr GLuint64 kSecond = 1'000'000'000;
    for (;;) {
        const GLenum status = glClientWaitSync(sync_, GL_SYNC_FLUSH_COMMANDS_BIT, kSecond);
        if (status != GL_TIMEOUT_EXPIRED) return;
    }
}

void Fence::reset()
{
    if (sync_) glDeleteSync(std::exchange(sync_, nullptr));
}

} // namespace iblab::gl
