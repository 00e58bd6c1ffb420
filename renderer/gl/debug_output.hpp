#pragma once
// KHR_debug hookup. On in debug builds and in tests (both ask for a debug context); every
// message is logged, and messages of type error are counted so tests can fail on them.
#include <functional>
#include <string>
#include <vector>

namespace iblab::gl {

struct DebugMessage {
    bool isError = false;
    // The shader compiler's own diagnostics, which ShaderLibrary reports again as a
    // ShaderError naming the file and line (the driver's lines count in the text it was
    // given, the files concatenated): an echo of them would say the same thing wrongly.
    bool fromShaderCompiler = false;
    std::string text; // "GL error [API, high]: GL_INVALID_ENUM in glTexParameteri(...)"
};

class DebugOutput {
public:
    // Installs the callback on the current context; synchronous so a breakpoint or a
    // backtrace in the callback points at the offending call.
    void install();
    int errorCount() const { return errorCount_; }
    const std::vector<DebugMessage>& messages() const { return messages_; }
    // The text of the first message of type error, or "" when there was none.
    std::string firstError() const;
    void clear();
    // Called for every message as well (the app prints them; tests collect them).
    std::function<void(const DebugMessage&)> onMessage;

    // Implementation detail of the C callback.
    void record(DebugMessage message);

private:
    int errorCount_ = 0;
    std::vector<DebugMessage> messages_;
};

// True when the current context was created with the debug flag and KHR_debug is usable.
bool currentContextHasDebugOutput();

} // namespace iblab::gl
