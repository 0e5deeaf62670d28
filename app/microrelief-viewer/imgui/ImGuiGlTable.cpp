#include "ImGuiGlTable.h"

#include "ImGuiBackends.h"

const GladGLContext* microrelief_imgui_gl = nullptr;

namespace microrelief {

void setImGuiGlTable(const GL& gl) {
    microrelief_imgui_gl = &gl;
}

}  // namespace microrelief
