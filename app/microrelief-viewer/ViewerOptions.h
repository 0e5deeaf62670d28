// The command line of microrelief-viewer: the map, camera and shading flags of
// microrelief-render (app/shared/SceneOptions.h, so both read them alike), and the
// viewer's own: the automation flags that let a test or a script drive it headless
// under Xvfb, the shader folder to watch, vsync.
#pragma once

#include "CommandLine.h"

#include <filesystem>
#include <optional>
#include <string>

#include "SceneOptions.h"

namespace microrelief {

struct ViewerOptions {
    SceneOptions scene;
    // --frames N: render N frames, then write the screenshots asked for and exit 0.
    int frames = 0;  // 0: run until the window closes
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
