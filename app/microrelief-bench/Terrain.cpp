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
#include "microrelief/core/ParallelRows.h"
#include "microrelief/core/synth/SyntheticMaps.h"
#include "microrelief/core/trace/Accuracy.h"
#include "microrelief/core/trace/ReferenceTracer.h"
#include "microrelief/gl/HeadlessRender.h"
#include "microrelief/io/PyramidFile.h"

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

// The same over the pixels the picture itself hits, where no reference was traced.
double fetchesOverPictureHits(const RenderedFrame& counted, const RenderedFrame& picture) {
    double sum = 0.0;
    std::size_t hits = 0;
    for (std::size_t k = 3; k < picture.position.size(); k += 4) {
        if (picture.position[k] < 0.5f) continue;
        sum += counted.stats[k - 3 + 1];
        ++hits;
    }
    return hits ? sum / hits : 0.0;
}

}  // namespace

// A picture slower than this is timed once after the first, not options.frames times.
constexpr double kSlowFrameMs = 10000.0;

const char* terrainPathName(TerrainPath path) {
    switch (path) {
        case TerrainPath::Whole:
            return "whole";
        case TerrainPath::Paged:
            return "paged";
        case TerrainPath::File:
            return "file";
    }
    return "?";
}

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
    std::map<TerrainPath, HeadlessRenderer> renderers;
    for (const TerrainPath path : {TerrainPath::Whole, TerrainPath::Paged, TerrainPath::File}) {
        HeadlessRenderer& renderer = renderers.try_emplace(path, context).first->second;
        PagingSettings paging;
        paging.mode =
            path == TerrainPath::Whole ? PagingSettings::Mode::Never : PagingSettings::Mode::Always;
        paging.memoryBytes = options.memoryBytes;
        renderer.setPaging(paging);
        renderer.setHeights(RenderJob{}, small, "relief");
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
        renderer.setHeights(RenderJob{}, tiny, "relief");
    }

    // One size's rows of one path, its map prepared; `map` where it is held in memory, else
    // `pages` (its pyramid file), from which the reference reads on sampled pixels.
    const auto measure = [&](HeadlessRenderer& renderer, TerrainPath path, int n, double prepareMs,
                             double fileMiB, float top, const HeightMap* map,
                             const std::shared_ptr<const PyramidPages>& pages,
                             std::map<int, ReferencePicture>& references) {
        for (int degrees : options.viewDegrees) {
            TerrainRow row;
            row.mapSize = n;
            row.path = path;
            row.viewDegrees = degrees;
            row.width = options.width;
            row.height = options.height;
            row.prepareMs = prepareMs;
            row.fileMiB = fileMiB;
            RenderJob job;
            job.width = options.width;
            job.height = options.height;
            job.camera =
                viewCamera(degrees, {}, reliefExtent(n, n, top, job.heightScale, {}).topHeight);

            HeadlessResult first;
            row.firstMs = wallMs(gl, [&] { first = renderer.render(job); });
            row.draws = first.paging.draws;
            row.pagesLoaded = first.paging.pagesLoaded;
            // Frames slower than kSlowFrameMs (a map far past the budget, its pages read
            // from disk for every picture) are timed once: the median of one.
            const auto framesAfter = [&](double firstMs) {
                return firstMs > kSlowFrameMs ? 1 : options.frames;
            };
            std::vector<double> exact, onePixel;
            std::size_t framePages = 0;
            const int exactFrames = framesAfter(row.firstMs);
            for (int f = 0; f < exactFrames; ++f) {
                exact.push_back(
                    wallMs(gl, [&] { framePages += renderer.render(job).paging.pagesLoaded; }));
            }
            row.pagesPerFrame = static_cast<double>(framePages) / exactFrames;
            job.method.pixelError = 1.0f;
            // What the coarser reads want, loaded (timed: it says how many frames to time).
            const double firstOnePixelMs = wallMs(gl, [&] { renderer.render(job); });
            for (int f = 0; f < framesAfter(firstOnePixelMs); ++f)
                onePixel.push_back(wallMs(gl, [&] { renderer.render(job); }));
            job.method.pixelError = 0.0f;
            row.frameMs = median(exact);
            row.frameOnePixelMs = median(onePixel);

            renderer.setCountFetches(true);
            const RenderedFrame counted = renderer.render(job).frame;
            renderer.setCountFetches(false);
            if (map) {
                auto reference = references.find(degrees);
                if (reference == references.end()) {
                    reference = references
                                    .emplace(degrees, traceReferencePicture(first.camera, *map,
                                                                            job.heightScale))
                                    .first;
                }
                const Accuracy accuracy =
                    compareWithReference(first.frame, first.camera, reference->second);
                row.checked = true;
                row.coverageMismatchPct = accuracy.coverageMismatchPercent();
                row.offHalfTexelPct = accuracy.offHalfTexelPercent();
                row.fetchesMean = fetchesOverHits(counted, reference->second);
            } else {
                row.fetchesMean = fetchesOverPictureHits(counted, first.frame);
                if (pages) {
                    // About 4096 pixels spread evenly (traceSampledReferencePicture).
                    const PagedReferenceTracer reference(pages, job.heightScale);
                    const Accuracy accuracy = compareWithReference(
                        first.frame, first.camera,
                        traceSampledReferencePicture(
                            first.camera, [&](const Ray& ray) { return reference.trace(ray); }, n,
                            glm::dmat3(1.0)));
                    row.checked = row.sampled = true;
                    row.coverageMismatchPct = accuracy.coverageMismatchPercent();
                    row.offHalfTexelPct = accuracy.offHalfTexelPercent();
                }
            }
            row.gpuMiB = renderer.gpuBytes() / double(1 << 20);
            row.processMiB = residentMiB();
            report(row);
        }
        renderer.setHeights(RenderJob{}, tiny, "relief");
    };

    for (int n : options.mapSizes) {
        const bool inMemory =
            options.inMemorySamples == 0 ||
            static_cast<std::size_t>(n) * static_cast<std::size_t>(n) <= options.inMemorySamples;
        // Shared with the pages, as the programs share theirs (no copy in the paged path's
        // preparation).
        std::shared_ptr<const HeightMap> map;
        if (inMemory) map = std::make_shared<const HeightMap>(benchRelief(n));
        std::map<int, ReferencePicture> references;  // per view, traced once for every path
        for (const TerrainPath path : {TerrainPath::Whole, TerrainPath::Paged}) {
            if (!map || (path == TerrainPath::Whole && n > maxTexture)) continue;
            HeadlessRenderer& renderer = renderers.at(path);
            const double prepareMs = wallMs(gl, [&] { renderer.setHeights(RenderJob{}, map, "relief"); });
            measure(renderer, path, n, prepareMs, 0.0, map->maxValue(), &*map, nullptr, references);
        }

        // The pyramid file, from the map's rows: copied where it is in memory, else made a
        // band at a time on every core (cobblesRows: the same samples).
        std::filesystem::create_directories(options.pyramidFolder);
        const std::filesystem::path file =
            options.pyramidFolder / ("relief-" + std::to_string(n) + ".mrpyr");
        MapRows rows;
        rows.width = rows.height = n;
        rows.read = [&](int y0, int y1, float* out) {
            if (map) {
                std::copy(map->samples.begin() + static_cast<std::ptrdiff_t>(y0) * n,
                          map->samples.begin() + static_cast<std::ptrdiff_t>(y1) * n, out);
                return;
            }
            parallelRows(y0, y1, n, [&](int a, int b) {
                synth::cobblesRows(n, n, kBenchReliefSeed, a, b,
                                   out + static_cast<std::ptrdiff_t>(a - y0) * n);
            });
        };
        HeadlessRenderer& renderer = renderers.at(TerrainPath::File);
        int shown = -1;
        const auto progress = [&](long long done, long long total) {
            const int percent = static_cast<int>(100 * done / total);
            if (n >= 16384 && percent / 10 != shown / 10) {
                std::fprintf(stderr, "microrelief-bench: pyramid file of %d^2: %d %%\n", n,
                             percent);
                shown = percent;
            }
        };
        std::shared_ptr<const PyramidFile> pages;
        const double prepareMs = wallMs(gl, [&] {
            writePyramidFile(file, rows, false, "bench relief " + std::to_string(n), file.string(),
                             kPyramidFilePageSide, progress);
            pages = PyramidFile::open(file);
            renderer.setPyramidPages(pages, file.string());
        });
        const double fileMiB = std::filesystem::file_size(file) / double(1 << 20);
        measure(renderer, TerrainPath::File, n, prepareMs, fileMiB, pages->largestSample(),
                map ? &*map : nullptr, map ? nullptr : pages, references);
        pages.reset();
        std::filesystem::remove(file);
    }
    std::error_code ignored;
    std::filesystem::remove(options.pyramidFolder, ignored);  // where empty
}

