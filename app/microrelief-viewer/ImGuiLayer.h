// Dear ImGui over a GLFW window: the context and both backends, set up and torn down
// together (RAII), so the panel's GL objects die before the window's context.
#pragma once

#include "microrelief/glfw/GlfwContext.h"

namespace microrelief {

class ImGuiLayer {
public:
    // Installs ImGui's GLFW callbacks, which call on to any installed before: install
    // the viewer's own first. `uiScale` sizes fonts and widgets (HiDPI).
    ImGuiLayer(GlfwContext& window, float uiScale);
    ~ImGuiLayer();
    ImGuiLayer(const ImGuiLayer&) = delete;
    ImGuiLayer& operator=(const ImGuiLayer&) = delete;

    void beginFrame();
    // Draws the frame's widgets into the bound framebuffer.
    void render();
    // Ends a frame without drawing it. ImGui sizes a new auto-fitting window in the first
    // frame that names it and hides it there: a frame of widgets ended here before the
    // first drawn frame makes that one show them.
    void endFrameUndrawn();

    // Whether ImGui uses the mouse or keyboard now (a widget is hovered, dragged, typed in).
    bool wantsMouse() const;
    bool wantsKeyboard() const;
};

}  // namespace microrelief
