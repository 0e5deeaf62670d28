// A GLFW window with its GL 3.3 core context, for the interactive viewer and for tests
// under Xvfb. The window is the context's default framebuffer.
#pragma once

#include <memory>
#include <string>

#include "microrelief/gl/GlContext.h"

struct GLFWwindow;

namespace microrelief {

// A GLFW window with a 3.3 core context; `visible` false gives a hidden window.
struct GlfwWindowOptions {
    int width = 1280;
    int height = 720;
    std::string title = "microrelief";
    bool visible = true;
};

class GlfwContext final : public GlContext {
public:
    explicit GlfwContext(const GlfwWindowOptions& options);
    ~GlfwContext() override;

    void makeCurrent() override;
    std::string description() const override { return "glfw"; }

    GLFWwindow* window() const { return window_; }

private:
    GLFWwindow* window_ = nullptr;
};

std::unique_ptr<GlfwContext> createGlfwContext(const GlfwWindowOptions& options);

}  // namespace microrelief
