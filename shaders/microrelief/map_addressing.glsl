// map_addressing.glsl: which texel of the height texture holds a sample of the map. The
// map's samples are addressed as scene-and-cli.md has it: clamped to the edge beyond the
// map, wrapped round a curved base in X (u); a tiled map (relief_map.glsl,
// MICRORELIEF_TILING) is its N x M larger image, each sample taken from the tile it falls
// in, so that tiles join across their seams as one image's neighbouring texels do.
#ifndef MICRORELIEF_MAP_ADDRESSING_GLSL
#define MICRORELIEF_MAP_ADDRESSING_GLSL

#include "relief_map.glsl"

// The texel holding sample p (integer sample coordinates of the whole map).
ivec2 mr_sampleTexel(mr_Relief relief, ivec2 p) {
    ivec2 count = ivec2(relief.map.size);
#if MICRORELIEF_BASE != 0
    p.x -= count.x * int(floor(float(p.x) / float(count.x)));  // u wraps round the base
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
