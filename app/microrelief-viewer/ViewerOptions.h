// The command line of microrelief-viewer: the map, camera and shading flags of
// microrelief-render (app/shared/SceneOptions.h, so both read them alike), and the
// viewer's own: the automation flags that let a test or a script drive it headless
// under Xvfb, the shader folder to watch, vsync.
#pragma once

#include "CommandLine.h"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "SceneOptions.h"
#include "microrelief/gl/HeightEditor.h"
#include "microrelief/gl/PagedPyramid.h"

namespace microrelief {

// --stroke MODE,U0,V0,U1,V1: a brush stroke a script draws, from map point (u0, v0) to
// (u1, v1), with --brush-radius and --brush-strength.
struct ScriptedStroke {
    BrushMode mode = BrushMode::Raise;
    glm::dvec2 from{0.0}, to{0.0};  // map uv
};

// Whether the viewer sculpts this scene's map: one map, neither repeated (--tile) nor
// replaced by an animated field every frame (--animate). --sculpt, --stroke and --undo
// are refused otherwise, and the B key says why.
inline bool sculptable(const RenderJob& job) {
    return job.animation.empty() && job.tiles == glm::ivec2(1, 1);
}

struct ViewerOptions {
    SceneOptions scene;
    // Sculpting: the brush the panel starts with, --sculpt to start in sculpt mode.
    Brush brush;
    bool sculpt = false;
    // For scripts and tests, before the first frame: strokes, then --undo N of them; after
    // the last frame (--frames), --save-map FILE writes the edited map (16-bit PNG, float
    // EXR or a DEM's GeoTIFF, atomically: MapFile.h).
    std::vector<ScriptedStroke> strokes;
    int undo = 0;
    std::optional<std::filesystem::path> saveMap;
    // --frames N: render N frames, then write the screenshots asked for and exit 0; more
    // while a map read through pages still loads the pages its view wants, so that the
    // screenshot is the exact picture.
    int frames = 0;  // 0: run until the window closes
    // A map larger than the GL's textures is read through pages within --memory
    // (gl/PagedPyramid.h), refined over frames until exact.
    PagingSettings paging;
    // --screenshot FILE: the 3D view (no panel) after the last frame, rendered at
    // exactly --size whatever the window's size, for a pixel-by-pixel comparison with
    // microrelief-render --size.
    std::optional<std::filesystem::path> screenshot;
    // --window-screenshot FILE: the whole window, panel included, after the last frame.
    std::optional<std::filesystem::path> windowScreenshot;
    // --print-command: print the microrelief-render command line of the last view on exit.
    bool printCommand = false;
    // --shader-dir DIR: where relief.frag is read from and watched for hot reload.
    std::optional<std::filesystem::path> shaderDir;
    bool vsync = true;     // --no-vsync turns it off
    bool panel = true;     // --no-panel hides the panel at start
    bool verbose = false;  // -v: print the GL renderer and shader logs
};

ParseResult<ViewerOptions> parseViewerOptions(int argc, char** argv);

}  // namespace microrelief
