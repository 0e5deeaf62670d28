#include "ViewerOptions.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>

#include "MapFile.h"
#include "SceneOptions.h"
#include "microrelief/Version.h"
#include "microrelief/core/Error.h"
#include "microrelief/io/AtomicFile.h"
#include "microrelief/io/ImageFile.h"

namespace microrelief {

namespace {

// The text of the sculpting flags, checked after the parse.
struct SculptFlags {
    std::vector<std::string> strokes;
    std::string saveMap;
    double radius = 8.0, strength = 0.02;
};

void addSculptFlags(CLI::App& app, ViewerOptions& o, SculptFlags& f) {
    app.add_flag("--sculpt", o.sculpt, "Start in sculpt mode (B toggles it)");
    app.add_option("--brush-radius", f.radius, "The brush's radius, map texels")
        ->capture_default_str();
    app.add_option("--brush-strength", f.strength,
                   "The brush's strength: raise, lower: map units a dab at its centre; smooth, "
                   "flatten: the fraction of the way a dab moves (above 1 it moves all the way)")
        ->capture_default_str();
    app.add_option("--stroke", f.strokes,
                   "For scripts: a brush stroke MODE,U0,V0,U1,V1 (raise, lower, smooth, flatten; "
                   "map uv from and to) drawn before the first frame; may repeat")
        ->take_all();
    app.add_option("--undo", o.undo, "For scripts: undo this many strokes after --stroke");
    app.add_option("--save-map", f.saveMap,
                   "After the last frame, write the edited map: FILE.png (16 bits, heights 0 to "
                   "1), FILE.exr (float) or, for an elevation model's, FILE.tif (a GeoTIFF of "
                   "metres on its grid)");
}

BrushMode parseBrushMode(const std::string& name) {
    for (BrushMode mode :
         {BrushMode::Raise, BrushMode::Lower, BrushMode::Smooth, BrushMode::Flatten}) {
        if (name == brushModeName(mode)) return mode;
    }
    throwBadInput("--stroke: unknown brush '" + name +
                  "' (expected raise, lower, smooth, flatten)");
}

void finishSculpt(ViewerOptions& o, const SculptFlags& f) {
    if (!(f.radius > 0.0) || !std::isfinite(f.radius) || f.radius > 1e5)
        throwBadInput("--brush-radius must be a positive number of texels (up to 100000)");
    if (!(f.strength > 0.0) || !std::isfinite(f.strength) || f.strength > 1e6)
        throwBadInput("--brush-strength must be a positive number (up to 1e6)");
    o.brush.radius = f.radius;
    o.brush.strength = static_cast<float>(f.strength);
    for (const std::string& text : f.strokes) {
        const auto comma = text.find(',');
        ScriptedStroke stroke;
        stroke.mode = parseBrushMode(text.substr(0, comma));
        if (comma == std::string::npos)
            throwBadInput("--stroke expects MODE,U0,V0,U1,V1 (map uv, 0 to 1), got '" + text + "'");
        std::vector<double> uv;
        try {
            uv = parseNumberList("--stroke", text.substr(comma + 1), 4,
                                 "MODE,U0,V0,U1,V1 (map uv, 0 to 1)");
        } catch (const Error&) {
            // The list's own message quotes the numbers only: the whole value, as given.
            throwBadInput("--stroke expects MODE,U0,V0,U1,V1 (map uv, 0 to 1), got '" + text + "'");
        }
        for (double value : uv) {
            if (value < 0.0 || value > 1.0)
                throwBadInput("--stroke " + text + ": map uv must lie in 0 to 1");
        }
        stroke.from = {uv[0], uv[1]};
        stroke.to = {uv[2], uv[3]};
        o.strokes.push_back(stroke);
    }
    if (o.undo < 0) throwBadInput("--undo must be 0 or more");
    // The window's rule (sculptable), refused with the reason that applies.
    if ((o.sculpt || !o.strokes.empty() || o.undo > 0) && !sculptable(o.scene.job)) {
        throwBadInput(o.scene.job.animation.empty()
                          ? "--sculpt, --stroke and --undo: the viewer sculpts an untiled map only "
                            "(" +
                                flagName("tiles") + " 1,1)"
                          : "--sculpt, --stroke and --undo: an animated relief cannot be sculpted "
                            "(" +
                                flagName("animation") + ")");
    }
    // Undone are the strokes the script draws (a map opened is not sculpted yet).
    if (o.undo > static_cast<int>(o.strokes.size())) {
        throwBadInput("--undo " + std::to_string(o.undo) + ": more than the " +
                      std::to_string(o.strokes.size()) + " --stroke given");
    }
    if (!f.saveMap.empty()) {
        o.saveMap = f.saveMap;
        checkMapExtension(*o.saveMap);
    }
}

void addViewerFlags(CLI::App& app, ViewerOptions& o, std::string& screenshot,
                    std::string& windowScreenshot, std::string& shaderDir, bool& noVsync,
                    bool& noPanel, std::size_t& memoryMib) {
    app.add_option("--frames", o.frames,
                   "Render this many frames (more while a paged map loads its view's pages), "
                   "write the screenshots asked for, and exit; 0 (the default): run until the "
                   "window closes");
    addMemoryFlag(app, memoryMib, "refined over frames until exact");
    app.add_option("--screenshot", screenshot,
                   "After the last frame, write the 3D view (no panel) at exactly " +
                       flagName("size") + " (implies --frames 1)");
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
            bool noPanel, std::size_t memoryMib) {
    scene.apply();
    // The mesh base is microrelief-render's so far (gl/HeadlessRender.h), not the window's.
    if (o.scene.job.onMesh)
        throwBadInput("--base mesh: not yet in microrelief-viewer (microrelief-render draws it)");
    // Maps past the GL's textures are paged; their samples and pyramid stay in memory.
    o.paging.memoryBytes = memoryMib << 20;
    allowPagedMaps(o.scene.job.map.load);
    // Checked here, not by CLI::NonNegativeNumber, whose message prints the range up to
    // the largest double in 309 digits.
    if (o.frames < 0)
        throwBadInput("--frames must be 0 (run until the window closes) or more, got " +
                      std::to_string(o.frames));
    if (!screenshot.empty()) {
        o.screenshot = screenshot;
        checkReplaceable(*o.screenshot);  // a folder named as one, whatever its extension
        checkImageExtension(*o.screenshot);
    }
    if (!windowScreenshot.empty()) {
        o.windowScreenshot = windowScreenshot;
        checkReplaceable(*o.windowScreenshot);
        checkImageExtension(*o.windowScreenshot);
    }
    if ((o.screenshot || o.windowScreenshot) && o.frames == 0) o.frames = 1;
    if (!shaderDir.empty()) {
        // The files the renderer reads from it, there before a window opens.
        std::error_code ec;
        if (!std::filesystem::exists(shaderDir, ec))
            throwBadInput("--shader-dir " + shaderDir + ": no such folder");
        if (!std::filesystem::is_directory(shaderDir, ec))
            throwBadInput("--shader-dir " + shaderDir + ": not a folder");
        for (const char* file : {"relief.frag", "relief_box.vert"}) {
            if (!std::filesystem::is_regular_file(std::filesystem::path(shaderDir) / file, ec))
                throwBadInput("--shader-dir " + shaderDir + ": no " + file +
                              " there (the folder of the project's shaders/)");
        }
        o.shaderDir = shaderDir;
    }
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
    std::size_t memoryMib = o.paging.memoryBytes >> 20;
    SculptFlags sculpt;
    scene.addMapAndCamera(app);
    scene.addShading(app);
    addViewerFlags(app, o, screenshot, windowScreenshot, shaderDir, noVsync, noPanel, memoryMib);
    addSculptFlags(app, o, sculpt);
    app.set_version_flag("--version",
                         std::string("microrelief-viewer ") + MICRORELIEF_VERSION_STRING);
    app.allow_windows_style_options(false);

    return parseCommandLine<ViewerOptions>(app, argc, argv, [&] {
        finish(o, scene, screenshot, windowScreenshot, shaderDir, noVsync, noPanel, memoryMib);
        finishSculpt(o, sculpt);
        if ((!o.strokes.empty() || o.undo > 0 || o.saveMap) && o.frames == 0) o.frames = 1;
        // Before the window opens, as microrelief-render does: no folder or device where a
        // file goes (it would be moved away), and no file given for two outputs (the last
        // written would replace the first).
        std::vector<std::filesystem::path> outputs;
        for (const auto* file : {&o.saveMap, &o.screenshot, &o.windowScreenshot})
            if (*file) outputs.push_back(**file);
        checkOutputTargets(outputs);
        // Nor one the viewer reads (the map, its albedo), which writing it would replace.
        std::vector<NamedFile> written;
        for (const auto& [file, flag] :
             {std::pair{&o.saveMap, "--save-map"}, std::pair{&o.screenshot, "--screenshot"},
              std::pair{&o.windowScreenshot, "--window-screenshot"}})
            if (*file) written.push_back({**file, flag});
        checkOutputsAreNotInputs(written, filesRead(o.scene.job));
        return o;
    });
}

}  // namespace microrelief
