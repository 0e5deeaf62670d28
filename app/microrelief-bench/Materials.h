// microrelief-bench --materials: what materials cost (issue 14). Shadows: the frame time
// with hard and with soft shadows beside the time without, per map and light; tiling: the
// same map tiled 1 x 1, 16 x 16 and 256 x 256 in the same view, its slopes kept (the
// height scale divided by the tile count). Wall-clock medians, the settings of one row
// drawn in turn frame by frame so that drift in the machine's speed hits them alike.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "microrelief/gl/GlContext.h"

namespace microrelief::bench {

struct MaterialRow {
    std::string study;      // "shadows" or "tiling"
    std::string map;        // the relief and its size
    std::string setting;    // off / hard / soft 1 deg; 1x1 / 16x16 / 256x256
    std::string condition;  // the light's elevation, or the view
    double msWall = 0.0;
    double ratio = 1.0;         // to the group's baseline: no shadows; the tiled program's 2 x 2
    double target = 0.0;        // the bound on the ratio
    double ratioToFirst = 1.0;  // to the group's first row (tiling: the untiled 1 x 1)
};

std::vector<MaterialRow> runMaterialsBenchmark(GlContext& context, int width, int height,
                                               int frames, bool quick);

// materials.csv and materials.md in `folder`; returns the markdown.
std::string writeMaterials(const std::filesystem::path& folder, const std::string& renderer,
                           const std::vector<MaterialRow>& rows);

}  // namespace microrelief::bench
