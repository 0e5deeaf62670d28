// The multilevel elevation map of the paper (section II, fig. 2): level k-1 holds the
// maximum of the level-k values it covers, down to a single value, so that a ray
// segment lying above a level's max over its footprint can be discarded whole.
//
// Two differences from the paper's sample pyramid make it exact for our surface:
//  * It bounds the bilinear surface, not just the samples. Finest level texel (i, j)
//    covers the texel square [i, i+1] x [j, j+1] in texel space (X = u W, Y = v H) and
//    holds the surface's maximum over that square. The square straddles four bilinear
//    cells; on each the bilinear patch is linear along both axes, so its max over a
//    sub-rectangle sits at a corner, and the nine corner points (texel corners, edge
//    midpoints, the sample itself) give the exact maximum.
//  * Any size reduces. Levels are stored padded to powers of two, Pw = 2^ceil(log2 W)
//    by Ph = 2^ceil(log2 H), with padding texels 0 (no surface there; heights are >= 0).
//    Level k is max(1, Pw >> k) by max(1, Ph >> k), GL's own mip sizes, and its texel
//    (p, q) covers finest texels [p 2^k, (p+1) 2^k) x [q 2^k, (q+1) 2^k): an index at
//    level k is the finest index shifted right by k, clamped to the level's size. Odd,
//    non-power-of-two and non-square maps need no special case.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "heightmap/HeightMap.h"

namespace microrelief {

class MaxPyramid {
public:
    explicit MaxPyramid(const HeightMap& map);

    int mapWidth() const { return mapWidth_; }
    int mapHeight() const { return mapHeight_; }
    int levelCount() const { return static_cast<int>(levels_.size()); }
    int levelWidth(int level) const { return widths_[level]; }
    int levelHeight(int level) const { return heights_[level]; }
    const std::vector<float>& levelData(int level) const { return levels_[level]; }
    float texel(int level, int p, int q) const {
        return levels_[level][static_cast<std::size_t>(q) * widths_[level] + p];
    }

    // The level whose texels are at least as wide as `extent` finest texels.
    int footprintLevel(double extent) const;

    // The level-`level` texel holding map point p (max_pyramid.glsl: pyramidTexelAt).
    glm::ivec2 texelAt(glm::dvec2 p, int level) const;

    // The bound over the segment from a to b that the shader reads (max_pyramid.glsl:
    // segmentBound): the max of the one to three texels the segment crosses at `level`
    // (in: the footprint level; out: the level read), counting them in `fetches`. Never
    // below the surface anywhere along the segment's path.
    double segmentBound(glm::dvec2 a, glm::dvec2 b, int& level, int& fetches) const;

private:
    int mapWidth_, mapHeight_;
    std::vector<int> widths_, heights_;
    std::vector<std::vector<float>> levels_;
};

}  // namespace microrelief
