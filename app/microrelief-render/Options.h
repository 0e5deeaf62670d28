// The command line of microrelief-render (scene-and-cli.md): parsed and validated into
// a RenderJob and the file names, or a one-line reason.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

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

struct ParseResult {
    std::optional<RenderOptions> options;  // empty: nothing to render
    int exitStatus = 0;                    // when empty: 0 after --help/--version, 2 on error
    std::string message;                   // the help text, the version, or the error
};

ParseResult parseRenderOptions(int argc, char** argv);

}  // namespace microrelief
