#include "microrelief/core/heightmap/PyramidPages.h"

#include <algorithm>
#include <utility>

#include "microrelief/core/Error.h"
#include "microrelief/core/heightmap/PyramidStream.h"

namespace microrelief {

namespace {

// Rows of samples a band of the in-memory build reads at a time (PyramidStream.h): its
// window of rows and their bounds take about 2 (band + 2) rows.
constexpr int kStreamBand = 256;

}  // namespace

PyramidPages::PyramidPages(int mapWidth, int mapHeight, bool wrapU, float largestSample)
    : mapWidth_(mapWidth),
      mapHeight_(mapHeight),
      wrapU_(wrapU),
      largestSample_(largestSample),
      scaleExponent_(pyramidScaleExponent(pyramidTop(largestSample))),
      windowSizes_(windowLevelSizes(mapWidth, mapHeight)) {}

std::vector<float> PyramidPages::readLevel(int level) const {
    const glm::ivec2 size = levelSize(level);
    std::vector<float> texels(static_cast<std::size_t>(size.x) * size.y);
    read(level, {0, 0, size.x, size.y}, texels.data());
    return texels;
}

PyramidInMemory::PyramidInMemory(std::shared_ptr<const HeightMap> map, bool wrapU,
                                 const std::string& source)
    : PyramidInMemory(map, wrapU, streamWindows(*map, wrapU, source)) {}

PyramidInMemory::PyramidInMemory(std::shared_ptr<const HeightMap> map, bool wrapU, Windows windows)
    : PyramidPages(map->width, map->height, wrapU, windows.largestSample),
      map_(std::move(map)),
      windows_(std::move(windows.levels)) {}

PyramidInMemory::Windows PyramidInMemory::streamWindows(const HeightMap& map, bool wrapU,
                                                        const std::string& source) {
    // Each level's texels are written once, row by row, by the stream: allocated without
    // being cleared first (a 20000 x 20000 map's windows are 2.1 GB).
    Windows windows;
    const std::vector<glm::ivec2> sizes = windowLevelSizes(map.width, map.height);
    for (const glm::ivec2 size : sizes)
        windows.levels.push_back(
            std::make_unique_for_overwrite<float[]>(static_cast<std::size_t>(size.x) * size.y));
    const MapRows rows{
        map.width, map.height, [&](int y0, int y1, float* out) {
            std::copy(map.samples.begin() + static_cast<std::ptrdiff_t>(y0) * map.width,
                      map.samples.begin() + static_cast<std::ptrdiff_t>(y1) * map.width, out);
        }};
    const StreamedPyramid streamed = streamPyramid(
        rows, wrapU, kStreamBand,
        [&](int level, int row, const float* texels) {
            if (level == 0) return;  // the samples: the map's own
            const int width = sizes[level - 1].x;
            std::copy_n(texels, width,
                        windows.levels[level - 1].get() + static_cast<std::size_t>(row) * width);
        },
        source);
    windows.largestSample = streamed.largestSample;
    return windows;
}

void PyramidInMemory::read(int level, const TexelRect& rect, float* out) const {
    const int width = levelSize(level).x;
    const float* data = level == 0 ? map_->samples.data() : windows_[level - 1].get();
    for (int y = rect.y0; y < rect.y1; ++y) {
        const float* from = data + static_cast<std::ptrdiff_t>(y) * width + rect.x0;
        out = std::copy(from, from + rect.width(), out);
    }
}

}  // namespace microrelief
