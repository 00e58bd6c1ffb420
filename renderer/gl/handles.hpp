#pragma once
// Move-only owners for every kind of GL object, so that nobody writes glDelete* by hand
// and nothing leaks when an exception unwinds a half-built pass. Each kind keeps a live
// count, which the soak test compares against its baseline.
#include <array>
#include <cstddef>
#include <span>
#include <utility>

#include <epoxy/gl.h>

namespace iblab::gl {

enum class ObjectKind : int { Texture, Buffer, Framebuffer, Renderbuffer, VertexArray, Shader, Program, Query, Count };

// Live objects of each kind created through these handles, process-wide.
int liveObjectCount(ObjectKind kind);
int liveObjectCountTotal();

namespace detail {
void countCreated(ObjectKind kind);
void countDestroyed(ObjectKind kind);
}

template <ObjectKind Kind>
class Handle {
public:
    Handle() = default;
    // Takes ownership of an id created elsewhere (0 stays empty).
    explicit Handle(GLuint adoptedId) : id_(adoptedId)
    {
        if (id_ != 0) detail::countCreated(Kind);
    }
    ~Handle() { reset(); }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;
    Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
    Handle& operator=(Handle&& other) noexcept
    {
        if (this != &other) {
            reset();
            id_ = std::exchange(other.id_, 0);
        }
        return *this;
    }

    GLuint id() const { return id_; }
    explicit operator bool() const { return id_ != 0; }
    GLuint release() { return std::exchange(id_, 0); }
    void reset()
    {
        if (id_ == 0) return;
        destroy(id_);
        detail::countDestroyed(Kind);
        id_ = 0;
    }

private:
    static void destroy(GLuint id);
    GLuint id_ = 0;
};

using Texture = Handle<ObjectKind::Texture>;
using Buffer = Handle<ObjectKind::Buffer>;
using Framebuffer = Handle<ObjectKind::Framebuffer>;
using Renderbuffer = Handle<ObjectKind::Renderbuffer>;
using VertexArray = Handle<ObjectKind::VertexArray>;
using Shader = Handle<ObjectKind::Shader>;
using Program = Handle<ObjectKind::Program>;
using Query = Handle<ObjectKind::Query>;

// DSA creation (GL 4.5): the object exists, with its target fixed, as soon as it is named.
Texture createTexture(GLenum target);
Buffer createBuffer();
Framebuffer createFramebuffer();
Renderbuffer createRenderbuffer();
VertexArray createVertexArray();
Query createQuery(GLenum target);

// An immutable buffer (no storage flags) holding a copy of values.
template <typename T>
Buffer createBufferWith(std::span<const T> values)
{
    Buffer buffer = createBuffer();
    glNamedBufferStorage(buffer.id(), GLsizeiptr(values.size_bytes()), values.data(), 0);
    return buffer;
}

} // namespace iblab::gl