void writeTerrainCsv(const std::filesystem::path& file, const std::string& renderer,
                     const std::vector<TerrainRow>& rows) {
    std::ostringstream out;
    out << "map_size,path,view_degrees,prepare_ms,file_mib,first_picture_ms,draws,pages_loaded,"
           "frame_ms,pages_per_frame,frame_1px_ms,fetches_per_hit_pixel,gpu_mib,process_mib,"
           "coverage_mismatch_pct,off_half_texel_pct,width,height,renderer\n";
    for (const TerrainRow& r : rows) {
        // Unchecked rows (no reference: the map not in memory) leave the accuracy empty.
        out << r.mapSize << ',' << terrainPathName(r.path) << ',' << r.viewDegrees << ','
            << fixed(r.prepareMs, 1) << ',' << fixed(r.fileMiB, 1) << ',' << fixed(r.firstMs, 2)
            << ',' << r.draws << ',' << r.pagesLoaded << ',' << fixed(r.frameMs, 3) << ','
            << fixed(r.pagesPerFrame, 1) << ',' << fixed(r.frameOnePixelMs, 3) << ','
            << fixed(r.fetchesMean, 2) << ',' << fixed(r.gpuMiB, 1) << ',' << fixed(r.processMiB, 0)
            << ',' << (r.checked ? fixed(r.coverageMismatchPct, 3) : std::string()) << ','
            << (r.checked ? fixed(r.offHalfTexelPct, 3) : std::string()) << ',' << r.width << ','
            << r.height << ',' << csvQuote(renderer) << '\n';
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
          "resident where the budget holds them). Paths: whole textures, pages from the map "
          "in memory, pages from a pyramid file (prepare: the file built, opened, uploaded; "
          "mismatch and off: against the CPU reference on every pixel, or, marked *, on "
          "about 4096 sampled pixels read from the pyramid file where the map is not held in "
          "memory).\n\n"
       << "| map | path | view | prepare s | first picture ms (paged: draws, pages) | frame ms "
          "(paged: pages a frame) | "
          "1 px frame ms | fetches / hit pixel | GL MiB | process MiB | file MiB | mismatch % | "
          "off % |\n"
       << "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const TerrainRow& r : rows) {
        md << "| " << r.mapSize << " | " << terrainPathName(r.path) << " | " << r.viewDegrees
           << "° | " << fixed(r.prepareMs / 1000.0, 1) << " | " << fixed(r.firstMs, 1)
           << (r.paged()
                   ? " (" + std::to_string(r.draws) + ", " + std::to_string(r.pagesLoaded) + ")"
                   : std::string())
           << " | " << fixed(r.frameMs, 1)
           << (r.paged() ? " (" + fixed(r.pagesPerFrame, 0) + ")" : std::string()) << " | "
           << fixed(r.frameOnePixelMs, 1) << " | " << fixed(r.fetchesMean, 1) << " | "
           << fixed(r.gpuMiB, 0) << " | " << fixed(r.processMiB, 0) << " | "
           << (r.path == TerrainPath::File ? fixed(r.fileMiB, 0) : std::string("-")) << " | "
           << (r.checked ? fixed(r.coverageMismatchPct, 3) + (r.sampled ? "*" : "")
                         : std::string("n/a"))
           << " | "
           << (r.checked ? fixed(r.offHalfTexelPct, 3) + (r.sampled ? "*" : "")
                         : std::string("n/a"))
           << " |\n";
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
    for (const TerrainPath path : {TerrainPath::Whole, TerrainPath::Paged, TerrainPath::File}) {
        std::vector<int> views;
        for (const TerrainRow& r : rows) {
            if (r.path == path &&
                std::find(views.begin(), views.end(), r.viewDegrees) == views.end())
                views.push_back(r.viewDegrees);
        }
        for (int view : views) {
            for (const TerrainRow& r : rows) {
                if (r.path == path && r.viewDegrees == view)
                    data << r.mapSize << ' ' << r.frameMs << ' ' << r.fetchesMean << '\n';
            }
            data << "\n\n";
            titles.push_back(std::string(terrainPathName(path)) + ", " + std::to_string(view) +
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
