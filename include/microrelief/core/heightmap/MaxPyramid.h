// The multilevel elevation map of the paper (section II, fig. 2): level k-1 holds the
// maximum of the level-k values it covers, down to a single value, so that a ray
// segment lying above a level's max over its footprint can be discarded whole.
//
// Differences from the paper's sample pyramid that make it exact for our surface, and
// small:
//  * It bounds the surface, not just the samples. Finest texel (i, j) covers the texel
//    square [i, i+1] x [j, j+1] in texel space (X = u W, Y = v H) and holds a bound of the
//    surface over that square (texelSquareBound): the largest of nine values, the sample
//    and the averages of its neighbours, which are the bilinear surface's peaks there and
//    the biquadratic piece's Bezier net alike, each rounded up to a float.
//  * The GPU stores it in half floats (BoundPrecision::Half, R16F; Float keeps the bounds
//    as they are, for use on the CPU alone): each
//    finest bound rounded up to 11 significant bits (storedBound), coarser levels the
//    maxima of those, so every bound stays on or above the surface. The GPU divides them by
//    2^S (pyramidScaleExponent: S from the top's binary exponent), so that the largest
//    lies below 2^15 and every nonzero one at or above 2^-14, the halves' normal range.
//  * Any size reduces, with no padding: the windows the multilevel traversal reads (below)
//    have GL's own mip sizes of W x H, level k max(1, W >> k) by max(1, H >> k), down to
//    1 x 1 (windowLevelSizes). Their levels are built on blocks: block (p, q) of level k
//    covers finest texels [p 2^k, (p+1) 2^k) x [q 2^k, (q+1) 2^k), except the last of a
//    row or column, which reaches to the map's edge (up to 2^(k+1) - 1 texels). An index
//    at level k is the finest index shifted right by k, clamped to the level's size.
//  * Overlapping windows: window (p, q) of level k is the max of blocks p..p+1 by q..q+1,
//    twice as wide, so that neighbouring windows overlap by half and a footprint whose
//    texels span at most one level-k boundary per axis lies inside the window at its
//    lower corner: a segment's bound is always one texel, read at a level no coarser than
//    its footprint (segmentBound).
//  * The quadtree the maxmip peer walks as it was published, power-of-two levels, is not
//    here: peers/MaxMipPyramid.h builds it from this pyramid's finest bounds.
//
// On a curved base u wraps (BaseShape.h): the finest level's texel squares at the seam
// take their neighbours from the other side of the map (wrapU), and a footprint that
// crosses the seam is read as its two parts (footprintBound). Coarser levels are as on
// the plane: no window reaches across the seam.
//
// A tiled map (MapAddressing's tiles) keeps the tile's pyramid: each finest texel bounds
// its square wherever the tile repeats (finestBound), and a footprint is taken into the
// tile, or read as the tile's top where it crosses a seam between tiles (tiledWindows).
//
// The same texels come out of the GPU builder (gl/PyramidBuilder.h), bit for bit: every
// value is computed in integer arithmetic on the floats' bits, which a GPU does exactly as
// a CPU does (no rounding mode, no flushed denormals, no reassociation can change it).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "microrelief/core/heightmap/HeightMap.h"

namespace microrelief {

// A rectangle of texels [x0, x1) x [y0, y1).
struct TexelRect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;

    bool empty() const { return x1 <= x0 || y1 <= y0; }
    int width() const { return x1 - x0; }
    int height() const { return y1 - y0; }
    bool operator==(const TexelRect&) const = default;
};

// The smallest float not below (a + b) / 2, for finite a, b >= 0 (-0 is taken as 0):
// the exact mean rounded up, computed on the floats' bits in 32-bit integers (the
// mantissas aligned with three guard bits and a sticky bit for what falls below them;
// see MaxPyramid.cpp). shaders/microrelief/pyramid_bound.glsl is the same code in GLSL.
float roundUpMean(float a, float b);

