// microrelief-bench materials: what shadows and tiling cost (Materials.h), written to
// materials.csv and materials.md.
#include <iostream>

#include "CommandHelpers.h"
#include "Commands.h"
#include "Materials.h"
#include "microrelief/headless/HeadlessContext.h"

namespace microrelief::bench {

void addMaterialsOptions(CLI::App& app, MaterialsFlags& flags) {
    addRunOptions(app, flags.run, "The 256 x 256 map alone (not 4096 too), 256x256 pictures",
                  "Picture size WIDTHxHEIGHT (default 512x512; 256x256 with --quick)",
                  "Folder for materials.csv and materials.md");
}

int runMaterialsCommand(const MaterialsFlags& flags) {
    checkFrames(flags.run);
    int width = 0, height = 0;
    parseSizeFlag(flags.run.size.value_or(flags.run.quick ? "256x256" : "512x512"), width, height);
    checkOutputFolder(flags.run.outDir);
    const auto context = createHeadlessContext(parseBackend(flags.run.backend));
    const std::vector<MaterialRow> rows =
        runMaterialsBenchmark(*context, width, height, flags.run.frames, flags.run.quick);
    const std::filesystem::path folder = flags.run.outDir;
    std::cout << '\n' << writeMaterials(folder, context->renderer(), rows);
    std::cout << "microrelief-bench: wrote " << (folder / "materials.csv").string()
              << " and materials.md\n";
    return 0;
}

}  // namespace microrelief::bench
