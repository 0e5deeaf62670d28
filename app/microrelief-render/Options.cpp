#include "Options.h"

#include <CLI/CLI.hpp>

#include "SceneOptions.h"
#include "core/Error.h"

namespace microrelief {

ParseResult<RenderOptions> parseRenderOptions(int argc, char** argv) {
    RenderOptions o;
    CLI::App app{
        "Renders a height map as microrelief, ray traced per pixel by multilevel binary "
        "subdivision\n"
        "(Vyatkin & Romaniuk), headless through EGL or OSMesa.",
        "microrelief-render"};
    app.get_formatter()->column_width(34);

    // The map, camera and shading flags are shared with microrelief-viewer, whose "copy as
    // command" writes them for this program (app/shared/SceneOptions.h).
    SceneFlags scene(o.heightFile, o.load, o.job);
    std::string backend = "auto", aov;
    std::string out = o.out.string();
    scene.addMapAndCamera(app);
    app.add_option("--out", out, "Shaded picture; the format follows the extension")
        ->capture_default_str();
    app.add_option("--aov", aov,
                   "World position AOV, OpenEXR: R,G,B = hit x,y,z, A = 1 hit / 0 miss");
    scene.addShading(app);
    app.add_option("--backend", backend, "GL backend: auto (EGL, then OSMesa), egl or osmesa")
        ->capture_default_str();
    app.add_flag(
        "--compare-reference", o.compareReference,
        "Also trace every pixel with the exact CPU reference and print how the picture differs");
    app.add_flag("-q,--quiet", o.quiet, "Print nothing on success");
    app.add_flag("-v,--verbose", o.verbose, "Print the GL renderer and shader logs");
    app.set_version_flag("--version", std::string("microrelief-render ") + MICRORELIEF_VERSION);
    app.allow_windows_style_options(false);

    return parseCommandLine<RenderOptions>(app, argc, argv, [&] {
        scene.apply();
        o.backend = parseBackend(backend);
        o.out = out;
        if (!aov.empty()) o.aov = aov;
        return o;
    });
}

}  // namespace microrelief
