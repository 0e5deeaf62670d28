// A GLFW window with its GL 3.3 core context, for the interactive viewer and for tests
// under Xvfb. The window is the context's default framebuffer.
#pragma once

#include "context/GlContext.h"

namespace microrelief {

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

}  // namespace microrelief
