// relief-renderer: a picture of a relief drawn by the library's renderer from the scene
// value, in a headless context, and a pick at its centre by the relief on the CPU. The
// walk-through of docs/api.md, which shows this file from its first #include.
//
//   relief-renderer [--height FILE] [--out FILE]
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "microrelief/core/DataPaths.h"
#include "microrelief/core/Error.h"
#include "microrelief/core/scene/Scene.h"
#include "microrelief/core/trace/CpuRelief.h"
#include "microrelief/gl/OffscreenTarget.h"
#include "microrelief/gl/ReliefMap.h"
#include "microrelief/gl/ReliefPrograms.h"
#include "microrelief/gl/ReliefRenderer.h"
#include "microrelief/gl/StateGuard.h"
#include "microrelief/headless/HeadlessContext.h"
#include "microrelief/io/ImageFile.h"
#include "microrelief/io/ReliefFiles.h"

using namespace microrelief;

int run(const std::string& heightFile, const std::string& out) {
    // The scene: what the relief is, and how it is looked at. Checked once, at the door.
    ReliefDesc relief;  // the bundled map, its colours, on the plane
    if (!heightFile.empty()) relief.map.file = heightFile;
    ViewDesc view;  // microrelief-render's default camera
    view.width = 640;
    view.height = 360;
    throwIfInvalid(validateScene(relief, view));
    checkOutputTargets({out});  // an image extension, not a folder: before any work

    // Its files: the heights and, with the bundled map, its colours. The library looks for
    // its data folder (the bundled map, the shaders) beside the running program
    // (../share/microrelief); this program does not live in the package's prefix: it names it.
    setDataDirectory(DATA_DIR);
    const ReliefFiles files = loadReliefFiles(relief);
    const std::string name = files.heightFile ? files.heightFile->string() : "the map";

    // A context; its programs; the map's GPU resources; one relief drawing the map. The GL
    // objects are made after the context, so they go before it.
    const std::unique_ptr<GlContext> context = createHeadlessContext(Backend::Auto);
    const GL& gl = context->gl();
    const auto programs = std::make_shared<ReliefPrograms>(gl, shaderDirectory());
    const std::shared_ptr<ReliefMap> map =
        ReliefMap::upload(programs, *files.heights, files.heights, name,
                          MapUploadSettings::of(relief));
    ReliefRenderer renderer(programs, view.method);
    renderer.apply(relief, map);
    if (files.albedo) renderer.setAlbedo(&*files.albedo, files.albedoFile->string());

    // The view drawn into an offscreen target (linear colour, encoded to sRGB by the GL).
    OffscreenTarget target(gl, view.width, view.height);
    target.clear(view.background);
    CameraFrame camera;
    {
        const gl::SrgbWrites srgb(gl);
        camera = renderer.draw(view);
    }
    const RenderedFrame frame = target.read(camera.eye);
    const std::vector<std::uint8_t> rgb = rgbFromRgba(frame.color, frame.width, frame.height);
    writeImageAtomically(out, {frame.width, frame.height, 3, PixelType::UInt8, rgb.data(), {}});

    // The centre pixel's hit, from the picture and from the relief on the CPU.
    const int column = view.width / 2, row = view.height / 2;
    CpuRelief cpu;
    cpu.apply(relief, files.heights);
    if (const std::optional<WorldHit> hit = cpu.pick(camera, column, row)) {
        const glm::dvec3 gpu = frame.worldPositionAt(column, row);
        std::printf("centre: gpu %.5f %.5f %.5f, cpu %.5f %.5f %.5f\n", gpu.x, gpu.y, gpu.z,
                    hit->position.x, hit->position.y, hit->position.z);
    }
    std::printf("relief-renderer: wrote %s (%s)\n", out.c_str(), context->renderer().c_str());
    return 0;
}

int main(int argc, char** argv) {
    try {
        std::string height, out = "relief.png";
        for (int k = 1; k < argc; k += 2) {
            const std::string flag = argv[k];
            if (k + 1 >= argc) throwBadInput(flag + ": a value is missing");
            if (flag == "--height")
                height = argv[k + 1];
            else if (flag == "--out")
                out = argv[k + 1];
            else
                throwBadInput("unknown option " + flag);
        }
        return run(height, out);
    } catch (const Error& e) {  // a bad file or value (exit 2), a missing GL (exit 1)
        std::fprintf(stderr, "relief-renderer: error: %s\n", e.what());
        return exitStatusOf(e.kind());
    }
}
