// relief_map.glsl: the relief's description, shared by every function of the library.
//
// Map space is where the traversal runs: (X, Y) = (u W, v H) are texel coordinates of
// the height map (texel i covers X in [i, i+1], its sample sits at X = i + 0.5) and the
// third coordinate is the height h in map units (world height / height scale). The
// relief occupies X in [0, W], Y in [0, H], 0 <= h <= h(X, Y).
#ifndef MICRORELIEF_RELIEF_MAP_GLSL
#define MICRORELIEF_RELIEF_MAP_GLSL

#include "precision.glsl"

struct ReliefMap {
    vec2 size;           // W, H: height map size in texels
    ivec2 pyramidSize;   // finest pyramid level size (W, H rounded up to powers of two)
    int levelCount;      // number of pyramid levels, the last one 1x1
    float maxHeight;     // the map's maximum height (pyramid top), in map units
    float heightScale;   // s: world height of map height 1
    int maxIterations;   // traversal budget; running out is reported, never silent
    float lodCone;       // accuracy-controlled level of detail: a level-k segment at ray
                         // parameter t may stand for the surface once 2^k <= lodCone * t;
                         // 0 is exact (multilevel_trace.glsl)
};

#endif
