// microrelief-bench --terrain: the paper's claim at terrain scale (issue 29). For each map
// size, the benchmark's relief (one continuous relief at every resolution) drawn by the
// multilevel method through HeadlessRenderer, the way microrelief-render draws it: in
// whole textures where the GL holds the map, through pages (gl/PagedPyramid.h) from the map
// and its pyramid in memory where the machine's memory holds them, and through pages from
// a pyramid file (io/PyramidFile.h) at every size, made a band of rows at a time: past
// memory too. Per size and view: the map's preparation (the pyramid built and uploaded; a
// file built and opened), the first picture (drawn again until no page is wanted: exact),
// the frame once its pages are resident, exact and at one pixel of error, the fetches per
// pixel, the GL and process memory, and the picture against the exact CPU reference where
// the map is held in memory.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "microrelief/gl/GlContext.h"

namespace microrelief::bench {

// How a row's map was drawn.
enum class TerrainPath { Whole, Paged, File };
const char* terrainPathName(TerrainPath path);

struct TerrainOptions {
    std::vector<int> mapSizes{1024, 4096, 16384, 24576, 65536};
    std::vector<int> viewDegrees{45, 80};
    int width = 256, height = 256;
    int frames = 10;                                   // timed frames after the first picture
    std::size_t memoryBytes = std::size_t{512} << 20;  // the page pool's budget
    // Maps of more samples than this are not made in memory: drawn from pyramid files
    // alone, checked against the reference on sampled pixels read from the file
    // (PagedReferenceTracer; 0: every map in memory).
    std::size_t inMemorySamples = 0;
    // Where the pyramid files are built, each removed after its size's rows.
    std::filesystem::path pyramidFolder = "terrain-pyramids";
};

struct TerrainRow {
    int mapSize = 0;
    TerrainPath path = TerrainPath::Whole;
    bool paged() const { return path != TerrainPath::Whole; }
    int viewDegrees = 0;
    // setHeights: the pyramid built (GPU whole, CPU paged), uploaded; a file: built (the
    // map's rows made too), opened and the coarse levels uploaded.
    double prepareMs = 0.0;
    double fileMiB = 0.0;    // the pyramid file's size
    double firstMs = 0.0;    // the first picture of this view, until exact, wall
    int draws = 0;           // its draws (paged: until none wanted a page)
    std::size_t pagesLoaded = 0;
    double frameMs = 0.0;  // median picture after the first, exact
    // Pages loaded a frame: 0 where the view's pages fit the budget (the frames draw once);
    // more where they do not, and every frame loads pages again.
    double pagesPerFrame = 0.0;
    double frameOnePixelMs = 0.0;  // the same at --pixel-error 1
    double fetchesMean = 0.0;      // texel reads per pixel whose ray met the relief
    double gpuMiB = 0.0;           // the map's textures, or pool, coarse texture and tables
    double processMiB = 0.0;       // the process's resident memory after the row
    // Against the CPU reference: every pixel (the map in memory), or about 4096 pixels
    // spread over the picture (`sampled`: the map read from its pyramid file); then
    bool checked = false, sampled = false;
    double coverageMismatchPct = 0.0, offHalfTexelPct = 0.0;
    int width = 0, height = 0;
};

void runTerrainBenchmark(GlContext& context, const TerrainOptions& options,
                         const std::function<void(const TerrainRow&)>& report);

// terrain.csv (written whole or not at all), and the same as a Markdown table, returned.
void writeTerrainCsv(const std::filesystem::path& file, const std::string& renderer,
                     const std::vector<TerrainRow>& rows);
std::string terrainTable(const std::string& renderer, const std::string& date,
                         const std::vector<TerrainRow>& rows);
// terrain.png: frame time and fetches against map size, whole and paged, per view
// (gnuplot). False with `why` where it cannot.
bool writeTerrainPlot(const std::filesystem::path& folder, const std::vector<TerrainRow>& rows,
                      std::string& why);

}  // namespace microrelief::bench