// The finest level's texel (i, j): a bound of the surface over texel square
// [i, i+1] x [j, j+1] built from the 3 x 3 samples around sample (i, j) (clamped, or
// wrapped in u when `wrapU`), never below the surface, for either interpolation. The
// nine values are the sample, the means of its neighbours along each axis and of the
// 2 x 2 blocks it shares (rows first, then columns, each rounded up by roundUpMean):
//  * bilinear: the surface's peaks over the square. The square straddles four bilinear
//    cells; on each the patch is linear along both axes, so its max over a sub-rectangle
//    sits at a corner, and the nine corner points (texel corners, edge midpoints, the
//    sample) are these means;
//  * biquadratic: the piece's Bezier control net, which is per axis (c0 + c1) / 2, c1,
//    (c1 + c2) / 2 of its three control points; the piece lies in the net's convex hull.
// Each mean is rounded up, and a mean of rounded-up values is at least the mean of the
// exact ones, so the bound is at least the exact maximum (it is that maximum rounded up,
// or an ulp or two above when a row's mean was rounded before the column's), and at most
// the largest of the nine samples.
float texelSquareBound(const HeightMap& map, int i, int j, bool wrapU);
// The same with the samples as `addressing` has them (i, j over the tiled whole).
float texelSquareBound(const HeightMap& map, int i, int j, const MapAddressing& addressing);

// How the bounds are kept: Float, the finest bounds as texelSquareBound gives them; Half,
// on the grid the GPU's half floats hold (the renderer's textures, and the CPU twin, which
// so reads what the shader reads).
enum class BoundPrecision { Float, Half };

// S for a pyramid whose top (largest texel) is `top`: the GPU holds bound / 2^S, where
// S = e - 14 and e = floor(log2 top) (from the float's exponent field), clamped to
// [-112, 113] so that 2^S and 2^(S - 14) are normal floats. Then the top, below 2^(e+1),
// is held below 2^15, within a half's range (65504).
int pyramidScaleExponent(float top);
// The top of a Half pyramid whose largest sample is `largestSample` (>= 0): that sample
// rounded up to 11 significant bits (no bound exceeds its nine samples, and the largest
// sample's own texel square has it among them). Its pyramidScaleExponent is the pyramid's S.
float pyramidTop(float largestSample);
// The finest bound `bound` (>= 0) as kept: Float, itself; Half, rounded up to 11 significant
// bits (the bits plus 2^13 - 1, the low 13 cleared: a carry moves into the exponent) and
// raised to at least 2^(S - 14), the smallest normal half times 2^S, when it is not 0. Both
// steps only raise it, so it stays a bound; divided by 2^S it is a normal half, exactly.
float storedBound(float bound, BoundPrecision precision, int scaleExponent);

// The stored finest bounds (storedBound of texelSquareBound, bit for bit) of the texels in
// `rect` of `map` as `addressing` has it, untiled, into `out` from texel (rect.x0, rect.y0)
// on, `stride` floats a row: in bands of rows on the machine's cores, each mean of the
// texels' nets taken once (neighbouring texels share them). What MaxPyramid's build and
// PyramidStream.h's compute.
void finestBounds(const HeightMap& map, const MapAddressing& addressing, const TexelRect& rect,
                  BoundPrecision precision, int scaleExponent, float* out, std::size_t stride);

// The windows' (and blocks') sizes: GL's mip sizes of W x H, max(1, W >> k) by
// max(1, H >> k), down to 1 x 1.
std::vector<glm::ivec2> windowLevelSizes(int mapWidth, int mapHeight);

// The texels to compute again, per level of a pyramid of `levelSizes` (windowLevelSizes, or
// peers/MaxMipPyramid.h's maxMipLevelSizes), when the samples inside `changed` (map texels) change:
// the finest texels whose 3 x 3 samples reach into it (across the seam when `wrapU`), then on each
// level the parents of the changed texels below (index >> 1, clamped to the level: the last absorbs
// the remainder), and the windows that hold a changed texel. aligned[k] (the blocks, or maxmip's
// quadtree texels) and windows[k] list at most two rectangles each (two where the region wraps
// round the seam), none where nothing changes. MaxPyramid::update and the GPU builder
// (gl/PyramidBuilder.h) compute these.
struct PyramidRegions {
    std::vector<std::vector<TexelRect>> aligned, windows;
};
PyramidRegions pyramidUpdateRegions(const std::vector<glm::ivec2>& levelSizes, int mapWidth,
                                    int mapHeight, bool wrapU, const TexelRect& changed);

// What a read of the pyramid gives a traversal (MaxPyramid::segmentBound, footprintBound):
// the bound, the level of the last window read (the statistics' stop level), and how many
// texels it read, counted as the shader's fetches. A traversal adds the reads' counts to
// its own (TraversalStats), so a new count is a field here and a line where it is kept.
struct BoundRead {
    double bound = 0.0;
    int level = -1;
    int fetches = 0;
};

