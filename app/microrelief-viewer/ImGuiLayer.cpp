#include "ImGuiLayer.h"

#include "ImGuiBackends.h"
#include "microrelief/core/Error.h"

namespace microrelief {

ImGuiLayer::ImGuiLayer(GlfwContext& window, float uiScale) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;  // no imgui.ini in whatever folder the viewer runs from
    ImGui::StyleColorsDark();
    ImGui::GetStyle().ScaleAllSizes(uiScale);
    ImFontConfig font;
    font.SizePixels = 13.0f * uiScale;  // the default font at the monitor's scale, not magnified
    io.Fonts->AddFontDefault(&font);

    setImGuiGlTable(window.gl());
    const bool platform = ImGui_ImplGlfw_InitForOpenGL(window.window(), true);
    if (!platform || !ImGui_ImplOpenGL3_Init("#version 330 core")) {
        if (platform) ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
        throwRuntime("Dear ImGui: cannot set up its GLFW and OpenGL 3 backends");
    }
}

ImGuiLayer::~ImGuiLayer() {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
}

void ImGuiLayer::beginFrame() {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
}

void ImGuiLayer::render() {
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void ImGuiLayer::endFrameUndrawn() {
    ImGui::EndFrame();
}

bool ImGuiLayer::wantsMouse() const {
    return ImGui::GetIO().WantCaptureMouse;
}
bool ImGuiLayer::wantsKeyboard() const {
    return ImGui::GetIO().WantCaptureKeyboard;
}

}  // namespace microrelief
