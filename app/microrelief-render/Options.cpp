#include "Options.h"

#include <unistd.h>

#include <CLI/CLI.hpp>

#include "SceneOptions.h"
#include "microrelief/Version.h"
#include "microrelief/core/Error.h"

namespace microrelief {

namespace {

// The camera path flags: what they need of each other. Throws Error(BadInput).
void applyBatchFlags(const CLI::App& app, RenderOptions& o, const std::string& cameras,
                     const std::string& frames, const std::string& shard,
                     const std::string& manifest) {
    BatchOptions& b = o.batch;
    const bool turntable = app.count("--turntable") > 0;
    if (turntable && b.turntable < 1) throwBadInput("--turntable needs at least 1 view");
    if (!cameras.empty()) b.cameras = cameras;
    if (turntable && b.cameras) throwBadInput("--turntable and --cameras: give one camera path");
    if (!frames.empty()) b.frames = parseFrameRange(frames);
    if (!shard.empty()) b.shard = parseShard(shard);
    if (!manifest.empty()) b.manifest = manifest;
    for (const char* flag : {"--frames", "--shard", "--skip-existing", "--manifest"}) {
        if (!b.active() && app.count(flag) > 0)
            throwBadInput(std::string(flag) +
                          " needs a camera path (--turntable N or --cameras FILE)");
    }
    if (b.active() && o.compareReference)
        throwBadInput("--compare-reference checks one picture: not with a camera path");
    if (b.active() && app.count("--out") == 0) o.out = "out/microrelief-{frame:04d}.png";
}

}  // namespace

std::string lightSizeUnused() {
    return flagName("shading.lightSizeDegrees") + " sets the light of soft shadows, and " +
           flagName("shading.shadows") + " is not soft: it changes nothing";
}

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
    SceneFlags scene(o.scene);
    std::string backend = "auto", aov;
    std::string out = o.out.string();
    scene.addMapAndCamera(app);
    app.add_option("--out", out,
                   "Shaded picture; the format follows the extension. With a camera path, a "
                   "pattern: {frame}, {frame:04d} (default out/microrelief-{frame:04d}.png)")
        ->capture_default_str();
    app.add_option("--aov", aov,
                   "World position AOV, OpenEXR: R,G,B = hit x,y,z, A = 1 hit / 0 miss; with " +
                       flagName("shading.shadows") +
                       " a fifth channel, shadow: 1 lit, 0 shadowed or a miss");
    scene.addShading(app);
    app.add_option("--backend", backend, "GL backend: auto (EGL, then OSMesa), egl or osmesa")
        ->capture_default_str();
    app.add_flag(
        "--compare-reference", o.compareReference,
        "Also trace every pixel with the exact CPU reference and print how the picture differs");
    std::size_t memoryMib = o.paging.memoryBytes >> 20;
    addMemoryFlag(app, memoryMib, "drawn again until exact");
    std::string pyramidCache;
    app.add_option("--pyramid-cache", pyramidCache,
                   "Draw the map through pages from its pyramid file in this folder, built "
                   "there once from the map's rows in bounded memory and reused while the map "
                   "is unchanged: for maps larger than memory (images and elevation models)");
    app.add_flag("-q,--quiet", o.quiet, "Print nothing on success");
    app.add_flag("-v,--verbose", o.verbose, "Print the GL renderer and shader logs");
    std::string cameras, frames, shard, manifest;
    const std::string paths = "Camera paths (one process, many frames)";
    app.add_option("--turntable", o.batch.turntable,
                   "Render N views around the target at the eye's distance and elevation, "
                   "frames 0 to N-1")
        ->group(paths);
    app.add_option("--cameras", cameras,
                   "Render the cameras of a file: CSV or JSON lines with eye, target, up, fovy "
                   "and per-row flags (docs/batch.md)")
        ->group(paths);
    app.add_option("--frames", frames,
                   "Only frames A-B of the path (numbered from 0, both included; A- to the end)")
        ->group(paths);
    app.add_option("--shard", shard,
                   "Only shard I of N (I/N): every N-th frame, from the I-th; slurm: I and N of "
                   "this task of a Slurm job array")
        ->group(paths);
    app.add_flag("--skip-existing", o.batch.skipExisting,
                 "Leave the frames whose files are there (files are written whole or not at all)")
        ->group(paths);
    app.add_option("--manifest", manifest,
                   "The CSV of the frames done (frame,file,camera,ms,status), appended to; "
                   "{shard} and {shards} expand (default: manifest.csv, with --shard "
                   "manifest-{shard}-of-{shards}.csv, in the folder of --out)")
        ->group(paths);
    app.set_version_flag("--version",
                         std::string("microrelief-render ") + MICRORELIEF_VERSION_STRING);
    app.allow_windows_style_options(false);

    return parseCommandLine<RenderOptions>(app, argc, argv, [&] {
        scene.apply();
        o.backend = parseBackend(backend);
        o.out = out;
        if (!aov.empty()) o.aov = aov;
        applyBatchFlags(app, o, cameras, frames, shard, manifest);
        o.lightSizeGiven = app.count(flagName("shading.lightSizeDegrees")) > 0;
        o.eyeGiven = app.count(flagName("camera.eye")) > 0;
        o.targetGiven = app.count(flagName("camera.target")) > 0;
        if (o.scene.job.onMesh && o.compareReference)
            throwBadInput("--compare-reference: not yet on the mesh base (" + flagName("base") +
                          " mesh)");
        o.paging.memoryBytes = memoryMib << 20;
        // Maps past the GL's textures are paged; their samples and pyramid stay in memory.
        allowPagedMaps(o.scene.job.map.load);
        if (!pyramidCache.empty()) {
            if (o.scene.job.onMesh)
                throwBadInput("--pyramid-cache: not yet on the mesh base (" + flagName("base") +
                              " mesh)");
            o.pyramidCache = pyramidCache;
            o.scene.job.map.load.maxSamples = 0;  // never held whole: the side bounds it
        }
        return o;
    });
}

}  // namespace microrelief
