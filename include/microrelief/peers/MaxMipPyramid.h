// The maximum mipmap the maxmip peer walks, as it was published (Tevs, Ihrke and Seidel,
// "Maximum Mipmaps for Fast, Accurate, and Scalable Dynamic Height Field Rendering",
// I3D 2008): a quadtree of power-of-two levels over the map, each texel the max of the
// two by two below it. The cone-map builds (ConeMap.h) walk it too.
//
// Layout: Pw = 2^ceil(log2 W) by Ph = 2^ceil(log2 H), level k max(1, Pw >> k) by
// max(1, Ph >> k) down to 1 x 1 (maxMipLevelSizes). Level 0's texel (i, j) is the max
// pyramid's finest bound over texel square [i, i+1] x [j, j+1] (core/heightmap/MaxPyramid.h:
// never below the surface there, in the precision that pyramid keeps), the padding texels
// beyond the map 0 (no surface there; heights are >= 0). A texel of level k is the max of
// its children, exactly (a max rounds nothing), so it bounds the surface over every finest
// square it covers: the bound the peer's traversal needs.
//
// The GPU's (gl/PyramidBuilder.h) is the same texel for texel.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "microrelief/core/heightmap/MaxPyramid.h"

namespace microrelief {

// The levels' sizes for a W x H map, finest first (the layout above).
std::vector<glm::ivec2> maxMipLevelSizes(int mapWidth, int mapHeight);

class MaxMipPyramid {
public:
    // From `pyramid`'s finest bounds, in its precision and scale (a Half pyramid's texels
    // are what the GPU holds, times 2^S).
    explicit MaxMipPyramid(const MaxPyramid& pyramid);

    int mapWidth() const { return mapWidth_; }
    int mapHeight() const { return mapHeight_; }
    int levelCount() const { return static_cast<int>(levels_.size()); }
    int levelWidth(int level) const { return sizes_[level].x; }
    int levelHeight(int level) const { return sizes_[level].y; }
    const std::vector<float>& levelData(int level) const { return levels_[level]; }
    float texel(int level, int p, int q) const {
        return levels_[level][static_cast<std::size_t>(q) * sizes_[level].x + p];
    }

private:
    int mapWidth_, mapHeight_;
    std::vector<glm::ivec2> sizes_;
    std::vector<std::vector<float>> levels_;
};

}  // namespace microrelief
