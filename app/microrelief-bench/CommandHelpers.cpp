#include "CommandHelpers.h"

#include <unistd.h>

#include <ctime>

#include "microrelief/io/AtomicFile.h"
#include "microrelief/io/ReliefFiles.h"

namespace microrelief::bench {

void addRunOptions(CLI::App& app, RunFlags& flags, const std::string& quickHelp,
                   const std::string& sizeHelp, const std::string& outDirHelp) {
    if (!quickHelp.empty()) app.add_flag("--quick", flags.quick, quickHelp);
    app.add_option_function<std::string>(
        "--size", [&flags](const std::string& text) { flags.size = text; }, sizeHelp);
    app.add_option("--frames", flags.frames,
                   "Timed frames per measurement, after warm-up (at least 10); methods: rounds, "
                   "each a frame of every setting of a map and view in turn")
        ->capture_default_str();
    app.add_option("--backend", flags.backend, "auto, egl or osmesa")->capture_default_str();
    app.add_option("--out-dir", flags.outDir, outDirHelp)->capture_default_str();
}

void checkFrames(const RunFlags& flags) {
    if (flags.frames < 10) throwBadInput("--frames must be at least 10");
}

std::string today() {
    const std::time_t now = std::time(nullptr);
    char buffer[32];
    std::strftime(buffer, sizeof buffer, "%Y-%m-%d", std::gmtime(&now));
    return buffer;
}

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

namespace {

// A whole number within [lo, hi], or one clear error naming the flag.
auto wholeIn(const char* flag, int lo, int hi) {
    return [flag, lo, hi](const std::string& text) {
        const bool digits = !text.empty() && text.size() <= 5 &&
                            text.find_first_not_of("0123456789") == std::string::npos;
        const int value = digits ? std::stoi(text) : -1;
        if (value < lo || value > hi)
            throwBadInput(std::string(flag) + ": '" + text + "' is not a whole number from " +
                          std::to_string(lo) + " to " + std::to_string(hi));
        return value;
    };
}

std::string number(int n) {
    return std::to_string(n);
}

}  // namespace

std::vector<int> parseViews(const std::string& list) {
    const std::vector<int> views = parseList(list, "--views", "--views", wholeIn("--views", 0, 89));
    if (views.empty()) throwBadInput("--views names no view");
    refuseRepeats(views, "--views", number);
    return views;
}

std::vector<int> parseMapSizes(const std::string& list) {
    std::vector<int> sizes;
    for (int n : parseList(list, "--map-sizes", "--map-sizes", wholeIn("--map-sizes", 0, 65536)))
        if (n > 0) sizes.push_back(n);
    refuseRepeats(sizes, "--map-sizes", number);
    return sizes;
}

std::vector<int> parseCoarseTiles(const std::string& list) {
    if (list == "0") return {};
    const std::vector<int> tiles =
        parseList(list, "--coarse-tiles", "--coarse-tiles", wholeIn("--coarse-tiles", 2, 64));
    if (tiles.empty()) throwBadInput("--coarse-tiles names no tile (0 for none)");
    refuseRepeats(tiles, "--coarse-tiles", number);
    return tiles;
}

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

void checkMapsAreNotOutputs(const std::filesystem::path& folder,
                            const std::vector<MapEntry>& maps) {
    std::vector<NamedFile> read;
    for (const MapEntry& map : maps)
        read.push_back({heightMapPath(map.source), "the map"});
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

}  // namespace microrelief::bench
