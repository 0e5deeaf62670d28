// The command line of microrelief-render (scene-and-cli.md): parsed and validated into
// a RenderJob and the file names, or a one-line reason.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "CommandLine.h"
#include "context/GlContext.h"
#include "heightmap/HeightMap.h"
#include "render/HeadlessRender.h"

namespace microrelief {

struct RenderOptions {
    std::optional<std::filesystem::path> heightFile;  // empty: the bundled default map
    HeightMapLoadOptions load;
    RenderJob job;
    std::filesystem::path out = "out/microrelief.png";
    std::optional<std::filesystem::path> aov;
    Backend backend = Backend::Auto;
    bool compareReference = false;  // print accuracy figures against the CPU reference
    bool quiet = false;
    bool verbose = false;
};

ParseResult<RenderOptions> parseRenderOptions(int argc, char** argv);

}  // namespace microrelief
