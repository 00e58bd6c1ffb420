#include "gl/headless_context.hpp"

#include <cstring>
#include <vector>

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include "gl/context_error.hpp"
#include "gl/context_info.hpp"

namespace iblab::gl {

struct HeadlessContext::Impl {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    std::string description;

    ~Impl()
    {
        if (display == EGL_NO_DISPLAY) return;
        eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
        eglTerminate(display);
    }
};

namespace {

bool hasExtension(const char* list, const char* name)
{
    if (!list) return false;
    const std::size_t n = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n) {
        const bool startOk = p == list || p[-1] == ' ';
        const bool endOk = p[n] == ' ' || p[n] == '\0';
        if (startOk && endOk) return true;
    }
    return false;
}

struct DisplayCandidate {
    EGLDisplay display;
    std::string label;
};

// Mesa's software device first: it needs neither DISPLAY nor a GPU, and it is what CI has.
// Other devices (a real GPU exposed through EGL) come after it only when it is absent.
std::vector<DisplayCandidate> candidateDisplays()
{
    std::vector<DisplayCandidate> result;
    const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (hasExtension(clientExtensions, "EGL_EXT_device_enumeration") && hasExtension(clientExtensions, "EGL_EXT_platform_device")) {
        EGLint count = 0;
        eglQueryDevicesEXT(0, nullptr, &count);
        std::vector<EGLDeviceEXT> devices(std::size_t(count > 0 ? count : 0));
        if (count > 0) eglQueryDevicesEXT(count, devices.data(), &count);
        std::vector<DisplayCandidate> others;
        for (EGLDeviceEXT device : devices) {
            const char* deviceExtensions = eglQueryDeviceStringEXT(device, EGL_EXTENSIONS);
            const bool software = hasExtension(deviceExtensions, "EGL_MESA_device_software");
            EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
            if (display == EGL_NO_DISPLAY) continue;
            (software ? result : others).push_back({display, software ? "EGL device (Mesa software)" : "EGL device"});
        }
        result.insert(result.end(), others.begin(), others.end());
    }
    if (hasExtension(clientExtensions, "EGL_MESA_platform_surfaceless")) {
        EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (display != EGL_NO_DISPLAY) result.push_back({display, "EGL surfaceless platform"});
    }
    return result;
}

} // namespace

HeadlessContext::HeadlessContext(const HeadlessContextOptions& options) : impl_(std::make_unique<Impl>())
{
    std::string failures;
    for (const DisplayCandidate& candidate : candidateDisplays()) {
        EGLint major = 0, minor = 0;
        if (!eglInitialize(candidate.display, &major, &minor)) {
            failures += " " + candidate.label + ": eglInitialize failed;";
            continue;
        }
        const char* displayExtensions = eglQueryString(candidate.display, EGL_EXTENSIONS);
        if (!hasExtension(displayExtensions, "EGL_KHR_surfaceless_context")) {
            failures += " " + candidate.label + ": no EGL_KHR_surfaceless_context;";
            eglTerminate(candidate.display);
            continue;
        }
        if (!eglBindAPI(EGL_OPENGL_API)) {
            failures += " " + candidate.label + ": no desktop OpenGL API;";
            eglTerminate(candidate.display);
            continue;
        }
        const EGLint contextAttributes[] = {
            EGL_CONTEXT_MAJOR_VERSION, 4,
            EGL_CONTEXT_MINOR_VERSION, 5,
            EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
            EGL_CONTEXT_OPENGL_DEBUG, options.debug ? EGL_TRUE : EGL_FALSE,
            EGL_NONE,
        };
        // No config: EGL_KHR_no_config_context lets us skip choosing a surface format we never use.
        EGLConfig config = EGL_NO_CONFIG_KHR;
        if (!hasExtension(displayExtensions, "EGL_KHR_no_config_context")) {
            const EGLint configAttributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
            EGLint found = 0;
            eglChooseConfig(candidate.display, configAttributes, &config, 1, &found);
        }
        EGLContext context = eglCreateContext(candidate.display, config, EGL_NO_CONTEXT, contextAttributes);
        if (context == EGL_NO_CONTEXT) {
            failures += " " + candidate.label + ": no OpenGL 4.5 core context;";
            eglTerminate(candidate.display);
            continue;
        }
        if (!eglMakeCurrent(candidate.display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
            failures += " " + candidate.label + ": eglMakeCurrent failed;";
            eglDestroyContext(candidate.display, context);
            eglTerminate(candidate.display);
            continue;
        }
        impl_->display = candidate.display;
        impl_->context = context;
        impl_->description = candidate.label + ": " + describeCurrentContext();
        requireCurrentContextFeatures(); // throws ContextError naming what is missing
        return;
    }
    throw ContextError("headless OpenGL: no EGL display gives an OpenGL 4.5 core context;" +
                       (failures.empty() ? std::string(" no EGL device or surfaceless platform found") : failures));
}

HeadlessContext::~HeadlessContext() = default;

void HeadlessContext::makeCurrent()
{
    eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, impl_->context);
}

const std::string& HeadlessContext::description() const { return impl_->description; }

} // namespace iblab::gl
