#include "gl/handles.hpp"

#include <atomic>

namespace iblab::gl {
namespace {
std::array<std::atomic<int>, std::size_t(ObjectKind::Count)> g_live{};
}

namespace detail {
void countCreated(ObjectKind kind) { ++g_live[std::size_t(kind)]; }
void countDestroyed(ObjectKind kind) { --g_live[std::size_t(kind)]; }
}

int liveObjectCount(ObjectKind kind) { return g_live[std::size_t(kind)].load(); }
int liveObjectCountTotal()
{
    int total = 0;
    for (const auto& n : g_live) total += n.load();
    return total;
}

template <> void Handle<ObjectKind::Texture>::destroy(GLuint id) { glDeleteTextures(1, &id); }
template <> void Handle<ObjectKind::Buffer>::destroy(GLuint id) { glDeleteBuffers(1, &id); }
template <> void Handle<ObjectKind::Framebuffer>::destroy(GLuint id) { glDeleteFramebuffers(1, &id); }
template <> void Handle<ObjectKind::Renderbuffer>::destroy(GLuint id) { glDeleteRenderbuffers(1, &id); }
template <> void Handle<ObjectKind::VertexArray>::destroy(GLuint id) { glDeleteVertexArrays(1, &id); }
template <> void Handle<ObjectKind::Shader>::destroy(GLuint id) { glDeleteShader(id); }
template <> void Handle<ObjectKind::Program>::destroy(GLuint id) { glDeleteProgram(id); }
template <> void Handle<ObjectKind::Query>::destroy(GLuint id) { glDeleteQueries(1, &id); }

Texture createTexture(GLenum target)
{
    GLuint id = 0;
    glCreateTextures(target, 1, &id);
    return Texture(id);
}
Buffer createBuffer()
{
    GLuint id = 0;
    glCreateBuffers(1, &id);
    return Buffer(id);
}
Framebuffer createFramebuffer()
{
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    return Framebuffer(id);
}
Renderbuffer createRenderbuffer()
{
    GLuint id = 0;
    glCreateRenderbuffers(1, &id);
    return Renderbuffer(id);
}
VertexArray createVertexArray()
{
    GLuint id = 0;
    glCreateVertexArrays(1, &id);
    return VertexArray(id);
}
Query createQuery(GLenum target)
{
    GLuint id = 0;
    glCreateQueries(target, 1, &id);
    return Query(id);
}

} // namespace iblab::gl