class MaxPyramid {
public:
    // `wrapU`: the map's u is periodic (a curved base), column W - 1 joins column 0.
    // The finest level bounds both last levels, bilinear and biquadratic: both take the
    // same nine values (texelSquareBound). `precision`: Float, the bounds unrounded; Half,
    // the renderer's (and the GPU builder's) texels.
    explicit MaxPyramid(const HeightMap& map, bool wrapU = false,
                        BoundPrecision precision = BoundPrecision::Float);
    // A tiled map's pyramid (`addressing`'s tiles): the tile's, its finest level bounding
    // each texel square wherever the tile repeats, across the seams between tiles and at
    // the whole's clamped edges; footprints are taken into the tile (footprintBound).
    MaxPyramid(const HeightMap& map, const MapAddressing& addressing,
               BoundPrecision precision = BoundPrecision::Float);

    // After samples of `map` (the same size as before) changed inside `changed`: the
    // texels whose bounds read them, on every level (pyramidUpdateRegions), computed
    // again (and every texel, where the top's binade and with it S changed, or the map is
    // tiled). The result is the pyramid of the new map, texel for texel.
    void update(const HeightMap& map, const TexelRect& changed);

    int mapWidth() const { return mapWidth_; }
    int mapHeight() const { return mapHeight_; }
    BoundPrecision precision() const { return precision_; }
    // S (pyramidScaleExponent of the top); 0 for Float.
    int scaleExponent() const { return scaleExponent_; }
    // The top: the surface's max as kept (map units), the largest sample rounded up.
    float maxHeight() const { return windows_.back().front(); }

    // The overlapping levels (the multilevel traversal's), GL's mip sizes of W x H, and the
    // blocks they are made of, in the same layout; level 0's blocks are the finest bounds,
    // block(0, i, j) the bound over texel square [i, i+1] x [j, j+1].
    int windowLevelCount() const { return static_cast<int>(windows_.size()); }
    int windowLevelWidth(int level) const { return windowSizes_[level].x; }
    int windowLevelHeight(int level) const { return windowSizes_[level].y; }
    const std::vector<float>& windowLevelData(int level) const { return windows_[level]; }
    float window(int level, int p, int q) const {
        return windows_[level][static_cast<std::size_t>(q) * windowSizes_[level].x + p];
    }
    const std::vector<float>& blockLevelData(int level) const { return blocks_[level]; }
    float block(int level, int p, int q) const {
        return blocks_[level][static_cast<std::size_t>(q) * windowSizes_[level].x + p];
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
    // segment's footprint. Never below the surface anywhere along the segment's path.
    BoundRead segmentBound(glm::dvec2 a, glm::dvec2 b) const;

    // The bound over a footprint rectangle [lo, hi] of map points (lo <= hi per axis), the
    // curved bases' form of segmentBound (max_pyramid.glsl: mr_footprintBound): one window,
    // or on a wrapped map whose rectangle reaches past X = W (hi.x >= W, lo.x < W), the
    // larger of the windows over its two parts, [lo.x, W) and [0, hi.x - W].
    BoundRead footprintBound(glm::dvec2 lo, glm::dvec2 hi) const;
    bool wrapsU() const { return wrapU_; }
    const MapAddressing& addressing() const { return addressing_; }

private:
    void build(const HeightMap& map);
    // Finest texel (i, j)'s bound over every occurrence of its square (tiled: the max over
    // the first and the last tile's), before storedBound.
    float finestBound(const HeightMap& map, int i, int j) const;
    void computeFinest(const HeightMap& map, const TexelRect& rect);
    void reduceBlocks(int level, const TexelRect& rect);
    void computeWindows(int level, const TexelRect& rect);

    // The window at windowLevel over the finest texels lo..hi, one fetch.
    BoundRead windowOver(glm::ivec2 lo, glm::ivec2 hi) const;
    // A tiled map's bound over its finest texels lo..hi (max_pyramid.glsl: mr_tiledWindows).
    BoundRead tiledWindows(glm::ivec2 lo, glm::ivec2 hi) const;

    int mapWidth_, mapHeight_;
    bool wrapU_ = false;
    MapAddressing addressing_;
    BoundPrecision precision_ = BoundPrecision::Half;
    int scaleExponent_ = 0;
    std::vector<glm::ivec2> windowSizes_;
    std::vector<std::vector<float>> blocks_;   // the windows' blocks; level 0 the finest
    std::vector<std::vector<float>> windows_;  // overlapping
};

}  // namespace microrelief
