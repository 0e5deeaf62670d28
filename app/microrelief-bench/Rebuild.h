// microrelief-bench --rebuild: what a map that changes costs (issue 16). For each map size,
// the benchmark's relief with its pyramids on the GPU: a full rebuild of both pyramids on
// the GPU (PyramidBuilder), the update after a 64 x 64 brush dab (HeightEditor: the dab,
// the pyramids over what it changed, the new top read back), and beside them a frame's
// trace of the same map and the CPU build and upload it replaces; the GPU memory the
// map's textures take per map texel.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "microrelief/gl/GlContext.h"

namespace microrelief::bench {

struct RebuildOptions {
    std::vector<int> mapSizes{1024, 2048, 4096, 8192};
    int width = 512, height = 512;  // the frame traced beside the rebuilds
    int frames = 10;                // timed repetitions of each, after a warm-up
};

struct RebuildRow {
    int mapSize = 0;
    double fullRebuildMs = 0.0;            // median, wall time to glFinish (the top read back)
    double brushUpdateMs = 0.0;            // median over dabs of 64 x 64 samples
    double frameTraceMs = 0.0;             // median frame, multilevel exact, 45 degrees
    double cpuBuildMs = 0.0;               // MaxPyramid on the CPU and the upload, once
    double bytesPerTexel = 0.0;            // the samples and the windows, per map texel
    double bytesPerTexelWithMaxMip = 0.0;  // and the aligned pyramid, where maxmip runs
    int width = 0, height = 0;
};

void runRebuild(GlContext& context, const RebuildOptions& options,
                const std::function<void(const RebuildRow&)>& report);

// rebuild.csv: map_size, full_rebuild_ms, brush_update_ms, frame_trace_ms, renderer, and the
// ratios, the CPU build, bytes per texel (with and without maxmip's pyramid) and the frame's
// size. Written whole or not at all.
void writeRebuildCsv(const std::filesystem::path& file, const std::string& renderer,
                     const std::vector<RebuildRow>& rows);
// The same as a Markdown table, returned.
std::string rebuildTable(const std::string& renderer, const std::string& date,
                         const std::vector<RebuildRow>& rows);

}  // namespace microrelief::bench
