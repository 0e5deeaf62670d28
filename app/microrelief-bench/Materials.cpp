#include "Materials.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "Benchmark.h"
#include "Report.h"
#include "Timing.h"
#include "microrelief/core/DataPaths.h"
#include "microrelief/core/Error.h"
#include "microrelief/gl/StateGuard.h"
#include "microrelief/gl/OffscreenTarget.h"
#include "microrelief/gl/ReliefRenderer.h"

namespace microrelief::bench {

namespace {

struct Variant {
    std::string name;
    std::function<void()> prepare;  // sets the renderer up for this variant
    ShadingOptions shading;
};

// Median wall milliseconds of each variant, drawn in turn: a round draws every variant
// once, after two warm-up rounds.
std::vector<double> timeInTurn(const GL& gl, ReliefRenderer& renderer, OffscreenTarget& target,
                               const CameraFrame& camera, std::vector<Variant>& variants,
                               int frames) {
    Timer timer(gl);
    std::vector<std::vector<double>> wall(variants.size());
    for (int round = -2; round < frames; ++round) {
        for (std::size_t v = 0; v < variants.size(); ++v) {
            variants[v].prepare();
            const auto [gpu, ms] = timer.time([&] {
                target.clear(glm::vec3(0.0f));
                const gl::SrgbWrites srgb(gl);
                renderer.draw(camera, variants[v].shading);
            });
            (void)gpu;
            if (round >= 0) wall[v].push_back(ms);
        }
    }
    std::vector<double> medians;
    for (auto& w : wall) medians.push_back(median(w));
    return medians;
}

}  // namespace

std::vector<MaterialRow> runMaterialsBenchmark(GlContext& context, int width, int height,
                                               int frames, bool quick) {
    context.makeCurrent();
    const GL& gl = context.gl();
    ReliefRenderer renderer(gl, shaderDirectory());
    OffscreenTarget target(gl, width, height);
    std::vector<MaterialRow> rows;

    // Shadows: the bench's relief at 45 degrees, lights high and low.
    for (int size : quick ? std::vector<int>{256} : std::vector<int>{256, 4096}) {
        const HeightMap map = benchRelief(size);
        renderer.apply(ReliefDesc{}, MethodSettings{}, &map, "cobbles");  // height scale 0.1
        const ReliefExtent extent = reliefExtent(map, 0.1);
        const CameraFrame camera =
            resolveCamera(viewCamera(45, {}, extent.topHeight), width, height, sceneRadius(extent));
        for (double elevation : {45.0, 10.0}) {
            const double e = glm::radians(elevation), a = glm::radians(200.0);
            std::vector<Variant> variants(3);
            const char* names[] = {"off", "hard", "soft 1 deg"};
            const ShadowMode modes[] = {ShadowMode::Off, ShadowMode::Hard, ShadowMode::Soft};
            for (int k = 0; k < 3; ++k) {
                variants[k].name = names[k];
                variants[k].prepare = [] {};
                variants[k].shading.lightDirection =
                    glm::vec3(std::cos(e) * std::cos(a), std::sin(e), std::cos(e) * std::sin(a));
                variants[k].shading.shadows = modes[k];
                variants[k].shading.lightSizeDegrees = 1.0f;
            }
            const std::vector<double> ms =
                timeInTurn(gl, renderer, target, camera, variants, frames);
            for (int k = 0; k < 3; ++k) {
                char condition[64];
                std::snprintf(condition, sizeof condition, "light %.0f deg", elevation);
                rows.push_back({"shadows", "cobbles " + std::to_string(size), variants[k].name,
                                condition, ms[k], ms[k] / ms[0], k == 1 ? 2.0 : 0.0,
                                ms[k] / ms[0]});
                std::printf("shadows %5d  %-10s %-13s %8.2f ms  %.2fx\n", size,
                            variants[k].name.c_str(), condition, ms[k], ms[k] / ms[0]);
                std::fflush(stdout);
            }
        }
    }

    // Tiling: the 256 map tiled 1, 2, 16 and 256 times a side in the same view at 45
    // degrees, the height scale divided by the count so the stones keep their shape.
    const HeightMap tile = benchRelief(256);
    // 2 x 2 beside 1 x 1: an untiled map is drawn by the untiled program, whose reads
    // skip the tiles' addressing; from 2 x 2 on, the tiled one.
    const int counts[] = {1, 2, 16, 256};
    std::vector<double> ms;
    for (int n : counts) {
        ReliefDesc tiled;
        tiled.tiles = {n, n};
        tiled.heightScale = 0.1f / n;
        renderer.apply(tiled, &tile, "cobbles");
        const ReliefExtent extent =
            reliefExtent(256 * n, 256 * n, tile.maxValue(), 0.1 / n, BaseShape{});
        const CameraFrame camera =
            resolveCamera(viewCamera(45, {}, extent.topHeight), width, height, sceneRadius(extent));
        std::vector<Variant> one(1);
        one[0].prepare = [] {};
        ms.push_back(timeInTurn(gl, renderer, target, camera, one, frames)[0]);
        // The bound: as the levels the traversal descends, from the tiled program's 2 x 2.
        const std::string setting = std::to_string(n) + "x" + std::to_string(n);
        if (n == 1) {
            // Its ratio to 2 x 2 is known once 2 x 2 is timed (below).
            rows.push_back(
                {"tiling", "cobbles 256", setting, "view 45 deg", ms.back(), 0.0, 0.0, 1.0});
            std::printf("tiling  %-9s %8.2f ms  (the untiled program)\n", setting.c_str(),
                        ms.back());
        } else {
            const double bound = std::log2(256.0 * n) / std::log2(512.0);
            rows.push_back({"tiling", "cobbles 256", setting, "view 45 deg", ms.back(),
                            ms.back() / ms[1], bound, ms.back() / ms.front()});
            std::printf("tiling  %-9s %8.2f ms  %.2fx of 2x2 (bound %.2fx), %.2fx of 1x1\n",
                        setting.c_str(), ms.back(), rows.back().ratio, bound,
                        rows.back().ratioToFirst);
        }
        std::fflush(stdout);
    }
    rows[rows.size() - std::size(counts)].ratio = ms[0] / ms[1];
    return rows;
}

std::string writeMaterials(const std::filesystem::path& folder, const std::string& renderer,
                           const std::vector<MaterialRow>& rows) {
    std::filesystem::create_directories(folder);
    std::ostringstream csv, md;
    csv << "study,map,setting,condition,ms_wall,ratio,target,ratio_to_first\n";
    md << "# microrelief-bench --materials\n\nRenderer: " << renderer
       << ". Wall-clock medians; ratios within this run. Shadows: the settings of a group "
          "drawn in turn, each to the same view without. Tiling: each count timed in its turn "
          "(its own map and pyramid), to the tiled program's 2 x 2 (an untiled "
          "map is drawn by the untiled program), the bound the levels the traversal descends, "
          "log2(256 N) / log2(512); the last column is to the untiled 1 x 1.\n\n"
       << "| study | map | condition | setting | ms | ratio | target | to the first |\n"
       << "|---|---|---|---|---|---|---|---|\n";
    for (const MaterialRow& r : rows) {
        csv << r.study << ',' << r.map << ',' << r.setting << ',' << r.condition << ',' << r.msWall
            << ',' << r.ratio << ',' << r.target << ',' << r.ratioToFirst << '\n';
        std::string target;
        if (r.target > 0.0) {
            char bound[32];
            std::snprintf(bound, sizeof bound, "%.2f", r.target);
            target = r.ratio <= r.target ? std::string("<= ") + bound + " met"
                                         : std::string("> ") + bound + " missed";
        }
        char line[256];
        std::snprintf(line, sizeof line, "| %s | %s | %s | %s | %.2f | %.2fx | %s | %.2fx |\n",
                      r.study.c_str(), r.map.c_str(), r.condition.c_str(), r.setting.c_str(),
                      r.msWall, r.ratio, target.c_str(), r.ratioToFirst);
        md << line;
    }
    for (const auto& [name, text] :
         {std::pair{"materials.csv", csv.str()}, {"materials.md", md.str()}})
        writeTextAtomically(folder / name, text);
    return md.str();
}

}  // namespace microrelief::bench
