#include "command_support.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <epoxy/gl.h>

#include "gl/pass_timer.hpp"
#include "frame/camera.hpp"
#include "io/error.hpp"

namespace iblab::app {

void frameAtStart(Renderer& renderer, FrameSettings& settings, float aspect)
{
    const SceneInfo scene = renderer.sceneInfo(settings);
    const bool model = settings.scene.kind == SceneKind::Model;
    const CameraSettings defaults;
    if (model && settings.camera.yawDegrees == defaults.yawDegrees && settings.camera.pitchDegrees == defaults.pitchDegrees)
        homeView(settings.camera, true);
    frameScene(settings.camera, scene.centre, scene.halfExtents, model, aspect);
}

double millisecondsSince(std::chrono::steady_clock::time_point start)
{
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

GpuTimeQuery::GpuTimeQuery()
{
    if (gl::isSoftwareRenderer()) return;
    query_ = gl::createQuery(GL_TIME_ELAPSED);
    glBeginQuery(GL_TIME_ELAPSED, query_->id());
}

std::optional<double> GpuTimeQuery::finish()
{
    if (!query_) return std::nullopt;
    glEndQuery(GL_TIME_ELAPSED);
    GLuint64 nanoseconds = 0;
    glGetQueryObjectui64v(query_->id(), GL_QUERY_RESULT, &nanoseconds);
    query_.reset();
    return double(nanoseconds) * 1e-6;
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

void restartWithHugePages()
{
    const char* current = std::getenv("GLIBC_TUNABLES");
    if (current && std::strstr(current, "glibc.malloc.hugetlb")) return;
    std::ifstream cmdline("/proc/self/cmdline", std::ios::binary);
    std::vector<std::string> arguments;
    for (std::string argument; std::getline(cmdline, argument, '\0');) arguments.push_back(argument);
    if (arguments.empty()) return;
    std::vector<char*> argv;
    for (std::string& argument : arguments) argv.push_back(argument.data());
    argv.push_back(nullptr);
    const std::string previous = current ? current : "";
    const std::string tunables = (previous.empty() ? "" : previous + ":") + "glibc.malloc.hugetlb=1";
    if (::setenv("GLIBC_TUNABLES", tunables.c_str(), 1) != 0) return;
    std::fflush(stdout);
    std::fflush(stderr);
    ::execv("/proc/self/exe", argv.data());
    if (previous.empty())
        ::unsetenv("GLIBC_TUNABLES");
    else
        ::setenv("GLIBC_TUNABLES", previous.c_str(), 1);
}

bool mallocHugePages()
{
    const char* tunables = std::getenv("GLIBC_TUNABLES");
    return tunables && std::strstr(tunables, "glibc.malloc.hugetlb=1");
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
