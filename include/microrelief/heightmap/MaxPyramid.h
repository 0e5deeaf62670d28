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
//
// Beside these aligned levels (the quadtree the maxmip peer walks) it keeps overlapping
// ones, which the multilevel traversal reads: overlapping texel (p, q) of level k is the
// max of aligned level-k texels p..p+1 by q..q+1, the surface's max over the window
// [p 2^k, (p+2) 2^k) x [q 2^k, (q+2) 2^k) of finest texels. Neighbouring windows overlap
// by half, so a footprint whose texels span at most one level-k boundary per axis lies
// inside the window at its lower corner: a segment's bound is always one texel, read at
// a level no coarser than its footprint (segmentBound).
//
// On a curved base u wraps (BaseShape.h): the finest level's texel squares at the seam
// take their neighbours from the other side of the map (wrapU), and a footprint that
// crosses the seam is read as its two parts (footprintBound). Coarser levels and the
// padding are as on the plane: no window reaches across the seam.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "microrelief/heightmap/HeightMap.h"

namespace microrelief {

class MaxPyramid {
public:
    // `wrapU`: the map's u is periodic (a curved base), column W - 1 joins column 0.
    // `interpolation`: the surface the finest level bounds (biquadratic: the max of the
    // Bezier control net of the patch over each texel square, see MaxPyramid.cpp).
    explicit MaxPyramid(const HeightMap& map, bool wrapU = false,
                        Interpolation interpolation = Interpolation::Bilinear);
    // A tiled map's pyramid (`addressing`'s tiles): the tile's, its finest level bounding
    // each texel square wherever the tile repeats, across the seams between tiles and at
    // the whole's clamped edges; footprints are taken into the tile (footprintBound).
    MaxPyramid(const HeightMap& map, const MapAddressing& addressing, Interpolation interpolation);

    int mapWidth() const { return mapWidth_; }
    int mapHeight() const { return mapHeight_; }
    int levelCount() const { return static_cast<int>(levels_.size()); }
    int levelWidth(int level) const { return widths_[level]; }
    int levelHeight(int level) const { return heights_[level]; }
    const std::vector<float>& levelData(int level) const { return levels_[level]; }
    float texel(int level, int p, int q) const {
        return levels_[level][static_cast<std::size_t>(q) * widths_[level] + p];
    }

    // The overlapping levels, in the same layout as the aligned ones.
    const std::vector<float>& windowLevelData(int level) const { return windows_[level]; }
    float window(int level, int p, int q) const {
        return windows_[level][static_cast<std::size_t>(q) * widths_[level] + p];
    }

    // The finest texel holding map point p, clamped to the map (max_pyramid.glsl:
    // finestTexelAt).
    glm::ivec2 finestTexelAt(glm::dvec2 p) const;

    // The level whose windows hold a footprint of finest texels lo..hi (per axis, lo <=
    // hi): the finest level k at which the footprint spans at most one level-k texel
    // boundary per axis (max_pyramid.glsl: mr_windowLevel).
    int windowLevel(glm::ivec2 lo, glm::ivec2 hi) const;

    // The bound over the segment from a to b that the shader reads (max_pyramid.glsl:
    // segmentBound): one overlapping texel, the window at windowLevel that holds the
    // segment's footprint; `level` is set to that level and `fetches` counts the read.
    // Never below the surface anywhere along the segment's path.
    double segmentBound(glm::dvec2 a, glm::dvec2 b, int& level, int& fetches) const;

    // The bound over a footprint rectangle [lo, hi] of map points (lo <= hi per axis), the
    // curved bases' form of segmentBound (max_pyramid.glsl: mr_footprintBound): one window,
    // or on a wrapped map whose rectangle reaches past X = W (hi.x >= W, lo.x < W), the
    // larger of the windows over its two parts, [lo.x, W) and [0, hi.x - W]. `level` is
    // the level of the last window read.
    double footprintBound(glm::dvec2 lo, glm::dvec2 hi, int& level, int& fetches) const;
    bool wrapsU() const { return wrapU_; }
    const MapAddressing& addressing() const { return addressing_; }

private:
    // The window at windowLevel over the finest texels lo..hi, one fetch.
    double windowOver(glm::ivec2 lo, glm::ivec2 hi, int& level, int& fetches) const;
    // A tiled map's bound over its finest texels lo..hi (max_pyramid.glsl: mr_tiledWindows).
    double tiledWindows(glm::ivec2 lo, glm::ivec2 hi, int& level, int& fetches) const;

    int mapWidth_, mapHeight_;
    bool wrapU_ = false;
    MapAddressing addressing_;
    std::vector<int> widths_, heights_;
    std::vector<std::vector<float>> levels_;
    std::vector<std::vector<float>> windows_;
};

}  // namespace microrelief
