#pragma once
// What every headless sub-command shares: its GL context with KHR_debug, its clock, and
// its one-line failure.
#include <chrono>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "gl/debug_output.hpp"
#include "gl/handles.hpp"
#include "ibl/error_metrics.hpp"
#include "gl/headless_context.hpp"
#include "frame/renderer.hpp"

namespace iblab::app {

// --distance 0: frames the scene the renderer holds for these settings (frameScene), a model
// from its home view unless --yaw or --pitch moved the camera from its default orientation.
void frameAtStart(Renderer& renderer, FrameSettings& settings, float aspect);

double millisecondsSince(std::chrono::steady_clock::time_point start);

// GPU time of the commands issued between construction and finish(), by GL_TIME_ELAPSED, on
// hardware renderers; llvmpipe's timer queries time the submission, not its deferred work,
// so there finish() answers nothing and the callers' steady-clock times stand alone.
class GpuTimeQuery {
public:
    GpuTimeQuery();
    // Ends the query and waits for its result; once.
    std::optional<double> finish();

private:
    std::optional<gl::Query> query_;
};

// Prints "iblab COMMAND: reason" on stderr as ONE line (driver logs and nested errors are
// folded) and returns the exit status 1.
int failCommand(const char* command, const std::string& reason);

// Ends a command whose output is complete (its files closed, its report printed) without
// tearing down what the process built: the kernel reclaims a GL context, llvmpipe's threads
// and libLLVM's state at once, where destroying them in order took 6-8 ms of a ~125 ms
// `iblab bake` (strace: report to exit_group). Call it where the command's own objects are
// still alive, so their destructors are skipped too. Sanitizer builds return `status`
// instead, so that the normal exit runs and LeakSanitizer still checks it.
int exitWithoutTeardown(int status);

// A bake spends much of its time faulting in fresh memory: the decoded maps, llvmpipe's
// textures, the read-backs (tens of MB, 4 KiB page by page). Where transparent huge pages
// are in "madvise" mode (the kernel default), glibc's malloc asks for them only when its
// glibc.malloc.hugetlb tunable is 1, and tunables are read once, when a process starts: so
// this restarts the process (/proc/self/exe, the same arguments) with the tunable set.
// `scripts/measure-bake.sh hugepages` measures one map and a batch both ways. Returns (doing
// nothing) when GLIBC_TUNABLES already names the tunable (the restarted process, or a user's
// choice, =0 to turn it off), or when the exec fails.
void restartWithHugePages();
// Whether this process runs with glibc.malloc.hugetlb=1 (the bake's report says so).
bool mallocHugePages();

// Prints each GL debug message on stderr as it comes, but the shader compiler's: the shader
// library reports those itself, naming the file and line.
void echoOnStderr(gl::DebugOutput& debug);

// A headless context whose GL errors are collected (and echoed on stderr when asked), so
// that a command can fail on them.
struct HeadlessGl {
    gl::HeadlessContext context;
    gl::DebugOutput debug;
    explicit HeadlessGl(bool debugContext, bool echoMessages = false);
};

// {"pixels", "relative_rmse", "mean_relative", "max_relative", "p99_relative", "fireflies"}
nlohmann::ordered_json errorMetricsJson(const ErrorMetrics& metrics);

} // namespace iblab::app
