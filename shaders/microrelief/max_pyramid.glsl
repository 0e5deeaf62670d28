// max_pyramid.glsl: reading the multilevel elevation map (paper, section II-III, fig. 6).
//
// `pyramid` is a single-channel float texture whose mip level k holds, per texel, the
// maximum of the bilinear surface over the finest texels it covers, with nearest
// filtering (GL_NEAREST_MIPMAP_NEAREST). Level k texel (p, q) covers map-space
// X in [p 2^k, (p+1) 2^k), Y in [q 2^k, (q+1) 2^k).
#ifndef MICRORELIEF_MAX_PYRAMID_GLSL
#define MICRORELIEF_MAX_PYRAMID_GLSL

#include "relief_map.glsl"

// The level of detail for a footprint `extent` texels wide (paper: 1/2^level < Lp <=
// 1/2^(level+1) in map units): the finest level whose texels are at least that wide,
// so that the footprint touches at most 2 x 2 of them.
int footprintLevel(ReliefMap map, float extent) {
    int level = extent <= 1.0 ? 0 : int(ceil(log2(extent)));
    // log2 of an exact power of two may round up one step; that is conservative (a
    // coarser max), never wrong.
    return min(level, map.levelCount - 1);
}

// The level-`level` texel that holds map point p. Exact integer arithmetic: the finest
// texel index, clamped to the map (not its padding), shifted right by the level.
ivec2 pyramidTexelAt(ReliefMap map, vec2 p, int level) {
    return clamp(ivec2(floor(p)), ivec2(0), ivec2(map.size) - 1) >> level;
}

// How a pyramid texel is read. 0 (default): textureLod at the texel's centre with
// nearest filtering, the ordinary texture path, as the paper has it ("the same mechanism
// as for the usual texture"). 1: texelFetch of the same texel, which skips the sampler's
// coordinate work (a quarter faster on llvmpipe; the same on most GPUs).
#ifndef MICRORELIEF_PYRAMID_TEXEL_FETCH
#define MICRORELIEF_PYRAMID_TEXEL_FETCH 0
#endif

// One pyramid texel.
float pyramidTexel(ReliefMap map, sampler2D pyramid, ivec2 texel, int level, inout int fetches) {
    fetches += 1;
#if MICRORELIEF_PYRAMID_TEXEL_FETCH
    return texelFetch(pyramid, texel, level).r;
#else
    vec2 levelSize = vec2(max(ivec2(1), map.pyramidSize >> level));
    return textureLod(pyramid, (vec2(texel) + 0.5) / levelSize, float(level)).r;
#endif
}

// The bound of the pyramid over the segment from a to b (map points): the max of every
// texel the segment crosses, never a single fetch at its centre, so it is conservative.
// `level` comes in as the footprint level and goes out as the level read:
//  * one fetch when the segment lies in a single texel at `level`, or at the level
//    above (whose texel contains the segment, so its max is a bound too, one level
//    looser): the common case;
//  * otherwise the texels the segment crosses at `level`, two, or three when it passes
//    a corner, since the level is coarse enough for it to span at most two per axis.
float segmentBound(ReliefMap map, sampler2D pyramid, vec2 a, vec2 b, inout int level, inout int fetches) {
    ivec2 ta = pyramidTexelAt(map, a, level), tb = pyramidTexelAt(map, b, level);
    // The footprint level makes |tb - ta| <= 1 per axis; rounding in log2 can leave it
    // one level short, which this restores.
    while (any(greaterThan(abs(tb - ta), ivec2(1))) && level < map.levelCount - 1) {
        level += 1;
        ta = pyramidTexelAt(map, a, level);
        tb = pyramidTexelAt(map, b, level);
    }
    if (ta == tb) return pyramidTexel(map, pyramid, ta, level, fetches);
    if (level + 1 < map.levelCount && (ta >> 1) == (tb >> 1)) {
        level += 1;
        return pyramidTexel(map, pyramid, ta >> 1, level, fetches);
    }
    float bound = max(pyramidTexel(map, pyramid, ta, level, fetches), pyramidTexel(map, pyramid, tb, level, fetches));
    if (ta.x != tb.x && ta.y != tb.y) {
        // Through a corner: the third texel is the one beside ta across whichever
        // boundary the segment crosses first (both differ, so b - a has no zero part).
        vec2 crossing = (vec2(max(ta, tb) << level) - a) / (b - a);
        ivec2 middle = crossing.x < crossing.y ? ivec2(tb.x, ta.y) : ivec2(ta.x, tb.y);
        bound = max(bound, pyramidTexel(map, pyramid, middle, level, fetches));
    }
    return bound;
}

#endif
