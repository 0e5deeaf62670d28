#include "microrelief/peers/MaxMipPyramid.h"

#include <algorithm>

namespace microrelief {

namespace {

int ceilPowerOfTwo(int n) {
    int p = 1;
    while (p < n) p <<= 1;
    return p;
}

}  // namespace

std::vector<glm::ivec2> maxMipLevelSizes(int mapWidth, int mapHeight) {
    std::vector<glm::ivec2> sizes;
    for (glm::ivec2 size(ceilPowerOfTwo(mapWidth), ceilPowerOfTwo(mapHeight));;
         size = glm::max(size >> 1, glm::ivec2(1))) {
        sizes.push_back(size);
        if (size == glm::ivec2(1)) return sizes;
    }
}

MaxMipPyramid::MaxMipPyramid(const MaxPyramid& pyramid)
    : mapWidth_(pyramid.mapWidth()),
      mapHeight_(pyramid.mapHeight()),
      sizes_(maxMipLevelSizes(mapWidth_, mapHeight_)) {
    for (const glm::ivec2 size : sizes_) levels_.emplace_back(std::size_t(size.x) * size.y, 0.0f);
    // Level 0: the finest bounds (the max pyramid's level-0 blocks, W x H), padded with 0.
    const std::vector<float>& finest = pyramid.blockLevelData(0);
    for (int j = 0; j < mapHeight_; ++j)
        std::copy_n(finest.begin() + static_cast<std::ptrdiff_t>(j) * mapWidth_, mapWidth_,
                    levels_[0].begin() + static_cast<std::ptrdiff_t>(j) * sizes_[0].x);
    for (int level = 1; level < levelCount(); ++level) {
        const glm::ivec2 c = sizes_[level - 1], size = sizes_[level];
        const std::vector<float>& child = levels_[level - 1];
        for (int q = 0; q < size.y; ++q) {
            for (int p = 0; p < size.x; ++p) {
                float best = 0.0f;
                for (int cq = 2 * q; cq <= std::min(2 * q + 1, c.y - 1); ++cq) {
                    for (int cp = 2 * p; cp <= std::min(2 * p + 1, c.x - 1); ++cp)
                        best = std::max(best, child[static_cast<std::size_t>(cq) * c.x + cp]);
                }
                levels_[level][static_cast<std::size_t>(q) * size.x + p] = best;
            }
        }
    }
}

}  // namespace microrelief
