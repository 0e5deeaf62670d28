// max_pyramid.glsl: reading the multilevel elevation map (paper, section II-III, fig. 6).
//
// Two pyramids, single-channel half-float textures (R16F) with nearest filtering
// (GL_NEAREST_MIPMAP_NEAREST), built by MaxPyramid, their bounds divided by 2^S
// (mr_pyramidScale, from the top, mr_ReliefMap's maxHeight):
//  * the aligned one (the quadtree, maxmip's), W, H rounded up to powers of two and halved
//    down to 1 x 1: level k texel (p, q) holds the maximum of the surface over map-space
//    X in [p 2^k, (p+1) 2^k), Y in [q 2^k, (q+1) 2^k);
//  * the overlapping one (the windows, the multilevel method's), GL's mip sizes of W x H:
//    level k texel (p, q) holds the max of blocks p..p+1 by q..q+1 of level k, block (p, q)
//    covering finest texels [p 2^k, (p+1) 2^k) x [q 2^k, (q+1) 2^k), the last of a row or
//    column to the map's edge; twice as wide as a block, so that windows overlap by half.
// The multilevel traversal reads the windows (mr_footprintBound), maxmip the quadtree. On a
// curved base the finest level bounds the surface across the seam u = 0 (MaxPyramid's
// wrapU) and a footprint that crosses the seam is read as its two parts.
#ifndef MICRORELIEF_MAX_PYRAMID_GLSL
#define MICRORELIEF_MAX_PYRAMID_GLSL

#include "base_surface.glsl"
#include "fetch_count.glsl"
#include "relief_map.glsl"
#include "texture_reads.glsl"

// The finest texel that holds map point p, clamped to the map (not its padding); the
// level-k texel holding it is this shifted right by k.
ivec2 mr_finestTexelAt(mr_Relief relief, vec2 p) {
    return clamp(ivec2(floor(p)), ivec2(0), ivec2(relief.map.size) - 1);
}

// 2^S: the pyramids hold bound / 2^S as halves, S = e - 14 for the top's binary exponent
// e (clamped to [-112, 113]), so the top lies below 2^15 and every nonzero bound at or
// above 2^-14, a half's normal range (MaxPyramid.h: pyramidScaleExponent). Exact: a power
// of two built from its bits, and a product with it exact too.
float mr_pyramidScale(mr_Relief relief) {
    int e = int(floatBitsToUint(relief.map.maxHeight) >> 23u) - 127;
    return uintBitsToFloat(uint(clamp(e - 14, -112, 113) + 127) << 23u);
}

// One pyramid texel: the bound it stands for, map units.
float mr_pyramidTexel(mr_Relief relief, MICRORELIEF_SAMPLER pyramid, ivec2 texel, int level) {
    MICRORELIEF_FETCHED_BOUNDS(1);
    vec2 levelSize = vec2(max(ivec2(1), relief.map.pyramidSize >> level));
    return MICRORELIEF_READ_PYRAMID(pyramid, texel, level, levelSize) * mr_pyramidScale(relief);
}

// floor(log2(n)) for n >= 1, exactly; 0 for n = 0.
int mr_floorLog2(int n) {
#if __VERSION__ >= 400
    return max(findMSB(n), 0);
#else
    if (n <= 1) return 0;
    int k = int(log2(float(n)));  // may be one off at powers of two
    if ((1 << k) > n) k -= 1;
    if ((2 << k) <= n) k += 1;
    return k;
#endif
}

// The level whose windows hold a footprint of finest texels lo..hi (lo <= hi per axis):
// the finest level k at which it spans at most one level-k texel boundary per axis. A
// span of d texels does once d < 2^k, so with m = floor(log2 d) that is m or m + 1.
int mr_windowLevel(mr_Relief relief, ivec2 lo, ivec2 hi) {
    ivec2 span = hi - lo;
    int level = mr_floorLog2(max(span.x, span.y));
    if (any(greaterThan((hi >> level) - (lo >> level), ivec2(1)))) level += 1;
    return min(level, relief.map.levelCount - 1);
}

