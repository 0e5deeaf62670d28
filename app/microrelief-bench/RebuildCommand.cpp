// microrelief-bench rebuild: what a changing map costs (Rebuild.h), a line a map size on
// the console, rebuild.csv written as the run goes and rebuild.md at its end.
#include <cstdio>
#include <iostream>

#include "CommandHelpers.h"
#include "Commands.h"
#include "Rebuild.h"
#include "Report.h"
#include "microrelief/headless/HeadlessContext.h"
#include "microrelief/io/AtomicFile.h"

namespace microrelief::bench {

void addRebuildOptions(CLI::App& app, RebuildFlags& flags) {
    addRunOptions(app, flags.run, "",
                  "Size WIDTHxHEIGHT of the frame traced beside the rebuilds (default 512x512)",
                  "Folder for rebuild.csv and rebuild.md");
    app.add_option("--map-sizes", flags.mapSizes, "Map sizes, comma-separated")
        ->capture_default_str();
}

namespace {

// A side in texels: digits only, 1 to 65536 (the maps are square).
std::vector<int> parseRebuildSizes(const std::string& list, const std::string& flag) {
    const std::vector<int> sizes =
        parseList(list, "--size", flag, [&flag](const std::string& text) {
            const bool digits = !text.empty() && text.size() <= 5 &&
                                text.find_first_not_of("0123456789") == std::string::npos;
            const int side = digits ? std::stoi(text) : 0;
            if (side < 1 || side > 65536)
                throwBadInput(flag + ": '" + text +
                              "' is not a map side (a whole number of texels, 1 to 65536)");
            return side;
        });
    if (sizes.empty()) throwBadInput(flag + " names no size (a comma-separated list: 1024,...)");
    return sizes;
}

}  // namespace

int runRebuildCommand(const RebuildFlags& flags) {
    checkFrames(flags.run);
    RebuildOptions options;
    parseSizeFlag(flags.run.size.value_or("512x512"), options.width, options.height);
    options.frames = flags.run.frames;
    checkOutputFolder(flags.run.outDir);
    options.mapSizes = parseRebuildSizes(flags.mapSizes, flags.mapSizesFlag);
    const auto context = createHeadlessContext(parseBackend(flags.run.backend));
    const std::filesystem::path folder = flags.run.outDir;
    std::vector<RebuildRow> rows;
    runRebuild(*context, options, [&](const RebuildRow& r) {
        rows.push_back(r);
        writeRebuildCsv(folder / "rebuild.csv", context->renderer(), rows);
        std::printf(
            "%5d: full rebuild %9.2f ms, 64x64 dab %7.3f ms, frame %8.2f ms (rebuild / frame "
            "%.2f, dab / frame %.3f), CPU build + upload %8.1f ms, %.2f GPU bytes per texel "
            "(%.2f with maxmip)\n",
            r.mapSize, r.fullRebuildMs, r.brushUpdateMs, r.frameTraceMs,
            r.fullRebuildMs / r.frameTraceMs, r.brushUpdateMs / r.frameTraceMs, r.cpuBuildMs,
            r.bytesPerTexel, r.bytesPerTexelWithMaxMip);
        std::fflush(stdout);
    });
    const std::string table = rebuildTable(context->renderer(), today(), rows);
    writeTextAtomically(folder / "rebuild.md", table);
    std::cout << '\n'
              << table << "microrelief-bench: wrote " << (folder / "rebuild.csv").string()
              << " and rebuild.md\n";
    return 0;
}

}  // namespace microrelief::bench
