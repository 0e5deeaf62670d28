// microrelief-bench: the multilevel method and its peers side by side, on one relief
// at several resolutions and on the bundled assets, from several view angles. Writes
// bench.csv, bench.md and plots into --out-dir; prints progress as it goes.
#include <CLI/CLI.hpp>

#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <iostream>
#include <map>

#include "Benchmark.h"
#include "CommandLine.h"
#include "Materials.h"
#include "Rebuild.h"
#include "Report.h"
#include "SceneOptions.h"
#include "Terrain.h"
#include "microrelief/Version.h"
#include "microrelief/core/DataPaths.h"
#include "microrelief/core/Error.h"
#include "microrelief/core/Log.h"
#include "microrelief/core/base/BaseType.h"
#include "microrelief/headless/HeadlessContext.h"
#include "microrelief/io/AtomicFile.h"
#include "microrelief/io/HeightMapFile.h"

using namespace microrelief;
using namespace microrelief::bench;

namespace {

std::string today() {
    const std::time_t now = std::time(nullptr);
    char buffer[32];
    std::strftime(buffer, sizeof buffer, "%Y-%m-%d", std::gmtime(&now));
    return buffer;
}

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
        const MapSource& source = entry.source;
        try {
            files.emplace_back(
                mapName(source),
                std::make_shared<const HeightMap>(loadHeightMap(
                    source.file ? *source.file : defaultHeightMapPath(), source.load)));
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

// Before any work: --out-dir is a folder we may write in, or the nearest part of it that
// exists is one, so that it can be made. Throws Error(BadInput).
void checkOutputFolder(const std::filesystem::path& folder) {
    std::error_code ec;
    std::filesystem::path existing = folder;
    while (!existing.empty() && !std::filesystem::exists(existing, ec))
        existing = existing.parent_path();
    if (existing.empty()) existing = ".";
    const std::string where = existing == folder ? "" : " (" + existing.string() + ")";
    if (!std::filesystem::is_directory(existing, ec))
        throwBadInput("--out-dir " + folder.string() + where + " is not a folder");
    if (::access(existing.c_str(), W_OK | X_OK) != 0)
        throwBadInput("--out-dir " + folder.string() + where + ": cannot write there");
}

// Before any work: no map measured is a file the run writes into --out-dir (a plot over
// the map it plots). Only files there now can be maps: the reports and plots by name, and
// the Pareto plots, named after the maps, as they are.
void checkMapsAreNotOutputs(const std::filesystem::path& folder,
                            const std::vector<MapEntry>& maps) {
    std::vector<NamedFile> read;
    for (const MapEntry& map : maps)
        if (map.source.file) read.push_back({*map.source.file, "the map"});
    std::vector<NamedFile> written;
    for (const char* name :
         {"bench.csv", "bench.md", "plots.gnuplot", "plot_data.txt", "time_vs_size.png",
          "fetches_vs_size.png", "rebuild.csv", "rebuild.md", "materials.csv", "materials.md",
          "terrain.csv", "terrain.md", "terrain.png"})
        written.push_back({folder / name, "--out-dir"});
    std::error_code ec;
    for (auto it = std::filesystem::directory_iterator(folder, ec);
         !ec && it != std::filesystem::directory_iterator(); it.increment(ec)) {
        if (it->path().filename().string().rfind("pareto-", 0) == 0)
            written.push_back({it->path(), "--out-dir"});
    }
    checkOutputsAreNotInputs(written, read);
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
            n +=
                settingsFor(method, std::max(m.map->width, m.map->height), options.maxSteps).size();
        }
    }
    return n * options.viewDegrees.size();
}

// A list that names an item twice would measure it twice and merge the rows: refused.
template <typename T, typename Name>
void refuseRepeats(const std::vector<T>& items, const std::string& flag, Name name) {
    for (std::size_t k = 0; k < items.size(); ++k)
        for (std::size_t l = 0; l < k; ++l)
            if (name(items[l]) == name(items[k]))
                throwBadInput(flag + " names " + name(items[k]) + " twice");
}