// The bound of the pyramid over the finest texels lo..hi: one texel of the overlapping
// pyramid `windows` (texel (p, q) of level k: the max over finest texels
// [p 2^k, (p+2) 2^k) x [q 2^k, (q+2) 2^k)), the window at the lower corner of the
// footprint, at the level of detail the footprint chooses (mr_windowLevel). The footprint
// lies inside that window, so the bound is conservative, and one textureLod reads it, as
// the paper has it. The last window of a row or column holds what lies past it (its last
// block reaches to the map's edge), so the index is clamped to the level. `level` is set
// to the level read.
float mr_windowOver(mr_Relief relief, MICRORELIEF_SAMPLER windows, ivec2 lo, ivec2 hi, out int level) {
    level = mr_windowLevel(relief, lo, hi);
    ivec2 last = max(ivec2(1), relief.map.pyramidSize >> level) - 1;
    return mr_pyramidTexel(relief, windows, min(lo >> level, last), level);
}

#if MICRORELIEF_TILING
// The bound over the finest texels lo..hi of a tiled map (lo <= hi; hi.x may pass the
// map's width round a curved base): taken into the tile, per axis the texels of one tile
// they cover, or the whole tile where they span one; the window over that rectangle, the
// pyramid's finest level bounding each tile's texel squares across its seams (MaxPyramid's
// tiled addressing). A footprint that crosses a seam between tiles covers the end of one
// tile and the start of the next: it reads the tile's top, one fetch and no branch (the
// tighter bound, the windows over both parts, cost a software rasteriser all four reads
// on every segment, 2.2x the untiled time where this costs 1.7x on llvmpipe; the looser
// bound only sends the few segments that cross a seam a level or two further down). So a
// view costs the levels the tiles add above a tile, and no more.
float mr_tiledWindows(mr_Relief relief, MICRORELIEF_SAMPLER windows, ivec2 lo, ivec2 hi, out int level) {
    ivec2 tile = ivec2(mr_tileSize(relief.map));
    ivec2 span = hi - lo;
    ivec2 a = lo - tile * (lo / tile), b = a + span;
    if (span.x >= tile.x - 1) {
        a.x = 0;
        b.x = tile.x - 1;
    }
    if (span.y >= tile.y - 1) {
        a.y = 0;
        b.y = tile.y - 1;
    }
    bool split = any(greaterThanEqual(b, tile));
    return mr_windowOver(relief, windows, split ? ivec2(0) : a, split ? tile - 1 : b, level);
}
#endif

// The bound over a segment's footprint, the map rectangle [lo, hi] (base_surface.glsl):
// the window that holds its texels; where u wraps (a curved base), a rectangle that reaches
// past X = W wraps across the seam, and the larger of the windows over its two parts,
// [lo.x, W) and [0, hi.x - W], bounds it (two fetches, for the segments that cross it).
float mr_footprintBound(mr_Relief relief, MICRORELIEF_SAMPLER windows, vec2 lo, vec2 hi, out int level) {
#if MICRORELIEF_TILING
    ivec2 tlo = mr_finestTexelAt(relief, lo), thi = mr_finestTexelAt(relief, hi);
#if MICRORELIEF_BASE_WRAPS_U
    if (hi.x >= relief.map.size.x) thi.x = int(floor(hi.x));  // past the seam: the tile's period takes it round
#endif
    return mr_tiledWindows(relief, windows, tlo, thi, level);
#else
#if MICRORELIEF_BASE_WRAPS_U
    if (hi.x >= relief.map.size.x) {
        ivec2 tlo = mr_finestTexelAt(relief, lo), thi = mr_finestTexelAt(relief, hi - vec2(relief.map.size.x, 0.0));
        float right = mr_windowOver(relief, windows, tlo, ivec2(int(relief.map.size.x) - 1, thi.y), level);
        return max(right, mr_windowOver(relief, windows, ivec2(0, tlo.y), thi, level));
    }
#endif
    return mr_windowOver(relief, windows, mr_finestTexelAt(relief, lo), mr_finestTexelAt(relief, hi), level);
#endif
}

#endif
