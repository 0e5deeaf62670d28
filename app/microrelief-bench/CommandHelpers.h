// What the runs' command lines share (Commands.h): the options every run takes, the
// comma-separated lists and their errors, the checks of --out-dir made before any work,
// and the date the reports carry.
#pragma once

#include <CLI/CLI.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "Commands.h"
#include "MapEntry.h"
#include "SceneOptions.h"
#include "microrelief/core/Error.h"

namespace microrelief::bench {

// --size (help `sizeHelp`), --frames, --backend and --out-dir (help `outDirHelp`), and,
// where `quickHelp` is given, --quick; in the order --help lists them.
void addRunOptions(CLI::App& app, RunFlags& flags, const std::string& quickHelp,
                   const std::string& sizeHelp, const std::string& outDirHelp);
// --frames's floor: at least 10.
void checkFrames(const RunFlags& flags);

// Today's date, UTC, as the reports carry it (2026-12-06).
std::string today();

// The items of a comma-separated list, empty ones kept: "30,", ",30" and "30,,45" each name
// an empty item, which the item's parser refuses (std::getline would drop a trailing one).
// An empty list has no items.
std::vector<std::string> splitCommas(const std::string& list);

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

// A list that names an item twice would measure it twice and merge the rows: refused.
template <typename T, typename Name>
void refuseRepeats(const std::vector<T>& items, const std::string& flag, Name name) {
    for (std::size_t k = 0; k < items.size(); ++k)
        for (std::size_t l = 0; l < k; ++l)
            if (name(items[l]) == name(items[k]))
                throwBadInput(flag + " names " + name(items[k]) + " twice");
}

// --views: angles from 0 to 89, at least one, none twice.
std::vector<int> parseViews(const std::string& list);
// --map-sizes of the procedural relief: sides from 0 to 65536, 0 left out (none), none
// twice.
std::vector<int> parseMapSizes(const std::string& list);
// --coarse-tiles: tile sides from 2 to 64 (ReliefRenderer::setCoarsePass), or 0 alone: none.
std::vector<int> parseCoarseTiles(const std::string& list);

// Before any work: --out-dir is a folder we may write in, or the nearest part of it that
// exists is one, so that it can be made. Throws Error(BadInput).
void checkOutputFolder(const std::filesystem::path& folder);

// Before any work: no map measured is a file the run writes into --out-dir (a plot over
// the map it plots). Only files there now can be maps: the reports and plots by name, and
// the Pareto plots, named after the maps, as they are.
void checkMapsAreNotOutputs(const std::filesystem::path& folder, const std::vector<MapEntry>& maps);

}  // namespace microrelief::bench
