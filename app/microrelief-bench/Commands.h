// microrelief-bench's runs, a subcommand each (main.cpp dispatches):
//   methods    the multilevel method against its peers: time, fetches, accuracy (the
//              default: no subcommand runs it, with the same options)
//   materials  what shadows and tiling cost
//   rebuild    what a changing map costs
//   terrain    the multilevel method against map size to terrain scale
//   mesh       the mesh base against the plane and cylinder it copies
// Each has its options as the command line gives them (filled by CLI11: add*Options) and
// a function that checks them, runs and writes its files (run*), throwing Error(BadInput)
// for a bad value before any work. The old spelling, --materials, --rebuild and --terrain
// on the default's command line, is runOldSpelling's.
#pragma once

#include <CLI/CLI.hpp>

#include <cstddef>
#include <optional>
#include <string>

#include "Benchmark.h"

namespace microrelief::bench {

// What every run takes.
struct RunFlags {
    bool quick = false;
    std::optional<std::string> size;  // WIDTHxHEIGHT; absent: the run's default
    int frames = 10;
    std::string backend = "auto";
    std::string outDir = "out/bench";
};

struct MethodsFlags {
    RunFlags run;
    std::string methods = "multilevel,maxmip,cone,rcsm,normal,offset,steep,pom,relief";
    std::string bases = "plane,cylinder,sphere";
    std::string interpolations = "bilinear,biquadratic";
    bool glsl330 = false;
    std::string clock = "auto";                        // the tables' clock (Report.h)
    std::string coarseTiles = "8";                     // BenchOptions::coarseTiles; 0: none
    std::optional<std::string> maps, views, mapSizes;  // absent: the defaults
};
void addMethodsOptions(CLI::App& app, MethodsFlags& flags);
int runMethodsCommand(const MethodsFlags& flags);
// The same in two steps: the options checked (Error(BadInput) for a bad one, before any
// work) and turned into what is measured; then the run. Without --maps the bundled map and
// the fetched ones are measured, where `readsFetchedMaps` (the old spelling of the other
// runs measures no map file, and reads no list).
struct MethodsRun {
    BenchOptions options;
    bool quick = false;
    std::string noFetchedMaps;  // the "not measured" line where the default found none
    std::string backend, outDir;
    std::string clock = "auto";  // checked: parseClock takes it
};
MethodsRun checkMethods(const MethodsFlags& flags, bool readsFetchedMaps);
int runMethodsCommand(const MethodsRun& run);

struct MaterialsFlags {
    RunFlags run;
};
void addMaterialsOptions(CLI::App& app, MaterialsFlags& flags);
int runMaterialsCommand(const MaterialsFlags& flags);

struct RebuildFlags {
    RunFlags run;
    std::string mapSizes = "1024,2048,4096,8192";
    std::string mapSizesFlag = "--map-sizes";  // as errors name it (the old spelling's differs)
};
void addRebuildOptions(CLI::App& app, RebuildFlags& flags);
int runRebuildCommand(const RebuildFlags& flags);

struct TerrainFlags {
    RunFlags run;
    std::optional<std::string> views, mapSizes;  // absent: TerrainOptions' defaults
    std::size_t memoryMib = 512;
};
void addTerrainOptions(CLI::App& app, TerrainFlags& flags);
int runTerrainCommand(const TerrainFlags& flags);

struct MeshFlags {
    RunFlags run;
    int mapSize = 256;
    std::string grids = "1,16,64", tubes = "32,128", views = "20,45,70";
};
void addMeshOptions(CLI::App& app, MeshFlags& flags);
int runMeshCommand(const MeshFlags& flags);

// The old spelling: on the default run's command line, --materials, --rebuild (with
// --rebuild-sizes) and --terrain (with --memory) run those subcommands instead, after the
// default's own options are checked as they always were.
struct OldSpelling {
    bool materials = false, rebuild = false, terrain = false;
    std::string rebuildSizes = RebuildFlags().mapSizes;
    std::optional<std::size_t> memoryMib;
};
void addOldSpellingOptions(CLI::App& app, OldSpelling& flags);
int runOldSpelling(const MethodsFlags& flags, const OldSpelling& old);

}  // namespace microrelief::bench
