#include "Terrain.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include "Benchmark.h"
#include "Report.h"
#include "SceneOptions.h"
#include "Timing.h"
#include "microrelief/core/trace/Accuracy.h"
#include "microrelief/gl/HeadlessRender.h"

namespace microrelief::bench {

namespace {

// The process's resident memory now (VmRSS), MiB; 0 where /proc does not say.
double residentMiB() {
    std::ifstream status("/proc/self/status");
    for (std::string line; std::getline(status, line);) {
        if (line.rfind("VmRSS:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;  // kB
    }
    return 0.0;
}

// The mean of the instrumented picture's texel reads over the pixels whose exact ray hits.
double fetchesOverHits(const RenderedFrame& counted, const ReferencePicture& reference) {
    double sum = 0.0;
    std::size_t hits = 0;
    for (std::size_t k = 0; k < reference.hits.size(); ++k) {
        if (!reference.hits[k]) continue;
        sum += counted.stats[k * 4 + 1];
        ++hits;
    }
    return hits ? sum / hits : 0.0;
}

}  // namespace

void runTerrainBenchmark(GlContext& context, const TerrainOptions& options,
                         const std::function<void(const TerrainRow&)>& report) {
    context.makeCurrent();
    const GL& gl = context.gl();
    GLint maxTexture = 0;
    gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
    // A renderer a path for the whole run, so that its programs are compiled once, before
    // any timing (pictures of a small map at every view), not in a first picture's time.
    // Between sizes each holds a 2 x 2 map: the large one's textures, pages and CPU
    // pyramid are freed before the next is made. The warm-up map is as large as the first
    // rows' (warmed on a 64 x 64 map, the first row, at 1024, still ran 2.5x slow here).
    const HeightMap small = benchRelief(1024), tiny(2, 2);
    std::map<bool, HeadlessRenderer> renderers;
    for (const bool paged : {false, true}) {
        HeadlessRenderer& renderer = renderers.try_emplace(paged, context).first->second;
        PagingSettings paging;
        paging.mode = paged ? PagingSettings::Mode::Always : PagingSettings::Mode::Never;
        paging.memoryBytes = options.memoryBytes;
        renderer.setPaging(paging);
        renderer.setHeightMap(small, "relief");
        for (int degrees : options.viewDegrees) {
            RenderJob job;
            job.width = options.width;
            job.height = options.height;
            job.camera =
                viewCamera(degrees, {}, reliefExtent(small, job.heightScale, {}).topHeight);
            // llvmpipe's first frames after start-up ran up to 1.7x slow (Benchmark.cpp):
            // half a second of pictures first.
            const auto warmUntil =
                std::chrono::steady_clock::now() + std::chrono::milliseconds(500);
            do {
                renderer.render(job);
            } while (std::chrono::steady_clock::now() < warmUntil);
            renderer.setCountFetches(true);
            renderer.render(job);
            renderer.setCountFetches(false);
        }
        renderer.setHeightMap(tiny, "relief");
    }

    for (int n : options.mapSizes) {
        const HeightMap map = benchRelief(n);
        std::map<int, ReferencePicture> references;  // per view, traced once for both paths
        for (const bool paged : {false, true}) {
            if (!paged && n > maxTexture) continue;  // past one texture: pages only
            HeadlessRenderer& renderer = renderers.at(paged);
            const double prepareMs = wallMs(gl, [&] { renderer.setHeightMap(map, "relief"); });
            for (int degrees : options.viewDegrees) {
                TerrainRow row;
                row.mapSize = n;
                row.paged = paged;
                row.viewDegrees = degrees;
                row.width = options.width;
                row.height = options.height;
                row.prepareMs = prepareMs;
                RenderJob job;
                job.width = options.width;
                job.height = options.height;
                job.camera =
                    viewCamera(degrees, {}, reliefExtent(map, job.heightScale, {}).topHeight);

                HeadlessResult first;
                row.firstMs = wallMs(gl, [&] { first = renderer.render(job); });
                row.draws = first.paging.draws;
                row.pagesLoaded = first.paging.pagesLoaded;
                std::vector<double> exact, onePixel;
                std::size_t framePages = 0;
                for (int f = 0; f < options.frames; ++f) {
                    exact.push_back(
                        wallMs(gl, [&] { framePages += renderer.render(job).paging.pagesLoaded; }));
                }
                row.pagesPerFrame = static_cast<double>(framePages) / options.frames;
                job.method.pixelError = 1.0f;
                renderer.render(job);  // what the coarser reads want, loaded
                for (int f = 0; f < options.frames; ++f)
                    onePixel.push_back(wallMs(gl, [&] { renderer.render(job); }));
                job.method.pixelError = 0.0f;
                row.frameMs = median(exact);
                row.frameOnePixelMs = median(onePixel);

                auto reference = references.find(degrees);
                if (reference == references.end()) {
                    reference = references
                                    .emplace(degrees, traceReferencePicture(first.camera, map,
                                                                            job.heightScale))
                                    .first;
                }
                const Accuracy accuracy =
                    compareWithReference(first.frame, first.camera, reference->second);
                row.coverageMismatchPct = accuracy.coverageMismatchPercent();
                row.offHalfTexelPct = accuracy.offHalfTexelPercent();
                renderer.setCountFetches(true);
                row.fetchesMean = fetchesOverHits(renderer.render(job).frame, reference->second);
                renderer.setCountFetches(false);
                row.gpuMiB = renderer.gpuBytes() / double(1 << 20);
                row.processMiB = residentMiB();
                report(row);
            }
            renderer.setHeightMap(tiny, "relief");
        }
    }
}

void writeTerrainCsv(const std::filesystem::path& file, const std::string& renderer,
                     const std::vector<TerrainRow>& rows) {
    std::ostringstream out;
    out << "map_size,path,view_degrees,prepare_ms,first_picture_ms,draws,pages_loaded,frame_ms,"
           "pages_per_frame,frame_1px_ms,fetches_per_hit_pixel,gpu_mib,process_mib,coverage_"
           "mismatch_pct,"
           "off_half_texel_pct,width,height,renderer\n";
    for (const TerrainRow& r : rows) {
        out << r.mapSize << ',' << (r.paged ? "paged" : "whole") << ',' << r.viewDegrees << ','
            << fixed(r.prepareMs, 1) << ',' << fixed(r.firstMs, 2) << ',' << r.draws << ','
            << r.pagesLoaded << ',' << fixed(r.frameMs, 3) << ',' << fixed(r.pagesPerFrame, 1)
            << ',' << fixed(r.frameOnePixelMs, 3) << ',' << fixed(r.fetchesMean, 2) << ','
            << fixed(r.gpuMiB, 1) << ',' << fixed(r.processMiB, 0) << ','
            << fixed(r.coverageMismatchPct, 3) << ',' << fixed(r.offHalfTexelPct, 3) << ','
            << r.width << ',' << r.height << ',' << csvQuote(renderer) << '\n';
    }
    writeTextAtomically(file, out.str());
}

std::string terrainTable(const std::string& renderer, const std::string& date,
                         const std::vector<TerrainRow>& rows) {
    std::ostringstream md;
    md << "Terrain run " << date << " on " << renderer
       << ": the multilevel method, wall time to glFinish (each picture read back), "
       << (rows.empty() ? 0 : rows[0].width) << " x " << (rows.empty() ? 0 : rows[0].height)
       << " pixels; frames are medians of the pictures after the first (a paged map's pages "
          "resident where the budget holds them).\n\n"
       << "| map | path | view | prepare s | first picture ms (paged: draws, pages) | frame ms "
          "(paged: pages a frame) | "
          "1 px frame ms | fetches / hit pixel | GL MiB | process MiB | mismatch % | off % |\n"
       << "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const TerrainRow& r : rows) {
        md << "| " << r.mapSize << " | " << (r.paged ? "paged" : "whole") << " | " << r.viewDegrees
           << "° | " << fixed(r.prepareMs / 1000.0, 1) << " | " << fixed(r.firstMs, 1)
           << (r.paged ? " (" + std::to_string(r.draws) + ", " + std::to_string(r.pagesLoaded) + ")"
                       : std::string())
           << " | " << fixed(r.frameMs, 1)
           << (r.paged ? " (" + fixed(r.pagesPerFrame, 0) + ")" : std::string()) << " | "
           << fixed(r.frameOnePixelMs, 1) << " | " << fixed(r.fetchesMean, 1) << " | "
           << fixed(r.gpuMiB, 0) << " | " << fixed(r.processMiB, 0) << " | "
           << fixed(r.coverageMismatchPct, 3) << " | " << fixed(r.offHalfTexelPct, 3) << " |\n";
    }
    return md.str();
}

bool writeTerrainPlot(const std::filesystem::path& folder, const std::vector<TerrainRow>& rows,
                      std::string& why) {
    if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) {
        why = "gnuplot is not installed (apt-get install gnuplot-nox)";
        return false;
    }
    // A block per path and view: map size, frame ms, fetches.
    std::ostringstream data;
    std::vector<std::string> titles;
    for (const bool paged : {false, true}) {
        std::vector<int> views;
        for (const TerrainRow& r : rows) {
            if (r.paged == paged &&
                std::find(views.begin(), views.end(), r.viewDegrees) == views.end())
                views.push_back(r.viewDegrees);
        }
        for (int view : views) {
            for (const TerrainRow& r : rows) {
                if (r.paged == paged && r.viewDegrees == view)
                    data << r.mapSize << ' ' << r.frameMs << ' ' << r.fetchesMean << '\n';
            }
            data << "\n\n";
            titles.push_back(std::string(paged ? "paged" : "whole") + ", " + std::to_string(view) +
                             " deg");
        }
    }
    if (titles.empty()) {
        why = "no rows";
        return false;
    }
    const std::filesystem::path table = folder / "terrain_plot.txt";
    writeTextAtomically(table, data.str());
    std::ostringstream script;
    script << "set terminal pngcairo size 1000,420 noenhanced\nset output "
           << gnuplotString((folder / "terrain.png.part").string())
           << "\nset multiplot layout 1,2\nset logscale x 2\nset grid\nset key top left\n"
              "set xlabel 'map size (texels a side)'\n";
    for (const auto& [column, label] :
         {std::pair<int, std::string>{2, "frame, wall ms"}, {3, "texel fetches per hit pixel"}}) {
        // Time on a log scale (pages reloaded every frame cost 100 times a frame), the
        // fetches from 0.
        script << (column == 2 ? "set logscale y\nset yrange [*:*]\n"
                               : "unset logscale y\nset yrange [0:*]\n")
               << "set ylabel '" << label << "'\nplot ";
        for (std::size_t k = 0; k < titles.size(); ++k) {
            script << (k ? ", " : "") << gnuplotString(table.string()) << " index " << k
                   << " using 1:" << column << " with linespoints title "
                   << gnuplotString(titles[k]);
        }
        script << '\n';
    }
    script << "unset multiplot\n";
    writeTextAtomically(folder / "terrain.gnuplot", script.str());
    const std::string command =
        "gnuplot " + shellQuote((folder / "terrain.gnuplot").string()) + " 2>&1";
    if (std::system(command.c_str()) != 0) {
        why = "gnuplot failed on " + (folder / "terrain.gnuplot").string();
        return false;
    }
    std::error_code ec;
    std::filesystem::rename(folder / "terrain.png.part", folder / "terrain.png", ec);
    if (ec) {
        why = "cannot rename " + (folder / "terrain.png.part").string() + ": " + ec.message();
        return false;
    }
    return true;
}

}  // namespace microrelief::bench
