// microrelief-bench terrain: the multilevel method against map size to terrain scale
// (Terrain.h), a line a row on the console, terrain.csv written as the run goes, then
// terrain.md and terrain.png.
#include <chrono>
#include <cstdio>
#include <iostream>

#include "CommandHelpers.h"
#include "CommandLine.h"
#include "Commands.h"
#include "Report.h"
#include "Terrain.h"
#include "microrelief/core/Machine.h"
#include "microrelief/headless/HeadlessContext.h"
#include "microrelief/io/AtomicFile.h"

namespace microrelief::bench {

void addTerrainOptions(CLI::App& app, TerrainFlags& flags) {
    const TerrainOptions defaults;  // the help's defaults are TerrainOptions' own
    const auto commas = [](const std::vector<int>& values) {
        std::string text;
        for (const int v : values) text += (text.empty() ? "" : ",") + std::to_string(v);
        return text;
    };
    addRunOptions(app, flags.run, "Maps 1024 and 4096: every path in seconds",
                  "Picture size WIDTHxHEIGHT (default " + std::to_string(defaults.width) + "x" +
                      std::to_string(defaults.height) + ")",
                  "Folder for terrain.csv, terrain.md and terrain.png (the pyramid files are "
                  "built in its terrain-pyramids, each removed after its size's rows)");
    app.add_option_function<std::string>(
        "--views", [&flags](const std::string& text) { flags.views = text; },
        "Comma-separated view angles in degrees from the surface normal, 0 to 89 (default " +
            commas(defaults.viewDegrees) + ")");
    app.add_option_function<std::string>(
        "--map-sizes", [&flags](const std::string& text) { flags.mapSizes = text; },
        "Comma-separated sides of the benchmark's relief (default " + commas(defaults.mapSizes) +
            "; 1024,4096 with --quick)");
    app.add_option("--memory", flags.memoryMib, "The page pool's budget, MiB")
        ->capture_default_str()
        ->check(wholeNumberIn(1, std::size_t{1} << 20));
}

int runTerrainCommand(const TerrainFlags& flags) {
    checkFrames(flags.run);
    TerrainOptions terrain;
    if (flags.views) terrain.viewDegrees = parseViews(*flags.views);
    if (flags.mapSizes)
        terrain.mapSizes = parseMapSizes(*flags.mapSizes);
    else if (flags.run.quick)
        terrain.mapSizes = {1024, 4096};
    if (flags.run.size) parseSizeFlag(*flags.run.size, terrain.width, terrain.height);
    checkOutputFolder(flags.run.outDir);
    terrain.frames = flags.run.frames;
    terrain.memoryBytes = flags.memoryMib << 20;
    // Maps made in memory (whole and paged paths, the reference) while their samples,
    // pyramid and reference take at most 60 % of the machine's memory (about 20 bytes a
    // sample: the paged path's 16, kPagedBytesPerSample, and the reference's own pyramid);
    // larger ones from pyramid files alone.
    terrain.inMemorySamples = physicalMemoryBytes() * 6 / 10 / 20;
    terrain.pyramidFolder = std::filesystem::path(flags.run.outDir) / "terrain-pyramids";
    if (terrain.mapSizes.empty()) throwBadInput("--map-sizes names no size");
    const auto context = createHeadlessContext(parseBackend(flags.run.backend));
    const std::filesystem::path folder = flags.run.outDir;
    std::vector<TerrainRow> rows;
    const auto start = std::chrono::steady_clock::now();
    std::printf(
        "microrelief-bench --terrain: %zu map sizes; a paged map's pyramid is built on the "
        "CPU (about 0.2 us a texel on two cores: minutes for the largest)\n",
        terrain.mapSizes.size());
    std::fflush(stdout);
    runTerrainBenchmark(*context, terrain, [&](const TerrainRow& r) {
        rows.push_back(r);
        writeTerrainCsv(folder / "terrain.csv", context->renderer(), rows);
        const double elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::printf(
            "[%6.0f s] %5d %-5s %2d deg: prepare %8.1f ms, first %8.1f ms (%d draws, %zu "
            "pages), frame %7.2f ms, 1 px %7.2f ms, %5.1f fetches, GL %6.0f MiB, process "
            "%6.0f MiB, %s\n",
            elapsed, r.mapSize, terrainPathName(r.path), r.viewDegrees, r.prepareMs, r.firstMs,
            r.draws, r.pagesLoaded, r.frameMs, r.frameOnePixelMs, r.fetchesMean, r.gpuMiB,
            r.processMiB,
            r.checked ? (fixed(r.coverageMismatchPct, 3) + " % / " + fixed(r.offHalfTexelPct, 3) +
                         " % off" + (r.sampled ? " (sampled pixels)" : ""))
                            .c_str()
                      : "not checked");
        std::fflush(stdout);
    });
    const std::string table = terrainTable(context->renderer(), today(), rows);
    writeTextAtomically(folder / "terrain.md", table);
    std::string why;
    const bool plot = writeTerrainPlot(folder, rows, why);
    if (!plot) std::cerr << "microrelief-bench: warning: no plot: " << why << '\n';
    std::cout << '\n'
              << table << "microrelief-bench: wrote " << (folder / "terrain.csv").string()
              << (plot ? ", terrain.md and terrain.png\n" : " and terrain.md\n");
    return 0;
}

}  // namespace microrelief::bench
