// microrelief-bench methods, the default run: the multilevel method and its peers side by
// side, on the procedural relief at several resolutions and on the bundled and fetched
// maps, from several view angles: time, texel fetches, accuracy (bench.csv, bench.md and
// plots in --out-dir; progress on the console as it goes).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>

#include "Benchmark.h"
#include "CommandHelpers.h"
#include "Commands.h"
#include "Report.h"
#include "SceneOptions.h"
#include "microrelief/core/Error.h"
#include "microrelief/core/base/BaseType.h"
#include "microrelief/headless/HeadlessContext.h"
#include "microrelief/io/ReliefFiles.h"

namespace microrelief::bench {

namespace {

// Where the benchmark looks for the real maps scripts/bench-maps.sh fetched:
// $MICRORELIEF_BENCH_MAPS, or out/bench-maps in the working folder (the script writes to the
// checkout's out/bench-maps, so a run from elsewhere names the folder with the variable).
std::filesystem::path fetchedMapsFolder() {
    const char* env = std::getenv("MICRORELIEF_BENCH_MAPS");
    return env && *env ? env : "out/bench-maps";
}

// The maps that FOLDER/maps.txt lists (one a line, FILE[:CHANNEL][:normalize] as --maps
// takes them, the file relative to FOLDER). None where there is no list, unless `required`
// (--maps fetched): then one error line naming the list.
std::vector<MapEntry> fetchedMaps(bool required) {
    const std::filesystem::path folder = fetchedMapsFolder();
    const std::filesystem::path list = folder / "maps.txt";
    std::ifstream in(list);
    if (!in) {
        if (required)
            throwBadInput("--maps fetched: " + list.string() +
                          ": no list of fetched maps (run scripts/bench-maps.sh)");
        return {};
    }
    std::vector<MapEntry> maps;
    int lineNumber = 0;
    for (std::string line; std::getline(in, line);) {
        ++lineNumber;
        if (line.empty()) continue;
        MapEntry entry{{},
                       std::string(required ? "--maps fetched: " : "") + list.string() + ":" +
                           std::to_string(lineNumber) + ": '" + line + "'"};
        try {
            entry.source = parseMapEntry(line);
        } catch (const Error& e) {
            throw e.after(entry.given + ": ");
        }
        entry.source.file = folder / *entry.source.file;
        maps.push_back(entry);
    }
    return maps;
}

// The "not measured" line of a default run that found no fetched map to measure: the list
// is missing (its folder relative to where the benchmark runs, unless the variable names
// it) or lists none.
std::string noFetchedMapsNote() {
    const std::filesystem::path list = fetchedMapsFolder() / "maps.txt";
    const std::string what = "the real maps scripts/bench-maps.sh fetches: ";
    if (std::ifstream(list)) return what + list.string() + " lists none";
    const char* env = std::getenv("MICRORELIEF_BENCH_MAPS");
    return what + "no list at " + list.string() +
           (env && *env ? ""
                        : " (relative to the working folder; MICRORELIEF_BENCH_MAPS names "
                          "another)");
}

// A --maps entry (MapEntry.h); 'default' the bundled map. 'fetched', the list, is the
// caller's: here it is refused with suffixes.
MapEntry givenMap(const std::string& text) {
    MapEntry entry{{}, "--maps '" + text + "'"};
    try {
        entry.source = parseMapEntry(text);
    } catch (const Error& e) {
        throw e.after(entry.given + ": ");
    }
    if (*entry.source.file == "fetched")
        throwBadInput(entry.given +
                      ": 'fetched' names a list of maps and takes no :CHANNEL or :normalize "
                      "(the list's lines may carry them)");
    if (*entry.source.file == "default") entry.source.file.reset();
    return entry;
}

// The loader's messages name the scene's fields; a map entry's are its suffixes.
std::string entryFieldName(const std::string& field) {
    if (field == "map.load.channel") return "channel";
    if (field == "map.load.normalize") return "':normalize'";
    return flagName(field);
}

// Two entries the report would name alike (a/rock.png and b/rock.png; a file relief.png and
// the procedural relief, where that is measured) would have their rows merged: refused,
// naming both.
void checkMapNamesDiffer(const std::vector<MapEntry>& entries, bool reliefMeasured) {
    std::map<std::string, std::string> givenBy;
    if (reliefMeasured) givenBy.emplace(kResampledRelief, "the procedural relief");
    for (const MapEntry& entry : entries) {
        const std::string name = mapName(entry.source);
        const auto [it, added] = givenBy.emplace(name, entry.given);
        if (!added)
            throwBadInput(entry.given + ": the report would name it '" + name + "', as it names " +
                          it->second + " (copy or link one of the files under another name)");
    }
}

std::vector<BenchMap> loadMaps(const BenchOptions& options) {
    checkMapNamesDiffer(options.assets, !options.mapSizes.empty());
    std::vector<BenchMap> maps;
    // The files first: a bad one is refused before minutes of making reliefs.
    std::vector<std::pair<std::string, std::shared_ptr<const HeightMap>>> files;
    for (const MapEntry& entry : options.assets) {
        ReliefDesc relief;
        relief.map = entry.source;
        try {
            files.emplace_back(mapName(entry.source),
                               loadReliefFiles(relief, ReliefParts::Heights).heights);
        } catch (const Error& e) {
            throw Error(e.kind(), entry.given + ": " + e.message(entryFieldName));
        }
    }
    // Each map on each base, the bases of one map together (a map is made once).
    for (int n : options.mapSizes) {
        std::cout << "microrelief-bench: making the " << n << "x" << n << " relief\n" << std::flush;
        const auto relief = std::make_shared<const HeightMap>(benchRelief(n));
        for (const BaseShape& base : options.bases)
            for (Interpolation interpolation : options.interpolations)
                maps.push_back({mapOnBase(kResampledRelief, base, interpolation), relief, 0.1, base,
                                interpolation});
    }
    for (const auto& [name, map] : files) {
        for (const BaseShape& base : options.bases)
            for (Interpolation interpolation : options.interpolations)
                maps.push_back(
                    {mapOnBase(name, base, interpolation), map, 0.1, base, interpolation});
    }
    return maps;
}

// What was asked for and is not measured, a line each (bench.md and the console say so,
// rather than leave its rows out unremarked).
std::vector<std::string> unmeasuredNotes(const BenchOptions& options,
                                         const std::vector<BenchMap>& maps) {
    std::vector<std::string> notes;
    for (const BenchMap& m : maps) {
        for (Method method : options.methods) {
            const std::string why = whyNotMeasured(method, m);
            if (why.empty()) continue;
            const std::string line = std::string(methodName(method)) + ": " + why;
            if (std::find(notes.begin(), notes.end(), line) == notes.end()) notes.push_back(line);
        }
    }
    return notes;
}

std::size_t countMeasurements(const BenchOptions& options, const std::vector<BenchMap>& maps) {
    std::size_t n = 0;
    for (const BenchMap& m : maps) {
        for (Method method : options.methods) {
            if (!whyNotMeasured(method, m).empty()) continue;
            n += settingsFor(method, std::max(m.map->width, m.map->height), options.maxSteps,
                             coarseTilesFor(options, m))
                     .size();
        }
    }
    return n * options.viewDegrees.size();
}

}  // namespace

void addMethodsOptions(CLI::App& app, MethodsFlags& flags) {
    addRunOptions(app, flags.run,
                  "The procedural relief at 256 and 4096 (other maps only where --maps names "
                  "them), views 45 and 80 degrees, 256x256, step budgets up to 1024 (minutes on "
                  "a CPU)",
                  "Picture size WIDTHxHEIGHT (default 512x512; 256x256 with --quick)",
                  "Folder for bench.csv, bench.md and the plots");
    app.add_option("--methods", flags.methods, "Comma-separated methods")->capture_default_str();
    app.add_option("--bases", flags.bases,
                   "Comma-separated base surfaces, each at microrelief-render's default size "
                   "(curved bases take multilevel, maxmip, pom and relief)")
        ->capture_default_str();
    app.add_option("--clock", flags.clock,
                   "What the tables' times and ratios read: timer (the GL timer query), wall "
                   "(the wall time to glFinish), cpu (the process's CPU time to glFinish, every "
                   "thread), or auto: the timer on a GPU, cpu on a CPU rasteriser (llvmpipe), "
                   "whose timer query misses its work. The CSV has all three medians")
        ->capture_default_str();
    app.add_flag("--glsl330", flags.glsl330,
                 "The shaders as GLSL 3.30, whatever the context gives (four texel reads a "
                 "bilinear cell where 4.00 gathers them): the path of an engine in a GL 3.3 "
                 "context, to set beside a run without it");
    app.add_option("--coarse-tiles", flags.coarseTiles,
                   "The coarse pass (a pass over T x T tiles of pixels that starts each pixel's "
                   "walk where its tile's rays may first meet the relief) measured as rows of "
                   "its own, 'exact+coarseT', beside the multilevel method's exact frame on the "
                   "plane: comma-separated tile sides from 2 to 64, or 0 for none")
        ->capture_default_str();
    app.add_option("--interpolations", flags.interpolations,
                   "Comma-separated last levels, bilinear and biquadratic (biquadratic with the "
                   "exact methods, multilevel, maxmip and cone)")
        ->capture_default_str();
    const auto given = [](std::optional<std::string>& flag) {
        return [&flag](const std::string& text) { flag = text; };
    };
    app.add_option_function<std::string>(
        "--maps", given(flags.maps),
        "Comma-separated height maps, FILE[:CHANNEL][:normalize] (any image the programs read; "
        "'default' the bundled map; 'fetched' the real maps scripts/bench-maps.sh fetched), "
        "instead of the default: the bundled map and the fetched ones where there are any "
        "(out/bench-maps/maps.txt, or $MICRORELIEF_BENCH_MAPS/maps.txt, whose lines take the "
        "same suffixes). :CHANNEL picks the image channel (as microrelief-render's --channel, "
        "default 0), :normalize maps [min, max] to [0, 1] (its --normalize). They are read from "
        "the right, ':normalize' last, and count only where they are exactly 'normalize' and a "
        "whole number; the rest is the file name, colons and all ('a:b.png' is a file; name a "
        "file 'x:1' as 'x:1:0'). The report calls a map by its file's stem and these suffixes "
        "(rock:1)");
    app.add_option_function<std::string>(
        "--views", given(flags.views),
        "Comma-separated view angles in degrees from the surface normal, 0 to 89 (default "
        "0,45,70,85; 45,80 with --quick)");
    app.add_option_function<std::string>(
        "--map-sizes", given(flags.mapSizes),
        "Comma-separated sides of the procedural relief (default 64,256,1024,4096,8192; "
        "256,4096 with --quick; 0 for none)");
}

MethodsRun checkMethods(const MethodsFlags& flags, bool readsFetchedMaps) {
    MethodsRun run;
    BenchOptions& options = run.options;
    run.quick = flags.run.quick;
    run.backend = flags.run.backend;
    run.outDir = flags.run.outDir;
    parseClock(flags.clock);  // refused before any work
    run.clock = flags.clock;
    checkFrames(flags.run);
    options.frames = flags.run.frames;
    options.glsl330 = flags.glsl330;
    std::string size = flags.run.size.value_or("512x512");
    if (run.quick) {
        options.mapSizes = {256, 4096};
        options.viewDegrees = {45, 80};
        options.maxSteps = 1024;
        if (!flags.run.size) size = "256x256";
    } else {
        options.mapSizes = {64, 256, 1024, 4096, 8192};
        // The default map list, unless --maps replaces it or the run measures no map file
        // (the old spelling of the other runs): a bad line of the fetched maps' list is no
        // matter then.
        if (!flags.maps && readsFetchedMaps) {
            options.assets = {{MapSource(), "the bundled map"}};
            const std::vector<MapEntry> fetched = fetchedMaps(false);
            options.assets.insert(options.assets.end(), fetched.begin(), fetched.end());
            if (fetched.empty()) run.noFetchedMaps = noFetchedMapsNote();
        }
        options.viewDegrees = {0, 45, 70, 85};
    }
    if (flags.maps) {
        for (const std::string& text : splitCommas(*flags.maps)) {
            if (text != "fetched") {
                options.assets.push_back(givenMap(text));
                continue;
            }
            for (const MapEntry& fetched : fetchedMaps(true)) options.assets.push_back(fetched);
        }
    }
    if (flags.views) options.viewDegrees = parseViews(*flags.views);
    if (flags.mapSizes) options.mapSizes = parseMapSizes(*flags.mapSizes);
    options.coarseTiles = parseCoarseTiles(flags.coarseTiles);
    parseSizeFlag(size, options.width, options.height);
    options.methods = parseList(flags.methods, "--method", "--methods", parseMethod);
    options.bases = parseList(flags.bases, "--base", "--bases",
                              [](const std::string& name) { return baseType(name).defaults; });
    options.interpolations =
        parseList(flags.interpolations, "--interpolation", "--interpolations", parseInterpolation);
    if (options.bases.empty())
        throwBadInput("--bases names no base (a comma-separated list: plane,cylinder,...)");
    if (options.interpolations.empty())
        throwBadInput("--interpolations names no interpolation (bilinear,biquadratic)");
    if (options.methods.empty())
        throwBadInput("--methods names no method (a comma-separated list: multilevel,maxmip,...)");
    refuseRepeats(options.methods, "--methods",
                  [](Method m) { return std::string(methodName(m)); });
    refuseRepeats(options.bases, "--bases",
                  [](const BaseShape& b) { return std::string(baseName(b)); });
    refuseRepeats(options.interpolations, "--interpolations",
                  [](Interpolation i) { return std::string(interpolationName(i)); });
    checkOutputFolder(run.outDir);
    checkMapsAreNotOutputs(run.outDir, options.assets);
    return run;
}

int runMethodsCommand(const MethodsRun& run) {
    const BenchOptions& options = run.options;
    const auto context = createHeadlessContext(parseBackend(run.backend));
    RunInfo info{context->renderer(),
                 today(),
                 "microrelief-bench" + std::string(run.quick ? " --quick" : "") +
                     (options.glsl330 ? " --glsl330" : "") +
                     (run.clock != "auto" ? " --clock " + run.clock : std::string()),
                 {},
                 parseClock(run.clock)};
    if (options.assets.empty() && options.mapSizes.empty())
        throwBadInput(
            "nothing to measure: no map (--maps names none, and --map-sizes 0 leaves out the "
            "procedural relief)");
    const std::vector<BenchMap> maps = loadMaps(options);
    const std::size_t total = countMeasurements(options, maps);
    if (total == 0)
        throwBadInput(
            "nothing to measure: none of --methods runs on the maps, bases and last levels "
            "asked for");
    info.notes = unmeasuredNotes(options, maps);
    if (!run.noFetchedMaps.empty()) info.notes.insert(info.notes.begin(), run.noFetchedMaps);
    for (const std::string& line : info.notes)
        std::cerr << "microrelief-bench: not measured: " << line << '\n';
    const std::filesystem::path folder = run.outDir;
    std::vector<Measurement> rows;
    const auto start = std::chrono::steady_clock::now();
    runBenchmark(*context, options, maps, [&](const Measurement& r) {
        rows.push_back(r);
        writeCsv(folder / "bench.csv", info, rows);
        const double elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::printf(
            "[%3zu/%zu %5.0f s] %-10s %-5s %s %d %2d deg: %8.3f ms timer, %8.3f ms wall, "
            "%8.3f ms cpu, %7.1f fetches, %.3f %% / %.3f %%\n",
            rows.size(), total, elapsed, r.method.c_str(), r.param.c_str(), r.map.c_str(),
            r.mapSize, r.viewDegrees, r.msMedian, r.msWallMedian, r.msCpuMedian, r.fetchesMean,
            r.coverageMismatchPct, r.offHalfTexelPct);
        std::fflush(stdout);
    });
    std::cout << '\n' << writeMarkdown(folder / "bench.md", info, rows);
    std::string why;
    const bool plots = writePlots(folder, info, rows, why);
    if (!plots) std::cerr << "microrelief-bench: warning: no plots: " << why << '\n';
    std::cout << "microrelief-bench: wrote " << (folder / "bench.csv").string()
              << (plots ? ", bench.md and plots in " : " and bench.md in ") << folder.string()
              << '\n';
    return 0;
}

int runMethodsCommand(const MethodsFlags& flags) {
    return runMethodsCommand(checkMethods(flags, true));
}

}  // namespace microrelief::bench
