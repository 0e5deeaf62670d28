#include "Rebuild.h"

#include <algorithm>
#include <chrono>
#include <sstream>

#include "Benchmark.h"
#include "Report.h"
#include "Timing.h"
#include "microrelief/core/DataPaths.h"
#include "microrelief/gl/HeightEditor.h"
#include "microrelief/gl/OffscreenTarget.h"
#include "microrelief/gl/ReliefRenderer.h"

namespace microrelief::bench {

void runRebuild(GlContext& context, const RebuildOptions& options,
                const std::function<void(const RebuildRow&)>& report) {
    context.makeCurrent();
    const GL& gl = context.gl();
    OffscreenTarget target(gl, options.width, options.height);
    for (int n : options.mapSizes) {
        RebuildRow row;
        row.mapSize = n;
        row.width = options.width;
        row.height = options.height;
        const HeightMap map = benchRelief(n);
        ReliefRenderer renderer(gl, shaderDirectory());

        // The path the pyramid took before: built on the CPU, uploaded whole.
        row.cpuBuildMs = wallMs(gl, [&] { renderer.apply(ReliefDesc{}, &map, "relief"); });
        renderer.apply(ReliefDesc{}, &map, "relief", PyramidBuild::Gpu);
        row.bytesPerTexel =
            static_cast<double>(renderer.textures()->gpuBytes(gl)) / (static_cast<double>(n) * n);

        std::vector<double> full, brush, frame;
        renderer.heightsReplaced();  // warm-up
        for (int k = 0; k < options.frames; ++k)
            full.push_back(wallMs(gl, [&] { renderer.heightsReplaced(); }));

        // A dab of radius 32 covers 64 x 64 samples; a stroke's dabs walk across the map.
        HeightEditor editor(gl, shaderDirectory());
        const Brush dab{BrushMode::Raise, 32.0, 0.01f};
        editor.dab(renderer, {n * 0.25, n * 0.5}, dab);
        for (int k = 0; k < options.frames; ++k) {
            const glm::dvec2 centre(n * (0.3 + 0.4 * k / options.frames) + 0.5, n * 0.5 + 0.5);
            brush.push_back(wallMs(gl, [&] { editor.dab(renderer, centre, dab); }));
        }
        editor.endStroke();

        const ReliefExtent extent = reliefExtent(n, n, renderer.maxHeight(), 0.1, {});
        const CameraFrame camera =
            resolveCamera(viewCamera(45, {}, extent.topHeight), options.width, options.height,
                          sceneRadius(extent));
        const auto draw = [&] {
            target.clear(glm::vec3(0.0f));
            renderer.draw(camera, ShadingOptions{});
        };
        draw();
        draw();
        for (int k = 0; k < options.frames; ++k) frame.push_back(wallMs(gl, draw));

        // The aligned pyramid too, as where the maxmip peer runs.
        MethodSettings maxmip;
        maxmip.method = Method::MaxMip;
        renderer.setMethod(maxmip);
        row.bytesPerTexelWithMaxMip =
            static_cast<double>(renderer.textures()->gpuBytes(gl)) / (static_cast<double>(n) * n);

        row.fullRebuildMs = median(full);
        row.brushUpdateMs = median(brush);
        row.frameTraceMs = median(frame);
        report(row);
    }
}

void writeRebuildCsv(const std::filesystem::path& file, const std::string& renderer,
                     const std::vector<RebuildRow>& rows) {
    std::ostringstream out;
    out << "map_size,full_rebuild_ms,brush_update_ms,frame_trace_ms,renderer,"
           "full_rebuild_over_frame,brush_update_over_frame,cpu_build_upload_ms,"
           "gpu_bytes_per_texel,gpu_bytes_per_texel_with_maxmip,width,height\n";
    for (const RebuildRow& r : rows) {
        out << r.mapSize << ',' << fixed(r.fullRebuildMs, 3) << ',' << fixed(r.brushUpdateMs, 3)
            << ',' << fixed(r.frameTraceMs, 3) << ',' << csvQuote(renderer) << ','
            << fixed(r.fullRebuildMs / r.frameTraceMs, 3) << ','
            << fixed(r.brushUpdateMs / r.frameTraceMs, 4) << ',' << fixed(r.cpuBuildMs, 1) << ','
            << fixed(r.bytesPerTexel, 2) << ',' << fixed(r.bytesPerTexelWithMaxMip, 2) << ','
            << r.width << ',' << r.height << '\n';
    }
    writeTextAtomically(file, out.str());
}

std::string rebuildTable(const std::string& renderer, const std::string& date,
                         const std::vector<RebuildRow>& rows) {
    std::ostringstream md;
    md << "Rebuild run " << date << " on " << renderer << ": medians, wall time to glFinish.\n\n"
       << "| map | full rebuild ms | 64 x 64 dab ms | frame ms ("
       << (rows.empty() ? 0 : rows[0].width) << " x " << (rows.empty() ? 0 : rows[0].height)
       << ") | rebuild / frame (target <= 1) | dab / frame (target <= 0.05) | CPU build + upload "
          "ms | "
          "GPU bytes per texel (with maxmip's pyramid) |\n"
       << "|---|---|---|---|---|---|---|---|\n";
    for (const RebuildRow& r : rows) {
        md << "| " << r.mapSize << " | " << fixed(r.fullRebuildMs, 1) << " | "
           << fixed(r.brushUpdateMs, 2) << " | " << fixed(r.frameTraceMs, 1) << " | "
           << fixed(r.fullRebuildMs / r.frameTraceMs, 2) << " | "
           << fixed(r.brushUpdateMs / r.frameTraceMs, 3) << " | " << fixed(r.cpuBuildMs, 0) << " | "
           << fixed(r.bytesPerTexel, 2) << " (" << fixed(r.bytesPerTexelWithMaxMip, 2) << ") |\n";
    }
    return md.str();
}

}  // namespace microrelief::bench
