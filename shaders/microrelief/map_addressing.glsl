// map_addressing.glsl: which texel of the height texture holds a sample of the map. The
// map's samples are addressed as scene-and-cli.md has it: clamped to the edge beyond the
// map, wrapped round a curved base in X (u: MICRORELIEF_BASE_WRAPS_U); a tiled map
// (relief_map.glsl, MICRORELIEF_TILING) is its N x M larger image, each sample taken from
// the tile it falls in, so that tiles join across their seams as one image's neighbouring
// texels do.
#ifndef MICRORELIEF_MAP_ADDRESSING_GLSL
#define MICRORELIEF_MAP_ADDRESSING_GLSL

#include "base_surface.glsl"
#include "relief_map.glsl"

// i modulo n, in 0..n - 1 (n > 0), in integers alone: % of non-negative operands only,
// the one case GLSL defines. (It was i - n floor(float(i) / float(n)): exact where division
// is correctly rounded, as on llvmpipe, but GLSL lets division be 2.5 ulp off; the likely
// cause of hits up to 0.84 texels off on an NVIDIA H200 with GLSL 3.30, the biquadratic
// level on a 75-sample-wide map on the sphere, a quotient 75 / 75 just under 1.)
int mr_wrapIndex(int i, int n) {
    return i >= 0 ? i % n : n - 1 - (n - 1 - i) % n;
}

// A map point's X less a cell's origin on a curved base (its local coordinate f.x), taken
// round the base into the turn centred on the cell, [0.5 - W / 2, 0.5 + W / 2): the whole
// cell, [0, 1], for every W >= 2, with no turn taken there (a turn centred on its near edge,
// [-W / 2, W / 2), took a two-sample map's far edge, f.x = 1, to -1: the other corner). The
// quotient stays 1 / 4 or more from an integer there, whatever the division's rounding.
float mr_wrapLocalX(mr_Relief relief, float fx) {
    return fx - relief.map.size.x * floor((fx - 0.5) / relief.map.size.x + 0.5);
}

// The texel holding sample p (integer sample coordinates of the whole map).
ivec2 mr_sampleTexel(mr_Relief relief, ivec2 p) {
    ivec2 count = ivec2(relief.map.size);
#if MICRORELIEF_BASE_WRAPS_U
    p.x = mr_wrapIndex(p.x, count.x);  // u wraps round the base
#else
    p.x = clamp(p.x, 0, count.x - 1);
#endif
    p.y = clamp(p.y, 0, count.y - 1);
#if MICRORELIEF_TILING
    ivec2 tile = ivec2(mr_tileSize(relief.map));
    p -= tile * (p / tile);  // p >= 0 here
#endif
    return p;
}

#endif
