// Dear ImGui (Debian's libimgui-dev) with its GLFW and OpenGL 3 backends, which the build
// compiles from the sources Debian ships so that the renderer backend calls GL through
// the project's per-context glad table (ImGuiGlTable.h), not through a loader of its own.
#pragma once

#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include "microrelief/gl/Gl.h"

namespace microrelief {

// The table ImGui_ImplOpenGL3_* calls through: the window context's. Set it before
// ImGui_ImplOpenGL3_Init; it must stay valid until ImGui_ImplOpenGL3_Shutdown.
void setImGuiGlTable(const GL& gl);

}  // namespace microrelief
