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

// The max of the pyramid over the map-space rectangle [lo, hi] at `level`: every texel
// the rectangle touches is read (at most 2 x 2 when the level comes from
// footprintLevel), never one fetch at its centre, so the bound is conservative.
float footprintMax(ReliefMap map, sampler2D pyramid, vec2 lo, vec2 hi, int level, inout int fetches) {
    ivec2 levelSize = max(ivec2(1), map.pyramidSize >> level);
    float toLevel = exp2(-float(level));
    ivec2 first = clamp(ivec2(floor(lo * toLevel)), ivec2(0), levelSize - 1);
    ivec2 last = clamp(ivec2(floor(hi * toLevel)), ivec2(0), levelSize - 1);
    vec2 texelSize = 1.0 / vec2(levelSize);
    float lod = float(level);
    float bound = 0.0;
    for (int q = first.y; q <= last.y; ++q) {
        for (int p = first.x; p <= last.x; ++p) {
            bound = max(bound, textureLod(pyramid, (vec2(p, q) + 0.5) * texelSize, lod).r);
            fetches += 1;
        }
    }
    return bound;
}

#endif
