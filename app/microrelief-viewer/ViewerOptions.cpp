#include "ViewerOptions.h"

#include <CLI/CLI.hpp>

#include "microrelief/Version.h"
#include "microrelief/core/Error.h"
#include "microrelief/image/ImageFile.h"

namespace microrelief {

namespace {

void addViewerFlags(CLI::App& app, ViewerOptions& o, std::string& screenshot,
                    std::string& windowScreenshot, std::string& shaderDir, bool& noVsync,
                    bool& noPanel) {
    app.add_option("--frames", o.frames,
                   "Render this many frames, write the screenshots asked for, and exit");
    app.add_option("--screenshot", screenshot,
                   "After the last frame, write the 3D view (no panel) at exactly --size (implies "
                   "--frames 1)");
    app.add_option(
        "--window-screenshot", windowScreenshot,
        "After the last frame, write the whole window, panel included (implies --frames 1)");
    app.add_flag("--print-command", o.printCommand,
                 "On exit, print the microrelief-render command line that renders the last view");
    app.add_option("--shader-dir", shaderDir,
                   "Folder of relief.frag, watched for hot reload (default: the source tree's "
                   "shaders/ when run "
                   "from the build tree, else the installed ones)");
    app.add_flag("--no-vsync", noVsync, "Start with vsync off");
    app.add_flag("--no-panel", noPanel, "Start with the panel hidden (Tab shows it)");
    app.add_flag("-v,--verbose", o.verbose, "Print the GL renderer and shader logs");
}

// Checks and fills what CLI11 parsed; throws Error(BadInput).
void finish(ViewerOptions& o, SceneFlags& scene, const std::string& screenshot,
            const std::string& windowScreenshot, const std::string& shaderDir, bool noVsync,
            bool noPanel) {
    scene.apply();
    // Checked here, not by CLI::NonNegativeNumber, whose message prints the range up to
    // the largest double in 309 digits.
    if (o.frames < 0)
        throwBadInput("--frames must be 0 (run until the window closes) or more, got " +
                      std::to_string(o.frames));
    if (!screenshot.empty()) {
        o.screenshot = screenshot;
        checkImageExtension(*o.screenshot);
    }
    if (!windowScreenshot.empty()) {
        o.windowScreenshot = windowScreenshot;
        checkImageExtension(*o.windowScreenshot);
    }
    if ((o.screenshot || o.windowScreenshot) && o.frames == 0) o.frames = 1;
    if (!shaderDir.empty()) o.shaderDir = shaderDir;
    o.vsync = !noVsync;
    o.panel = !noPanel;
}

}  // namespace

ParseResult<ViewerOptions> parseViewerOptions(int argc, char** argv) {
    ViewerOptions o;
    CLI::App app{
        "Shows a height map as microrelief in a window, ray traced per pixel by multilevel binary\n"
        "subdivision (Vyatkin & Romaniuk), with a panel for the map, the light and the method's\n"
        "debug views. Drop an image on the window to open it.",
        "microrelief-viewer"};
    app.get_formatter()->column_width(34);

    SceneFlags scene(o.scene);
    std::string screenshot, windowScreenshot, shaderDir;
    bool noVsync = false, noPanel = false;
    scene.addMapAndCamera(app);
    scene.addShading(app);
    addViewerFlags(app, o, screenshot, windowScreenshot, shaderDir, noVsync, noPanel);
    app.set_version_flag("--version",
                         std::string("microrelief-viewer ") + MICRORELIEF_VERSION_STRING);
    app.allow_windows_style_options(false);

    return parseCommandLine<ViewerOptions>(app, argc, argv, [&] {
        finish(o, scene, screenshot, windowScreenshot, shaderDir, noVsync, noPanel);
        return o;
    });
}

}  // namespace microrelief
