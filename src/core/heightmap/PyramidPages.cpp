#include "microrelief/core/heightmap/PyramidPages.h"

#include <algorithm>
#include <utility>

#include "microrelief/core/Error.h"

namespace microrelief {

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

PyramidInMemory::PyramidInMemory(HeightMap map, MaxPyramid pyramid)
    : PyramidPages(map.width, map.height, pyramid.wrapsU(), map.maxValue()),
      map_(std::move(map)),
      pyramid_(std::move(pyramid)) {
    if (pyramid_.precision() != BoundPrecision::Half || pyramid_.addressing().tilesX != 1 ||
        pyramid_.addressing().tilesY != 1 || pyramid_.mapWidth() != map_.width ||
        pyramid_.mapHeight() != map_.height)
        throwRuntime("PyramidInMemory: the map's own pyramid, untiled, of BoundPrecision::Half");
}

void PyramidInMemory::read(int level, const TexelRect& rect, float* out) const {
    const int width = levelSize(level).x;
    const std::vector<float>& data =
        level == 0 ? map_.samples : pyramid_.windowLevelData(level - 1);
    for (int y = rect.y0; y < rect.y1; ++y) {
        const auto from = data.begin() + static_cast<std::ptrdiff_t>(y) * width + rect.x0;
        out = std::copy(from, from + rect.width(), out);
    }
}

}  // namespace microrelief
