// The old spelling of microrelief-bench's runs (Commands.h): --materials, --rebuild and
// --terrain on the default run's command line, checked in the order they always were (the
// default's options first, then the flags against each other), then the subcommand run.
#include "CommandHelpers.h"
#include "CommandLine.h"
#include "Commands.h"

namespace microrelief::bench {

void addOldSpellingOptions(CLI::App& app, OldSpelling& old) {
    // A group of their own in --help, its title the note. (Hidden, group "", CLI11 would
    // name them "" in its errors: ": 'x' is not a whole number".)
    const std::string group = "The old spelling, kept: microrelief-bench SUBCOMMAND instead";
    app.add_flag("--materials", old.materials, "materials")->group(group);
    app.add_flag("--rebuild", old.rebuild, "rebuild")->group(group);
    app.add_option("--rebuild-sizes", old.rebuildSizes, "rebuild --map-sizes")->group(group);
    app.add_flag("--terrain", old.terrain, "terrain")->group(group);
    app.add_option_function<std::size_t>(
           "--memory", [&old](std::size_t mib) { old.memoryMib = mib; }, "terrain --memory")
        ->check(wholeNumberIn(1, std::size_t{1} << 20))
        ->group(group);
}

int runOldSpelling(const MethodsFlags& flags, const OldSpelling& old) {
    const bool other = old.materials || old.rebuild || old.terrain;
    const MethodsRun methods = checkMethods(flags, !other);
    if (int(old.rebuild) + int(old.materials) + int(old.terrain) > 1)
        throwBadInput("--rebuild, --materials and --terrain: one at a time");
    if (flags.glsl330 && other)
        throwBadInput(
            "--glsl330 is for the methods' comparison, not --rebuild, --materials or --terrain");
    if (old.terrain)
        return runTerrainCommand({flags.run, flags.views, flags.mapSizes,
                                  old.memoryMib.value_or(TerrainFlags().memoryMib)});
    if (old.memoryMib)
        throwBadInput("--memory is the page budget of --terrain; the other runs page nothing");
    if (old.materials) return runMaterialsCommand({flags.run});
    if (old.rebuild) {
        RunFlags run = flags.run;
        if (run.quick && !run.size) run.size = "256x256";  // --quick's pictures, as the default's
        return runRebuildCommand({run, old.rebuildSizes, "--rebuild-sizes"});
    }
    return runMethodsCommand(methods);
}

}  // namespace microrelief::bench
