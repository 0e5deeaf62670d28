#include "PyramidCache.h"

#include <algorithm>
#include <cstdio>
#include <string>

#include "Progress.h"
#include "SceneOptions.h"
#include "microrelief/core/Error.h"
#include "microrelief/io/HeightMapFile.h"

namespace microrelief {

namespace {

// The build's progress: a line when it starts, then the percentage on a terminal.
BuildProgress buildProgress(const std::string& map, bool quiet) {
    if (quiet) return {};
    auto shown = std::make_shared<int>(-1);
    const bool terminal = BatchProgress::stderrIsTerminal();
    return [map, shown, terminal](long long done, long long total) {
        const int percent = static_cast<int>(100 * done / std::max(total, 1LL));
        if (*shown < 0) {
            std::fprintf(stderr,
                         "microrelief-render: building the pyramid file of %s (once; reused "
                         "while the map is unchanged)\n",
                         map.c_str());
        }
        if (terminal && percent != *shown) {
            std::fprintf(stderr, "\rmicrorelief-render: pyramid %3d %%%s", percent,
                         done == total ? "\n" : "");
            std::fflush(stderr);
        }
        *shown = percent;
    };
}

}  // namespace

std::shared_ptr<const PyramidFile> openPyramidCache(const RenderOptions& options,
                                                    const std::filesystem::path& map,
                                                    const HeightMapLoadOptions& load, bool wrapU) {
    return openOrBuildPyramidFile(map, *options.pyramidCache, load, wrapU,
                                  buildProgress(map.string(), options.quiet));
}

BaseShape drawnBase(const SceneOptions& scene, const std::filesystem::path& map) {
    const std::optional<Georeference> grid = readMapGrid(map);
    return grid ? fittedBase(scene.job.base, *grid, scene.georeference) : scene.job.base;
}

std::string pyramidFileRefusal(const RenderJob& job, bool compareReference) {
    if (job.method.method != Method::Multilevel) {
        return "--pyramid-cache reads the map through pages, which only the multilevel method "
               "reads: not " +
               flagName("method") + " " + std::string(methodName(job.method.method));
    }
    if (job.tiles != glm::ivec2(1, 1))
        return "--pyramid-cache draws one map: not with " + flagName("tiles");
    if (!job.animation.empty())
        return "--pyramid-cache draws a map's own heights: not with " + flagName("animation");
    if (compareReference && job.base.kind != BaseKind::Plane) {
        return "--compare-reference over a pyramid file traces the plane's reference: not "
               "with " +
               flagName("base") + " " + baseName(job.base);
    }
    return {};
}

void checkDrawnFromPyramidFile(const RenderJob& job, bool compareReference) {
    if (const std::string refusal = pyramidFileRefusal(job, compareReference); !refusal.empty())
        throwBadInput(refusal);
}

ReliefFiles loadFilesOrPointToCache(const RenderJob& job, bool compareReference,
                                    ReliefParts parts) {
    try {
        return loadReliefFiles(job, parts);
    } catch (const MapOverMemory& e) {
        if (!pyramidFileRefusal(job, compareReference).empty()) throw;
        throw e.followedBy("; --pyramid-cache FOLDER draws it from disk");
    }
}

}  // namespace microrelief
