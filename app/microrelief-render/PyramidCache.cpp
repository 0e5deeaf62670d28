#include "PyramidCache.h"

#include <algorithm>
#include <cstdio>
#include <string>

#include "Progress.h"
#include "microrelief/core/Error.h"

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

void checkDrawnFromPyramidFile(const RenderJob& job) {
    if (job.method.method != Method::Multilevel) {
        throwBadInput(
            "--pyramid-cache reads the map through pages, which only the multilevel method "
            "reads: not --method " +
            std::string(methodName(job.method.method)));
    }
    if (job.tiles != glm::ivec2(1, 1))
        throwBadInput("--pyramid-cache draws one map: not with --tile");
    if (!job.animation.empty())
        throwBadInput("--pyramid-cache draws a map's own heights: not with --animate");
}

}  // namespace microrelief
