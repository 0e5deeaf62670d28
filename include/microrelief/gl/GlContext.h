// One small interface over the ways we get a GL 3.3+ core context (the shape of
// Magnum's Platform/Windowless*Application and GLFW's egl_context.c / osmesa_context.c):
// a GLFW window (GlfwContext.h), EGL or OSMesa headless (HeadlessContext.h), one file
// each, or a context the caller made (adoptCurrentContext). A context owns its GL
// function table, loaded through its own platform's GetProcAddress.
#pragma once

#include <memory>
#include <string>

#include "microrelief/gl/Gl.h"

namespace microrelief {

// The core versions a context is asked for, newest first, until the driver gives one:
// Mesa answers a request for 3.3 with its newest (4.5 on llvmpipe), but NVIDIA's EGL gives
// exactly what is asked, and pages (shader storage) need 4.3, textureGather 4.0.
inline constexpr int kCoreContextVersions[][2] = {{4, 6}, {4, 5}, {4, 4}, {4, 3},
                                                  {4, 2}, {4, 1}, {4, 0}, {3, 3}};

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

// A GlContext over the context current on this thread, made by the caller (an engine's
// window, its own EGL or WGL set-up): the table is loaded through `load` (the platform's
// GetProcAddress, eglGetProcAddress or glfwGetProcAddress). makeCurrent() does nothing:
// the caller keeps its context current while microrelief's GL objects are used. Throws
// Error(Runtime) when the functions do not load or the GL is older than 3.3 core.
std::unique_ptr<GlContext> adoptCurrentContext(GLADloadfunc load,
                                               const std::string& description = "adopted");

}  // namespace microrelief
