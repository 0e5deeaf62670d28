// One small interface over the ways we get a GL 3.3+ core context (the shape of
// Magnum's Platform/Windowless*Application and GLFW's egl_context.c / osmesa_context.c):
// a GLFW window, EGL headless, OSMesa headless; one file each. A context owns its GL
// function table, loaded through its own platform's GetProcAddress.
#pragma once

#include <memory>
#include <string>

#include "gl/Gl.h"

struct GLFWwindow;

namespace microrelief {

enum class Backend { Auto, Egl, OsMesa };

class GlContext {
public:
    virtual ~GlContext() = default;
    GlContext(const GlContext&) = delete;
    GlContext& operator=(const GlContext&) = delete;

    virtual void makeCurrent() = 0;
    // "egl (device 0: NVIDIA ...)", "egl (surfaceless)", "osmesa", "glfw".
    virtual std::string description() const = 0;

    const GL& gl() const { return gl_; }
    std::string renderer() const;  // GL_RENDERER
    std::string version() const;   // GL_VERSION

protected:
    GlContext() = default;
    // Loads the table for the current context and checks it is GL 3.3 core or newer;
    // throws Error(Runtime) otherwise.
    void loadFunctions(GLADuserptrloadfunc load, void* user, const std::string& who);

    GL gl_{};
};

// Headless contexts render only into framebuffer objects. Auto tries EGL (a hardware
// device first, then Mesa's software device or the surfaceless platform) and falls
// back to OSMesa. Throws Error(Runtime) saying what each backend answered.
std::unique_ptr<GlContext> createHeadlessContext(Backend backend);

// The individual backends; each throws Error(Runtime) when it is absent or fails.
std::unique_ptr<GlContext> createEglContext();
std::unique_ptr<GlContext> createOsMesaContext();

// Whether a backend is installed at all: EGL offers a device or surfaceless display,
// libOSMesa can be opened. A present backend that then fails to make a context is a
// failure to report, not an absence (tests skip only on absence).
bool isBackendPresent(Backend backend);

// A GLFW window with a 3.3 core context; `visible` false gives a hidden window.
struct GlfwWindowOptions {
    int width = 1280;
    int height = 720;
    std::string title = "microrelief";
    bool visible = true;
};
class GlfwContext;
std::unique_ptr<GlfwContext> createGlfwContext(const GlfwWindowOptions& options);

Backend parseBackend(const std::string& name);  // "auto" | "egl" | "osmesa"
const char* backendName(Backend backend);

}  // namespace microrelief
