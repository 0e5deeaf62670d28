// The command line of microrelief-render (scene-and-cli.md): parsed and validated into
// a RenderJob and the file names, or a one-line reason.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "CommandLine.h"
#include "FrameSelection.h"
#include "SceneOptions.h"
#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/gl/HeadlessRender.h"
#include "microrelief/headless/HeadlessContext.h"

namespace microrelief {

// A camera path (--turntable, --cameras) and what a run does with it (README, "Camera
// paths and batch rendering"). Without a path the program draws its one picture.
struct BatchOptions {
    int turntable = 0;  // views; 0: no turntable
    std::optional<std::filesystem::path> cameras;
    FrameRange frames;
    std::optional<Shard> shard;
    bool skipExisting = false;
    std::optional<std::string> manifest;  // a pattern with {shard}, {shards}

    bool active() const { return turntable > 0 || cameras.has_value(); }
};

struct RenderOptions {
    SceneOptions scene;  // the map, its colours, the camera and the shading
    std::filesystem::path out = "out/microrelief.png";  // with a path: a FramePattern
    std::optional<std::filesystem::path> aov;
    BatchOptions batch;
    Backend backend = Backend::Auto;
    bool compareReference = false;  // print accuracy figures against the CPU reference
    bool quiet = false;
    bool verbose = false;
    bool lightSizeGiven = false;  // --light-size on the command line
    // --eye, --target on the command line: on the mesh base, the one not given frames the
    // mesh (gl/HeadlessRender.h: meshCamera).
    bool eyeGiven = false, targetGiven = false;
    // Maps past the GL's texture size: read through pages, within --memory (MiB).
    PagingSettings paging;
    // --pyramid-cache: the map drawn from its pyramid file kept there (io/PyramidFile.h),
    // never read whole.
    std::optional<std::filesystem::path> pyramidCache;
};

// The warning for a --light-size that no frame uses (soft shadows are off).
std::string lightSizeUnused();

ParseResult<RenderOptions> parseRenderOptions(int argc, char** argv);

}  // namespace microrelief
