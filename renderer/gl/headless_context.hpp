#pragma once
// An OpenGL 4.5 core context with no window and no display, for tests, CI, `iblab render`
// and `iblab bench`. It prefers Mesa's software EGL device (works with no DISPLAY and no
// GPU) and falls back to the surfaceless platform, then to any EGL device.
#include <memory>
#include <string>

namespace iblab::gl {

struct HeadlessContextOptions {
    bool debug = true; // create a debug context so KHR_debug reports every GL error
};

class HeadlessContext {
public:
    // Throws iblab::gl::ContextError with a one-line reason when no 4.5 core context can be made.
    explicit HeadlessContext(const HeadlessContextOptions& options = {});
    ~HeadlessContext();
    HeadlessContext(const HeadlessContext&) = delete;
    HeadlessContext& operator=(const HeadlessContext&) = delete;

    void makeCurrent();
    // "EGL device (Mesa software): llvmpipe (LLVM 15.0.6, 256 bits), OpenGL 4.5 core"
    const std::string& description() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace iblab::gl
