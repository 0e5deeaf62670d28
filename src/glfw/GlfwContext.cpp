#include "microrelief/glfw/GlfwContext.h"

#include <GLFW/glfw3.h>

#include <string>

#include "microrelief/core/Error.h"

namespace microrelief {

namespace {

GLADapiproc loadGlfw(void*, const char* name) {
    return glfwGetProcAddress(name);
}

// glfwInit once per process; glfwTerminate at exit, after every window is gone.
void initGlfw() {
    static const bool ready = [] {
        glfwSetErrorCallback(nullptr);
        if (glfwInit() != GLFW_TRUE) return false;
        std::atexit(glfwTerminate);
        return true;
    }();
    if (!ready) {
        const char* description = nullptr;
        glfwGetError(&description);
        throwRuntime(std::string("GLFW: cannot initialise (") +
                     (description ? description : "no display?") + ")");
    }
}

}  // namespace

GlfwContext::GlfwContext(const GlfwWindowOptions& options) {
    initGlfw();
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_VISIBLE, options.visible ? GLFW_TRUE : GLFW_FALSE);
    glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_TRUE);
    // The newest core version the driver gives, down to 3.3 (GlContext.h).
    for (const auto& [major, minor] : kCoreContextVersions) {
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, major);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, minor);
        window_ = glfwCreateWindow(options.width, options.height, options.title.c_str(), nullptr,
                                   nullptr);
        if (window_) {
            glfwGetError(nullptr);  // the refusals of newer versions are not this window's
            break;
        }
    }
    if (!window_) {
        const char* description = nullptr;
        glfwGetError(&description);
        throwRuntime(std::string("GLFW: cannot open a GL 3.3 core window (") +
                     (description ? description : "?") + ")");
    }
    try {
        makeCurrent();
        loadFunctions(loadGlfw, nullptr, "GLFW");
    } catch (...) {
        glfwDestroyWindow(window_);  // the constructor throws: no destructor runs
        throw;
    }
}

GlfwContext::~GlfwContext() {
    if (window_) glfwDestroyWindow(window_);
}

void GlfwContext::makeCurrent() {
    glfwMakeContextCurrent(window_);
}

std::unique_ptr<GlfwContext> createGlfwContext(const GlfwWindowOptions& options) {
    return std::make_unique<GlfwContext>(options);
}

}  // namespace microrelief
