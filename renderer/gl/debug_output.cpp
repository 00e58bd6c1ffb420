#include "gl/debug_output.hpp"

#include <epoxy/gl.h>

namespace iblab::gl {
namespace {

const char* sourceName(GLenum source)
{
    switch (source) {
    case GL_DEBUG_SOURCE_API: return "API";
    case GL_DEBUG_SOURCE_WINDOW_SYSTEM: return "window system";
    case GL_DEBUG_SOURCE_SHADER_COMPILER: return "shader compiler";
    case GL_DEBUG_SOURCE_THIRD_PARTY: return "third party";
    case GL_DEBUG_SOURCE_APPLICATION: return "application";
    default: return "other";
    }
}

const char* typeName(GLenum type)
{
    switch (type) {
    case GL_DEBUG_TYPE_ERROR: return "error";
    case GL_DEBUG_TYPE_DEPRECATED_BEHAVIOR: return "deprecated";
    case GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR: return "undefined behaviour";
    case GL_DEBUG_TYPE_PORTABILITY: return "portability";
    case GL_DEBUG_TYPE_PERFORMANCE: return "performance";
    case GL_DEBUG_TYPE_MARKER: return "marker";
    default: return "other";
    }
}

const char* severityName(GLenum severity)
{
    switch (severity) {
    case GL_DEBUG_SEVERITY_HIGH: return "high";
    case GL_DEBUG_SEVERITY_MEDIUM: return "medium";
    case GL_DEBUG_SEVERITY_LOW: return "low";
    default: return "note";
    }
}

void GLAPIENTRY debugCallback(GLenum source, GLenum type, GLuint, GLenum severity, GLsizei length, const GLchar* message,
                              const void* user)
{
    auto* output = static_cast<DebugOutput*>(const_cast<void*>(user));
    DebugMessage m;
    m.isError = type == GL_DEBUG_TYPE_ERROR;
    m.fromShaderCompiler = source == GL_DEBUG_SOURCE_SHADER_COMPILER;
    m.text = std::string("GL ") + typeName(type) + " [" + sourceName(source) + ", " + severityName(severity) +
             "]: " + std::string(message, length >= 0 ? std::size_t(length) : std::char_traits<char>::length(message));
    output->record(std::move(m));
}

} // namespace

bool currentContextHasDebugOutput()
{
    GLint flags = 0;
    glGetIntegerv(GL_CONTEXT_FLAGS, &flags);
    return (flags & GL_CONTEXT_FLAG_DEBUG_BIT) != 0;
}

void DebugOutput::install()
{
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(debugCallback, this);
    // Notifications (buffer placement hints and the like) drown the log; keep the rest.
    glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DEBUG_SEVERITY_NOTIFICATION, 0, nullptr, GL_FALSE);
}

void DebugOutput::record(DebugMessage message)
{
    if (message.isError) ++errorCount_;
    if (onMessage) onMessage(message);
    // Bounded: a per-frame error in the GUI must not grow memory without limit.
    if (messages_.size() < 1000) messages_.push_back(std::move(message));
}

std::string DebugOutput::firstError() const
{
    for (const DebugMessage& m : messages_)
        if (m.isError) return m.text;
    return {};
}

void DebugOutput::clear()
{
    errorCount_ = 0;
    messages_.clear();
}

} // namespace iblab::gl
