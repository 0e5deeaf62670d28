// The viewer's Dear ImGui panel: immediate mode, so it reads and edits a plain state
// struct each frame and hands back what the user asked for; the app does the work.
#pragma once

#include <deque>
#include <filesystem>
#include <optional>
#include <string>

#include "FrameStats.h"
#include "microrelief/core/trace/CpuRelief.h"
#include "SceneOptions.h"
#include "microrelief/gl/HeightEditor.h"

namespace microrelief {

// What the panel shows and edits. The scene's map file, load options, height scale,
// shading and background are the view's own; its camera and size mirror the view.
struct ViewerState {
    SceneOptions scene;
    bool vsync = true;
    bool continuous = false;  // re-render the relief every frame, not only on change
    float resolution = 1.0f;  // the view's pixels per framebuffer pixel, per side
    bool flyMode = false;
    bool panelVisible = true;
    std::string typedPath;  // the panel's path field

    // Sculpting (B): the left button paints with `brush` on the relief under the cursor.
    bool sculpt = false;
    Brush brush;
    std::string savePath;  // where "Save map" writes (.png 16-bit, .exr float, .tif a DEM's)
    // An animated relief (--animate): scene.job.time advances while it plays.
    bool playing = true;

    // Shown only.
    std::string mapName;
    std::string albedoName;  // the colours in use, empty for none
    int mapWidth = 0, mapHeight = 0;
    std::string mapError;     // the last failed load; the previous map stays
    std::string shaderError;  // the last failed compile (file:line); the previous program runs
    std::string shaderFolder;
    std::string glRenderer;
    std::optional<double> gpuMilliseconds;  // the relief pass, GL timer query
    double wallMilliseconds = 0.0;          // the relief pass, draw to glFinish
    double frameMilliseconds = 0.0;         // the last frame's work, CPU side, swap included
    IterationStats iterations;
    int iterationBudget = 0;
    bool pagedMap = false;  // the map is read through pages (larger than the GL's textures)
    std::string paging;     // then its pool and whether the view is exact
    std::optional<WorldHit> pick;
    int undoSteps = 0;
    bool mapEdited = false;  // sculpted since it was opened or saved
    double yawDegrees = 0.0, pitchDegrees = 0.0;
    std::deque<std::string> log;  // newest last
};

struct PanelActions {
    std::optional<std::filesystem::path> openMap;  // a path typed into the panel
    bool reloadMap = false;                        // channel or normalisation changed
    bool heightScaleChanged = false;
    bool baseChanged = false;           // a size of the base surface
    bool baseKindChanged = false;       // another base surface: the view frames it
    bool interpolationChanged = false;  // the last level: the pyramid is built anew
    bool albedoChanged = false;         // colours on or off
    bool fovyChanged = false;
    bool methodChanged = false;
    bool screenshot = false;
    bool copyCommand = false;
    bool resetView = false;
    bool reloadShaders = false;
    bool vsyncChanged = false;
    bool undo = false;
    bool saveMap = false;
};

// Draws the panel (when visible) and the hover read-out near the cursor. `uiScale`
// is the monitor's content scale.
PanelActions drawPanel(ViewerState& state, float uiScale);

// The controls, for the panel's help and the README: key or mouse, what it does.
struct ControlHelp {
    const char* input;
    std::string action;  // a flag in it by its field (flagName), as the row spells it
};
extern const ControlHelp kControls[];
extern const int kControlCount;

}  // namespace microrelief
