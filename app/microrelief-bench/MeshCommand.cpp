// microrelief-bench mesh: the mesh base against the analytic base it copies (Mesh.h), a line
// a row on the console, mesh.csv written as the run goes and mesh.md at its end.
#include <cstdio>
#include <iostream>

#include "CommandHelpers.h"
#include "Commands.h"
#include "Mesh.h"
#include "Report.h"
#include "microrelief/headless/HeadlessContext.h"

namespace microrelief::bench {

void addMeshOptions(CLI::App& app, MeshFlags& flags) {
    addRunOptions(app, flags.run, "", "Size WIDTHxHEIGHT of the pictures (default 256x256)",
                  "Folder for mesh.csv and mesh.md");
    app.add_option("--map-size", flags.mapSize,
                   "Side of the benchmark's relief, texels (a square map)")
        ->capture_default_str();
    app.add_option("--grids", flags.grids,
                   "Flat grids of N x N quads (1 to 128) copying the plane base (2 N^2 "
                   "triangles), comma-separated; 0 alone: none")
        ->capture_default_str();
    app.add_option("--tubes", flags.tubes,
                   "Tubes of S sides (4 to 512) and S/4 rings, at least one, copying the "
                   "cylinder base (2 S max(1, S/4) triangles), comma-separated; 0 alone: none")
        ->capture_default_str();
    app.add_option("--views", flags.views, "View angles, degrees from the base's normal")
        ->capture_default_str();
}

namespace {

// Counts from `least` to `most`, or "0" alone for none.
std::vector<int> parseCounts(const std::string& list, const std::string& flag, int least,
                             int most, const std::string& what) {
    if (list == "0") return {};
    std::vector<int> counts = parseList(list, flag, flag, [&](const std::string& text) {
        const bool digits = !text.empty() && text.size() <= 5 &&
                            text.find_first_not_of("0123456789") == std::string::npos;
        const int n = digits ? std::stoi(text) : 0;
        if (n < least || n > most)
            throwBadInput(flag + ": '" + text + "' is not " + what + " (a whole number, " +
                          std::to_string(least) + " to " + std::to_string(most) + ")");
        return n;
    });
    if (counts.empty()) throwBadInput(flag + " names nothing (a comma-separated list, or 0)");
    refuseRepeats(counts, flag, [](int n) { return std::to_string(n); });
    return counts;
}

}  // namespace

int runMeshCommand(const MeshFlags& flags) {
    checkFrames(flags.run);
    MeshBenchOptions options;
    parseSizeFlag(flags.run.size.value_or("256x256"), options.width, options.height);
    options.frames = flags.run.frames;
    if (flags.mapSize < 2 || flags.mapSize > 8192)
        throwBadInput("--map-size: " + std::to_string(flags.mapSize) +
                      " is not a map side (2 to 8192 texels)");
    options.mapSize = flags.mapSize;
    // 128 quads a side is 32768 triangles, 512 sides 131072: past the 10k, and the
    // CPU twins' count over every prism a ray's box crosses takes minutes beyond.
    options.gridQuads = parseCounts(flags.grids, "--grids", 1, 128, "a grid's quads a side");
    options.tubeSides = parseCounts(flags.tubes, "--tubes", 4, 512, "a tube's sides");
    if (options.gridQuads.empty() && options.tubeSides.empty())
        throwBadInput("--grids 0 and --tubes 0 leave nothing to measure");
    options.viewDegrees = parseViews(flags.views);
    checkOutputFolder(flags.run.outDir);
    const auto context = createHeadlessContext(parseBackend(flags.run.backend));
    const Clock clock = resolveClock(Clock::Auto, context->renderer());
    const std::filesystem::path folder = flags.run.outDir;
    std::vector<MeshBenchRow> rows;
    runMeshBench(*context, options, clock, [&](const MeshBenchRow& r) {
        rows.push_back(r);
        writeMeshCsv(folder / "mesh.csv", context->renderer(), clock, rows);
        std::printf(
            "%-8s %2d deg, %-12s %6d triangles: base %7.2f ms, mesh %7.2f ms, mesh / base %.2f "
            "(%.2f-%.2f); hit/miss differ %.2f %%, offset median %.3f texel; fetches base "
            "%.1f, mesh %.1f over %.1f prisms\n",
            r.base.c_str(), r.degrees, r.mesh.c_str(), r.triangles, r.baseMs, r.meshMs,
            r.ratio.median, r.ratio.low, r.ratio.high,
            r.pixels ? 100.0 * r.hitMiss / r.pixels : 0.0, r.offsetMedian, r.baseFetches,
            r.meshFetches, r.prisms);
        std::fflush(stdout);
    });
    const std::string table = meshTable(context->renderer(), clock, today(), options, rows);
    writeTextAtomically(folder / "mesh.md", table);
    std::cout << '\n'
              << table << "microrelief-bench: wrote " << (folder / "mesh.csv").string()
              << " and mesh.md\n";
    return 0;
}

}  // namespace microrelief::bench
