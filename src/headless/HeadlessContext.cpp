#include "microrelief/headless/HeadlessContext.h"

#include "microrelief/core/Error.h"

namespace microrelief {

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
