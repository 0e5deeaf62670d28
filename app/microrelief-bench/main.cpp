// microrelief-bench: what the multilevel method costs, a run a subcommand (Commands.h):
// methods (the default: against its peers), materials, rebuild, terrain and mesh. Each writes its
// reports into --out-dir and prints progress as it goes. main() parses and dispatches.
#include <CLI/CLI.hpp>

#include <functional>
#include <iostream>
#include <vector>

#include "CommandLine.h"
#include "Commands.h"
#include "microrelief/Version.h"
#include "microrelief/core/Error.h"
#include "microrelief/core/Log.h"

using namespace microrelief;
using namespace microrelief::bench;

namespace {

// A subcommand's options follow its name: one of the default's given before it would be
// the default's, and lost.
void refuseOptionsBefore(const CLI::App& app, const CLI::App& subcommand) {
    for (const CLI::Option* option : app.get_options()) {
        if (option->count() > 0)
            throwBadInput(option->get_name() + " comes before '" + subcommand.get_name() +
                          "': a subcommand's options follow its name (microrelief-bench " +
                          subcommand.get_name() + " " + option->get_name() + " ...)");
    }
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Measures the multilevel method against its peers: time, texel fetches, accuracy.",
                 "microrelief-bench"};
    MethodsFlags defaults;  // no subcommand: the methods' run, or the old spelling's
    addMethodsOptions(app, defaults);
    app.set_version_flag("--version",
                         std::string("microrelief-bench ") + MICRORELIEF_VERSION_STRING);
    OldSpelling old;
    addOldSpellingOptions(app, old);

    MethodsFlags methods;
    MaterialsFlags materials;
    RebuildFlags rebuild;
    TerrainFlags terrain;
    MeshFlags mesh;
    struct Subcommand {
        CLI::App* app;
        std::function<int()> run;
    };
    const std::vector<Subcommand> subcommands = {
        {app.add_subcommand("methods",
                            "The default: the multilevel method against its peers, time, texel "
                            "fetches and accuracy (bench.csv, bench.md, plots)"),
         [&] { return runMethodsCommand(methods); }},
        {app.add_subcommand("materials",
                            "What materials cost: shadows (hard, soft) against none, and the "
                            "map tiled 1x1, 2x2, 16x16 and 256x256 (materials.csv, materials.md)"),
         [&] { return runMaterialsCommand(materials); }},
        {app.add_subcommand("rebuild",
                            "What a changing map costs: the pyramids rebuilt on the GPU in full "
                            "and after a 64x64 brush dab, beside a frame's trace of the same map "
                            "(rebuild.csv, rebuild.md)"),
         [&] { return runRebuildCommand(rebuild); }},
        {app.add_subcommand("terrain",
                            "The multilevel method against map size to terrain scale, in whole "
                            "textures, through pages and from pyramid files (past the GL's "
                            "texture limit and past memory too): preparation, first picture, "
                            "frame, fetches, memory, accuracy (terrain.csv, terrain.md, "
                            "terrain.png)"),
         [&] { return runTerrainCommand(terrain); }},
        {app.add_subcommand("mesh",
                            "The mesh base against the analytic base it copies: flat grids "
                            "against the plane, tubes against the cylinder, on the same map, "
                            "pixels and camera: time, agreement, fetches (mesh.csv, mesh.md)"),
         [&] { return runMeshCommand(mesh); }}};
    addMethodsOptions(*subcommands[0].app, methods);
    addMaterialsOptions(*subcommands[1].app, materials);
    addRebuildOptions(*subcommands[2].app, rebuild);
    addTerrainOptions(*subcommands[3].app, terrain);
    addMeshOptions(*subcommands[4].app, mesh);
    app.require_subcommand(0, 1);
    // After the subcommands, which would take it as their own.
    app.footer("Without a subcommand: methods, with the options above.\n");

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
        // The words a subcommand did not expect are its own.
        const CLI::App* where = &app;
        for (const CLI::App* subcommand : app.get_subcommands()) where = subcommand;
        std::cerr << "microrelief-bench: error: " << printable(parseErrorMessage(e, *where))
                  << '\n';
        return 2;
    }
    setLogSink([](LogLevel level, const std::string& message) {
        if (level == LogLevel::Warning)
            std::cerr << "microrelief-bench: warning: " << message << '\n';
    });
    try {
        for (const Subcommand& subcommand : subcommands) {
            if (!subcommand.app->parsed()) continue;
            refuseOptionsBefore(app, *subcommand.app);
            return subcommand.run();
        }
        return runOldSpelling(defaults, old);
    } catch (const Error& e) {
        std::cerr << "microrelief-bench: error: " << e.what() << '\n';
        return exitStatusOf(e.kind());
    }
}