// The items of a comma-separated list, empty ones kept: "30,", ",30" and "30,,45" each name
// an empty item, which the item's parser refuses (std::getline would drop a trailing one).
// An empty list has no items.
std::vector<std::string> splitCommas(const std::string& list) {
    std::vector<std::string> items;
    if (list.empty()) return items;
    for (std::size_t start = 0;;) {
        const std::size_t comma = list.find(',', start);
        items.push_back(list.substr(start, comma - start));
        if (comma == std::string::npos) return items;
        start = comma + 1;
    }
}

// A comma-separated list flag, each item read by the parser of the single flag; its
// errors name the list flag the user gave (the parsers name the single one).
template <typename Parse>
auto parseList(const std::string& list, const std::string& single, const std::string& flag,
               Parse parse) {
    std::vector<decltype(parse(std::string()))> items;
    for (const std::string& name : splitCommas(list)) {
        try {
            items.push_back(parse(name));
        } catch (const Error& e) {
            std::string message = e.message(flagName);
            if (const auto at = message.find(single); at != std::string::npos)
                message.replace(at, single.size(), flag);
            throw Error(e.kind(), message);
        }
    }
    return items;
}

// --terrain: its own defaults where the flags were not given (with --quick, maps 1024 and
// 4096: every path in seconds), then the run and its files.
int runTerrain(const CLI::App& app, const BenchOptions& options, bool quick, std::size_t memoryMib,
               const std::string& backend, const std::string& outDir) {
    TerrainOptions terrain;
    if (app.count("--map-sizes"))
        terrain.mapSizes = options.mapSizes;
    else if (quick)
        terrain.mapSizes = {1024, 4096};
    if (app.count("--views")) terrain.viewDegrees = options.viewDegrees;
    if (app.count("--size")) {
        terrain.width = options.width;
        terrain.height = options.height;
    }
    terrain.frames = options.frames;
    terrain.memoryBytes = memoryMib << 20;
    // Maps made in memory (whole and paged paths, the reference) while their samples,
    // pyramid and reference take at most 60 % of the machine's memory (about 20 bytes a
    // sample: the paged path's 16, kPagedBytesPerSample, and the reference's own pyramid);
    // larger ones from pyramid files alone.
    terrain.inMemorySamples = physicalMemoryBytes() * 6 / 10 / 20;
    terrain.pyramidFolder = std::filesystem::path(outDir) / "terrain-pyramids";
    if (terrain.mapSizes.empty()) throwBadInput("--map-sizes names no size");
    const auto context = createHeadlessContext(parseBackend(backend));
    const std::filesystem::path folder = outDir;
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

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Measures the multilevel method against its peers: time, texel fetches, accuracy.",
                 "microrelief-bench"};
    bool quick = false, materials = false;
    std::string size = "512x512", backend = "auto", outDir = "out/bench";
    std::string methodList = "multilevel,maxmip,cone,rcsm,normal,offset,steep,pom,relief";
    std::string baseList = "plane,cylinder,sphere";
    std::string interpolationList = "bilinear,biquadratic";
    BenchOptions options;
    bool rebuild = false;
    std::string rebuildSizes = "1024,2048,4096,8192";
    app.add_flag("--rebuild", rebuild,
                 "Instead: what a changing map costs, the pyramids rebuilt on the GPU in full and "
                 "after a 64x64 brush dab, beside a frame's trace of the same map (rebuild.csv)");
    app.add_option("--rebuild-sizes", rebuildSizes, "Map sizes for --rebuild, comma-separated")
        ->capture_default_str();
    bool terrain = false;
    std::size_t memoryMib = 512;
    // The help's defaults are TerrainOptions' own.
    const TerrainOptions terrainDefaults;
    const auto commas = [](const std::vector<int>& values) {
        std::string text;
        for (const int v : values) text += (text.empty() ? "" : ",") + std::to_string(v);
        return text;
    };
    app.add_flag("--terrain", terrain,
                 "Instead: the multilevel method against map size to terrain scale, in whole "
                 "textures, through pages and from pyramid files (past the GL's texture limit "
                 "and past memory too): preparation, first picture, frame, fetches, memory, "
                 "accuracy (terrain.csv, terrain.md, terrain.png). Its defaults: --map-sizes " +
                     commas(terrainDefaults.mapSizes) + ", --views " +
                     commas(terrainDefaults.viewDegrees) + ", --size " +
                     std::to_string(terrainDefaults.width) + "x" +
                     std::to_string(terrainDefaults.height));
    app.add_option("--memory", memoryMib, "The page pool's budget for --terrain, MiB")
        ->capture_default_str()
        ->check(wholeNumberIn(1, std::size_t{1} << 20));
    app.add_flag("--quick", quick,
                 "The procedural relief at 256 and 4096 (other maps only where --maps names "
                 "them), views 45 and 80 degrees, 256x256, step budgets up to 1024 (minutes on a "
                 "CPU); with --terrain, maps 1024 and 4096");
    app.add_flag("--materials", materials,
                 "Only what materials cost: shadows (hard, soft) against none, and the map tiled "
                 "1x1, 2x2, 16x16 and 256x256 (materials.csv, materials.md)");
    app.add_option("--size", size,
                   "Picture size WIDTHxHEIGHT (default 512x512; 256x256 with --quick)");
    app.add_option("--frames", options.frames,
                   "Timed frames per measurement, after two warm-up frames (at least 10)")
        ->capture_default_str();
    app.add_option("--methods", methodList, "Comma-separated methods")->capture_default_str();
    app.add_option("--bases", baseList,
                   "Comma-separated base surfaces, each at microrelief-render's default size "
                   "(curved bases take multilevel, maxmip, pom and relief)")
        ->capture_default_str();
    app.add_flag("--glsl330", options.glsl330,
                 "The shaders as GLSL 3.30, whatever the context gives (four texel reads a "
                 "bilinear cell where 4.00 gathers them): the path of an engine in a GL 3.3 "
                 "context, to set beside a run without it");
    app.add_option("--interpolations", interpolationList,
                   "Comma-separated last levels, bilinear and biquadratic (biquadratic with the "
                   "exact methods, multilevel, maxmip and cone)")
        ->capture_default_str();
    std::string mapList, viewList, sizeList;
    app.add_option("--maps", mapList,
                   "Comma-separated height maps, FILE[:CHANNEL][:normalize] (any image the "
                   "programs read; 'default' the bundled map; 'fetched' the real maps "
                   "scripts/bench-maps.sh fetched), instead of the default: the bundled map and "
                   "the fetched ones where there are any (out/bench-maps/maps.txt, or "
                   "$MICRORELIEF_BENCH_MAPS/maps.txt, whose lines take the same suffixes). "
                   ":CHANNEL picks the image channel (as microrelief-render's --channel, default "
                   "0), :normalize maps [min, max] to [0, 1] (its --normalize). They are read "
                   "from the right, ':normalize' last, and count only where they are exactly "
                   "'normalize' and a whole number; the rest is the file name, colons and all "
                   "('a:b.png' is a file; name a file 'x:1' as 'x:1:0'). The report calls a map "
                   "by its file's stem and these suffixes (rock:1)");
    app.add_option("--views", viewList,
                   "Comma-separated view angles in degrees from the surface normal, 0 to 89 "
                   "(default 0,45,70,85; 45,80 with --quick)");
    app.add_option("--map-sizes", sizeList,
                   "Comma-separated sides of the procedural relief (default 64,256,1024,4096,8192; "
                   "256,4096 with --quick; 0 for none)");
    app.add_option("--backend", backend, "auto, egl or osmesa")->capture_default_str();
    app.set_version_flag("--version",
                         std::string("microrelief-bench ") + MICRORELIEF_VERSION_STRING);
    app.add_option("--out-dir", outDir, "Folder for bench.csv, bench.md and the plots")
        ->capture_default_str();
    if (const auto status = parseArgumentsOrExit(app, argc, argv, "microrelief-bench"))
        return *status;
    setLogSink([](LogLevel level, const std::string& message) {
        if (level == LogLevel::Warning)
            std::cerr << "microrelief-bench: warning: " << message << '\n';
    });
    std::string noFetchedMaps;  // a "Not measured" line where the default measures none
    try {
        if (options.frames < 10) throwBadInput("--frames must be at least 10");
        if (quick) {
            options.mapSizes = {256, 4096};
            options.viewDegrees = {45, 80};
            options.maxSteps = 1024;
            if (!app.count("--size")) size = "256x256";
        } else {
            options.mapSizes = {64, 256, 1024, 4096, 8192};
            // The default map list, unless --maps replaces it or the run measures no map
            // file (--rebuild, --materials, --terrain): a bad line of the fetched maps' list
            // is no matter then.
            if (!app.count("--maps") && !rebuild && !materials && !terrain) {
                options.assets = {{MapSource(), "the bundled map"}};
                const std::vector<MapEntry> fetched = fetchedMaps(false);
                options.assets.insert(options.assets.end(), fetched.begin(), fetched.end());
                if (fetched.empty()) noFetchedMaps = noFetchedMapsNote();
            }
            options.viewDegrees = {0, 45, 70, 85};
        }
        // A whole number within [lo, hi], or one clear error naming the flag.
        const auto wholeIn = [](const char* flag, int lo, int hi) {
            return [flag, lo, hi](const std::string& text) {
                const bool digits = !text.empty() && text.size() <= 5 &&
                                    text.find_first_not_of("0123456789") == std::string::npos;
                const int value = digits ? std::stoi(text) : -1;
                if (value < lo || value > hi)
                    throwBadInput(std::string(flag) + ": '" + text +
                                  "' is not a whole number from " + std::to_string(lo) + " to " +
                                  std::to_string(hi));
                return value;
            };
        };
        if (app.count("--maps")) {
            for (const std::string& text : splitCommas(mapList)) {
                if (text != "fetched") {
                    options.assets.push_back(givenMap(text));
                    continue;
                }
                for (const MapEntry& fetched : fetchedMaps(true)) options.assets.push_back(fetched);
            }
        }
        if (app.count("--views"))
            options.viewDegrees =
                parseList(viewList, "--views", "--views", wholeIn("--views", 0, 89));
        if (app.count("--map-sizes")) {
            options.mapSizes.clear();
            for (int n : parseList(sizeList, "--map-sizes", "--map-sizes",
                                   wholeIn("--map-sizes", 0, 65536)))
                if (n > 0) options.mapSizes.push_back(n);
        }
        if (options.viewDegrees.empty()) throwBadInput("--views names no view");
        const auto number = [](int n) { return std::to_string(n); };
        refuseRepeats(options.viewDegrees, "--views", number);
        refuseRepeats(options.mapSizes, "--map-sizes", number);
        parseSizeFlag(size, options.width, options.height);
        options.methods = parseList(methodList, "--method", "--methods", parseMethod);
        options.bases = parseList(baseList, "--base", "--bases",
                                  [](const std::string& name) { return baseType(name).defaults; });
        options.interpolations =
            parseList(interpolationList, "--interpolation", "--interpolations", parseInterpolation);
        if (options.bases.empty())
            throwBadInput("--bases names no base (a comma-separated list: plane,cylinder,...)");
        if (options.interpolations.empty())
            throwBadInput("--interpolations names no interpolation (bilinear,biquadratic)");
        if (options.methods.empty())
            throwBadInput(
                "--methods names no method (a comma-separated list: multilevel,maxmip,...)");
        refuseRepeats(options.methods, "--methods",
                      [](Method m) { return std::string(methodName(m)); });
        refuseRepeats(options.bases, "--bases",
                      [](const BaseShape& b) { return std::string(baseName(b)); });
        refuseRepeats(options.interpolations, "--interpolations",
                      [](Interpolation i) { return std::string(interpolationName(i)); });
        checkOutputFolder(outDir);
        checkMapsAreNotOutputs(outDir, options.assets);
        if (int(rebuild) + int(materials) + int(terrain) > 1)
            throwBadInput("--rebuild, --materials and --terrain: one at a time");
        if (options.glsl330 && (rebuild || materials || terrain))
            throwBadInput(
                "--glsl330 is for the methods' comparison, not --rebuild, --materials "
                "or --terrain");
        if (terrain) return runTerrain(app, options, quick, memoryMib, backend, outDir);
        if (app.count("--memory"))
            throwBadInput("--memory is the page budget of --terrain; the other runs page nothing");
        if (rebuild) {
            RebuildOptions rebuildOptions;
            rebuildOptions.width = options.width;
            rebuildOptions.height = options.height;
            rebuildOptions.frames = options.frames;
            rebuildOptions.mapSizes =
                parseList(rebuildSizes, "--size", "--rebuild-sizes", [](const std::string& text) {
                    // A side in texels: digits only, 1 to 65536 (the maps are square).
                    const bool digits = !text.empty() && text.size() <= 5 &&
                                        text.find_first_not_of("0123456789") == std::string::npos;
                    const int side = digits ? std::stoi(text) : 0;
                    if (side < 1 || side > 65536)
                        throwBadInput("--rebuild-sizes: '" + text +
                                      "' is not a map side (a whole number of texels, 1 to 65536)");
                    return side;
                });
            if (rebuildOptions.mapSizes.empty())
                throwBadInput("--rebuild-sizes names no size (a comma-separated list: 1024,...)");
            const auto context = createHeadlessContext(parseBackend(backend));
            const std::filesystem::path folder = outDir;
            std::vector<RebuildRow> rows;
            runRebuild(*context, rebuildOptions, [&](const RebuildRow& r) {
                rows.push_back(r);
                writeRebuildCsv(folder / "rebuild.csv", context->renderer(), rows);
                std::printf(
                    "%5d: full rebuild %9.2f ms, 64x64 dab %7.3f ms, frame %8.2f ms (rebuild / "
                    "frame %.2f, dab / frame %.3f), CPU build + upload %8.1f ms, %.2f GPU bytes "
                    "per texel (%.2f with maxmip)\n",
                    r.mapSize, r.fullRebuildMs, r.brushUpdateMs, r.frameTraceMs,
                    r.fullRebuildMs / r.frameTraceMs, r.brushUpdateMs / r.frameTraceMs,
                    r.cpuBuildMs, r.bytesPerTexel, r.bytesPerTexelWithMaxMip);
                std::fflush(stdout);
            });
            const std::string table = rebuildTable(context->renderer(), today(), rows);
            writeTextAtomically(folder / "rebuild.md", table);
            std::cout << '\n'
                      << table << "microrelief-bench: wrote " << (folder / "rebuild.csv").string()
                      << " and rebuild.md\n";
            return 0;
        }

        const auto context = createHeadlessContext(parseBackend(backend));
        if (materials) {
            const std::vector<MaterialRow> rows = runMaterialsBenchmark(
                *context, options.width, options.height, options.frames, quick);
            std::cout << '\n' << writeMaterials(outDir, context->renderer(), rows);
            std::cout << "microrelief-bench: wrote "
                      << (std::filesystem::path(outDir) / "materials.csv").string()
                      << " and materials.md\n";
            return 0;
        }
        RunInfo info{context->renderer(),
                     today(),
                     "microrelief-bench" + std::string(quick ? " --quick" : "") +
                         (options.glsl330 ? " --glsl330" : ""),
                     {}};
        if (options.assets.empty() && options.mapSizes.empty())
            throwBadInput(
                "nothing to measure: no map (--maps names none, and --map-sizes 0 "
                "leaves out the procedural relief)");
        const std::vector<BenchMap> maps = loadMaps(options);
        const std::size_t total = countMeasurements(options, maps);
        if (total == 0)
            throwBadInput(
                "nothing to measure: none of --methods runs on the maps, bases and "
                "last levels asked for");
        info.notes = unmeasuredNotes(options, maps);
        if (!noFetchedMaps.empty()) info.notes.insert(info.notes.begin(), noFetchedMaps);
        for (const std::string& line : info.notes)
            std::cerr << "microrelief-bench: not measured: " << line << '\n';
        const std::filesystem::path folder = outDir;
        std::vector<Measurement> rows;
        const auto start = std::chrono::steady_clock::now();
        runBenchmark(*context, options, maps, [&](const Measurement& r) {
            rows.push_back(r);
            writeCsv(folder / "bench.csv", info, rows);
            const double elapsed =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            std::printf(
                "[%3zu/%zu %5.0f s] %-10s %-5s %s %d %2d deg: %8.3f ms timer, %8.3f ms wall, "
                "%7.1f fetches, %.3f %% / %.3f %%\n",
                rows.size(), total, elapsed, r.method.c_str(), r.param.c_str(), r.map.c_str(),
                r.mapSize, r.viewDegrees, r.msMedian, r.msWallMedian, r.fetchesMean,
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
    } catch (const Error& e) {
        std::cerr << "microrelief-bench: error: " << e.what() << '\n';
        return exitStatusOf(e.kind());
    }
}
