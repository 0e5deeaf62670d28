#include "context/GlContext.h"

#include "core/Error.h"

namespace microrelief {

void GlContext::loadFunctions(GLADuserptrloadfunc load, void* user, const std::string& who) {
    const int version = gladLoadGLContextUserPtr(&gl_, load, user);
    if (version == 0) throwRuntime(who + ": cannot load the GL functions");
    const int major = GLAD_VERSION_MAJOR(version), minor = GLAD_VERSION_MINOR(version);
    if (major < 3 || (major == 3 && minor < 3)) {
        throwRuntime(who + ": OpenGL " + std::to_string(major) + "." + std::to_string(minor) +
                     " is too old; microrelief needs 3.3 core");
    }
}

namespace {
std::string glString(const GL& gl, GLenum name) {
    const auto* text = reinterpret_cast<const char*>(gl.GetString(name));
    return text ? text : "";
}
}  // namespace

std::string GlContext::renderer() const {
    return glString(gl_, GL_RENDERER);
}
std::string GlContext::version() const {
    return glString(gl_, GL_VERSION);
}

std::unique_ptr<GlContext> createHeadlessContext(Backend backend) {
    switch (backend) {
        case Backend::Egl:
            return createEglContext();
        case Backend::OsMesa:
            return createOsMesaContext();
        case Backend::Auto:
            break;
    }
    std::string eglReason;
    try {
        return createEglContext();
    } catch (const Error& e) {
        eglReason = e.what();
    }
    try {
        return createOsMesaContext();
    } catch (const Error& e) {
        throwRuntime("no GL backend available: " + eglReason + "; " + e.what());
    }
}

bool isEglPresent();     // EglContext.cpp
bool isOsMesaPresent();  // OsMesaContext.cpp

bool isBackendPresent(Backend backend) {
    switch (backend) {
        case Backend::Egl:
            return isEglPresent();
        case Backend::OsMesa:
            return isOsMesaPresent();
        case Backend::Auto:
            return isEglPresent() || isOsMesaPresent();
    }
    return false;
}

Backend parseBackend(const std::string& name) {
    if (name == "auto") return Backend::Auto;
    if (name == "egl") return Backend::Egl;
    if (name == "osmesa") return Backend::OsMesa;
    throwBadInput("unknown backend '" + name + "' (expected auto, egl or osmesa)");
}

const char* backendName(Backend backend) {
    switch (backend) {
        case Backend::Auto:
            return "auto";
        case Backend::Egl:
            return "egl";
        case Backend::OsMesa:
            return "osmesa";
    }
    return "?";
}

}  // namespace microrelief
