#include "InputBindings.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>

#include <glm/gtc/constants.hpp>

namespace microrelief {

ViewerCommand keyCommand(int key, int mods, bool flyMode, int* debugView) {
    const bool ctrl = (mods & GLFW_MOD_CONTROL) != 0;
    switch (key) {
        case GLFW_KEY_ESCAPE: return ViewerCommand::Quit;
        case GLFW_KEY_F: return ViewerCommand::ToggleFly;
        case GLFW_KEY_R: return ViewerCommand::ResetView;
        case GLFW_KEY_TAB: return ViewerCommand::TogglePanel;
        case GLFW_KEY_F12:
        case GLFW_KEY_P: return ViewerCommand::Screenshot;
        case GLFW_KEY_C: return ViewerCommand::CopyCommand;
        case GLFW_KEY_V: return ViewerCommand::ToggleVsync;
        case GLFW_KEY_B: return ViewerCommand::ToggleSculpt;
        case GLFW_KEY_Z: return ctrl ? ViewerCommand::Undo : ViewerCommand::None;
        case GLFW_KEY_S: return ctrl && !flyMode ? ViewerCommand::SaveMap : ViewerCommand::None;
        case GLFW_KEY_LEFT_BRACKET: return ViewerCommand::ShrinkBrush;
        case GLFW_KEY_RIGHT_BRACKET: return ViewerCommand::GrowBrush;
        case GLFW_KEY_SPACE: return ViewerCommand::TogglePlay;
        default:
            if (key >= GLFW_KEY_1 && key <= GLFW_KEY_6) {
                if (debugView) *debugView = key - GLFW_KEY_1;
                return ViewerCommand::DebugView;
            }
            return ViewerCommand::None;
    }
}

glm::dvec3 flyDirection(const std::function<bool(int key)>& down) {
    const auto held = [&](int key) { return down(key) ? 1.0 : 0.0; };
    return {held(GLFW_KEY_D) - held(GLFW_KEY_A), held(GLFW_KEY_E) - held(GLFW_KEY_Q),
            held(GLFW_KEY_W) - held(GLFW_KEY_S)};
}

glm::vec3 turnLight(const glm::vec3& direction, double dx, double dy) {
    const glm::dvec3 l = glm::normalize(glm::dvec3(direction));
    const double azimuth = std::atan2(l.z, l.x) + dx * (glm::half_pi<double>() / 400.0);
    const double elevation =
        std::clamp(std::asin(std::clamp(l.y, -1.0, 1.0)) - dy * (glm::half_pi<double>() / 400.0),
                   glm::radians(0.5), glm::radians(89.5));
    return glm::vec3(std::cos(elevation) * std::cos(azimuth), std::sin(elevation),
                     std::cos(elevation) * std::sin(azimuth));
}

}  // namespace microrelief
