// The viewer's keys and drags as data, without a window: which command a key press gives
// (keyCommand; the README's and docs/viewer.md's key table), where the fly keys held move
// the eye (flyDirection), and how a drag with L held turns the light (turnLight). ViewerApp
// reads the events from GLFW and Dear ImGui and carries the commands out.
#pragma once

#include <functional>

#include <glm/glm.hpp>

namespace microrelief {

enum class ViewerCommand {
    None,
    Quit,          // Esc (asks first where there are edits not saved)
    ToggleFly,     // F
    ResetView,     // R
    TogglePanel,   // Tab
    Screenshot,    // P, F12
    CopyCommand,   // C
    ToggleVsync,   // V
    ToggleSculpt,  // B
    Undo,          // Ctrl+Z
    SaveMap,       // Ctrl+S, out of fly mode (where S flies back)
    ShrinkBrush,   // [
    GrowBrush,     // ]
    TogglePlay,    // Space
    DebugView,     // 1 to 6: the debug view keyCommand's `debugView` names
};

// The command of `key` (a GLFW key) pressed with `mods` (GLFW modifier bits) held;
// `debugView` is set for ViewerCommand::DebugView (0 for key 1, ...).
ViewerCommand keyCommand(int key, int mods, bool flyMode, int* debugView = nullptr);

// The fly keys held (`down`: whether a GLFW key is): x right (D, A), y up (E, Q), z forward
// (W, S), each -1, 0 or 1.
glm::dvec3 flyDirection(const std::function<bool(int key)>& down);

// The light `direction` turned by a drag of (dx, dy) window units: about the vertical
// across, raised or lowered up and down, a quarter turn per 400 units, its elevation kept
// within [0.5, 89.5] degrees. A unit vector.
glm::vec3 turnLight(const glm::vec3& direction, double dx, double dy);

}  // namespace microrelief
