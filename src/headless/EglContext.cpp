// Headless GL through EGL: a device-platform display (EGL_EXT_platform_device),
// hardware devices before Mesa's software device, then Mesa's surfaceless platform.
// The context is made current without a surface (EGL_KHR_surfaceless_context); all
// rendering goes to framebuffer objects.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>
#include <string>
#include <vector>

#include "microrelief/headless/HeadlessContext.h"
#include "microrelief/core/Error.h"

namespace microrelief {

namespace {

bool hasExtension(const char* list, const char* name) {
    if (!list) return false;
    const std::size_t n = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n) {
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    }
    return false;
}

std::string eglErrorName(EGLint error) {
    switch (error) {
        case EGL_NOT_INITIALIZED:
            return "EGL_NOT_INITIALIZED";
        case EGL_BAD_ACCESS:
            return "EGL_BAD_ACCESS";
        case EGL_BAD_ALLOC:
            return "EGL_BAD_ALLOC";
        case EGL_BAD_ATTRIBUTE:
            return "EGL_BAD_ATTRIBUTE";
        case EGL_BAD_CONFIG:
            return "EGL_BAD_CONFIG";
        case EGL_BAD_CONTEXT:
            return "EGL_BAD_CONTEXT";
        case EGL_BAD_DISPLAY:
            return "EGL_BAD_DISPLAY";
        case EGL_BAD_MATCH:
            return "EGL_BAD_MATCH";
        case EGL_BAD_PARAMETER:
            return "EGL_BAD_PARAMETER";
        default:
            return "EGL error " + std::to_string(error);
    }
}

struct Candidate {
    EGLDisplay display;
    std::string name;
};

std::vector<Candidate> candidateDisplays() {
    std::vector<Candidate> hardware, software;
    const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!getPlatformDisplay) return {};

    if (hasExtension(clientExtensions, "EGL_EXT_platform_device")) {
        auto queryDevices =
            reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
        auto queryDeviceString = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
            eglGetProcAddress("eglQueryDeviceStringEXT"));
        EGLint count = 0;
        if (queryDevices && queryDevices(0, nullptr, &count) && count > 0) {
            std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
            queryDevices(count, devices.data(), &count);
            for (EGLint k = 0; k < count; ++k) {
                const char* ext =
                    queryDeviceString ? queryDeviceString(devices[k], EGL_EXTENSIONS) : nullptr;
                const bool isSoftware = hasExtension(ext, "EGL_MESA_device_software");
                EGLDisplay display =
                    getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[k], nullptr);
                if (display == EGL_NO_DISPLAY) continue;
                const std::string name =
                    "device " + std::to_string(k) + (isSoftware ? ", software" : "");
                (isSoftware ? software : hardware).push_back({display, name});
            }
        }
    }
    std::vector<Candidate> all = hardware;
    all.insert(all.end(), software.begin(), software.end());
    if (hasExtension(clientExtensions, "EGL_MESA_platform_surfaceless")) {
        EGLDisplay display =
            getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (display != EGL_NO_DISPLAY) all.push_back({display, "surfaceless"});
    }
    return all;
}

GLADapiproc loadEgl(void*, const char* name) {
    return reinterpret_cast<GLADapiproc>(eglGetProcAddress(name));
}

class EglContext final : public GlContext {
public:
    EglContext(EGLDisplay display, EGLContext context, std::string name)
        : display_(display), context_(context), name_(std::move(name)) {
        makeCurrent();
        loadFunctions(loadEgl, nullptr, "EGL (" + name_ + ")");
    }
    ~EglContext() override {
        eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(display_, context_);
        // No eglTerminate: a device display is one per process and other contexts
        // (another renderer, another test) may still live on it.
    }

    void makeCurrent() override {
        if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) {
            throwRuntime("EGL (" + name_ +
                         "): eglMakeCurrent failed: " + eglErrorName(eglGetError()));
        }
    }
    std::string description() const override { return "egl (" + name_ + ")"; }

private:
    EGLDisplay display_;
    EGLContext context_;
    std::string name_;
};

// Creates a core context of 3.3 or newer on `display`, or says why not.
EGLContext createContextOn(EGLDisplay display, std::string& why) {
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) {
        why = "eglInitialize: " + eglErrorName(eglGetError());
        return EGL_NO_CONTEXT;
    }
    if (!hasExtension(eglQueryString(display, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context")) {
        why = "no EGL_KHR_surfaceless_context";
        return EGL_NO_CONTEXT;
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
        why = "no desktop OpenGL API";
        return EGL_NO_CONTEXT;
    }
    const EGLint configAttributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE,
                                       EGL_PBUFFER_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint configs = 0;
    if (!eglChooseConfig(display, configAttributes, &config, 1, &configs) || configs == 0) {
        why = "no OpenGL config";
        return EGL_NO_CONTEXT;
    }
    // The newest core version the driver gives, down to 3.3 (GlContext.h).
    for (const auto& [wantMajor, wantMinor] : kCoreContextVersions) {
        const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                            wantMajor,
                                            EGL_CONTEXT_MINOR_VERSION,
                                            wantMinor,
                                            EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                            EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                            EGL_NONE};
        EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttributes);
        if (context != EGL_NO_CONTEXT) return context;
    }
    why = "eglCreateContext (core 4.6 down to 3.3, the last: " + eglErrorName(eglGetError()) + ")";
    return EGL_NO_CONTEXT;
}

}  // namespace

bool isEglPresent() {
    return !candidateDisplays().empty();
}

std::unique_ptr<GlContext> createEglContext() {
    const std::vector<Candidate> candidates = candidateDisplays();
    if (candidates.empty()) throwRuntime("EGL: no device or surfaceless display available");
    std::string reasons;
    for (const Candidate& c : candidates) {
        std::string why;
        EGLContext context = createContextOn(c.display, why);
        if (context != EGL_NO_CONTEXT) {
            try {
                return std::make_unique<EglContext>(c.display, context, c.name);
            } catch (const Error& e) {
                // The constructor threw, so no destructor runs: release it here and go on
                // to the next display.
                eglMakeCurrent(c.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
                eglDestroyContext(c.display, context);
                why = e.what();
            }
        }
        reasons += (reasons.empty() ? "" : ", ") + c.name + ": " + why;
    }
    throwRuntime("EGL: no display gave a GL 3.3 core context (" + reasons + ")");
}

}  // namespace microrelief
