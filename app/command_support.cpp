#include "command_support.hpp"

#include <cstdio>
#include <cstdlib>

#include "io/error.hpp"

namespace iblab::app {

double millisecondsSince(std::chrono::steady_clock::time_point start)
{
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

int failCommand(const char* command, const std::string& reason)
{
    std::fprintf(stderr, "iblab %s: %s\n", command, oneLine(reason).c_str());
    return 1;
}

int exitWithoutTeardown(int status)
{
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
    return status;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
    return status;
#endif
#endif
    std::fflush(stdout);
    std::fflush(stderr);
    std::_Exit(status);
}

void echoOnStderr(gl::DebugOutput& debug)
{
    debug.onMessage = [](const gl::DebugMessage& m) {
        if (!m.fromShaderCompiler) std::fprintf(stderr, "iblab: %s\n", m.text.c_str());
    };
}

HeadlessGl::HeadlessGl(bool debugContext, bool echoMessages) : context(gl::HeadlessContextOptions{.debug = debugContext})
{
    if (!debugContext || !gl::currentContextHasDebugOutput()) return;
    if (echoMessages) echoOnStderr(debug);
    debug.install();
}

nlohmann::ordered_json errorMetricsJson(const ErrorMetrics& m)
{
    return {{"pixels", m.pixels},
            {"relative_rmse", m.relativeRmse},
            {"mean_relative", m.meanRelative},
            {"max_relative", m.maxRelative},
            {"p99_relative", m.p99Relative},
            {"fireflies", m.fireflies}};
}

} // namespace iblab::app
