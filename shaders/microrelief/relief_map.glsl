// relief_map.glsl: the relief's description, shared by every function of the library.
//
// Map space is where the traversal reads the map: (X, Y) = (u W, v H) are texel
// coordinates of the height map (texel i covers X in [i, i+1], its sample sits at
// X = i + 0.5) and the third coordinate is the height h in map units (object height /
// height scale on the plane, a fraction of the canonical radius on a curved base).
//
// The relief's object space is the world of the scene convention (scene-and-cli.md): the
// base surface and the map over it where the spec puts them. The model transform of
// mr_ReliefPlacement takes it into the world; the tracers take their ray in the world and
// report t, which an affine transform keeps.
//
// The base surface (base_surface.glsl) is chosen by the host with MICRORELIEF_BASE
// (variants.glsl): MR_BASE_PLANE the plane y = 0, MR_BASE_CYLINDER a cylinder,
// MR_BASE_ELLIPSOID an ellipsoid (scene-and-cli.md, "Base surfaces"). The
// traversal runs in the base's frame, where the ray is a straight line with the world's
// t: map space itself on the plane (the relief occupies X in [0, W], Y in [0, H],
// 0 <= h <= h(X, Y)), the canonical frame q = object / frameScale on a curved base.
#ifndef MICRORELIEF_RELIEF_MAP_GLSL
#define MICRORELIEF_RELIEF_MAP_GLSL

#include "variants.glsl"

#ifndef MICRORELIEF_BASE
#define MICRORELIEF_BASE MR_BASE_PLANE
#endif

// The last level's interpolation (relief_patch.glsl): MR_INTERPOLATION_BILINEAR or
// MR_INTERPOLATION_BIQUADRATIC.
#ifndef MICRORELIEF_INTERPOLATION
#define MICRORELIEF_INTERPOLATION MR_INTERPOLATION_BILINEAR
#endif
#include "precision.glsl"

// The relief is three things, each set by whoever knows it:
//  * mr_ReliefMap, the map's data: what the host uploaded (the samples and the two max
//    pyramids, their sizes and levels) and the largest height, the pyramid's top;
//  * mr_ReliefPlacement, where that map sits: over which base surface (the macro
//    MICRORELIEF_BASE and the base's sizes), how high its heights rise, and the model
//    transform that places the relief's object space in the world (any affine map, the
//    paper's M);
//  * mr_RayQuery, what one ray asks of it (relief_query.glsl): a t range, the closest
//    hit or any hit, a budget, a level-of-detail cone.
// mr_Relief holds the first two: the surface every function of the library describes.
struct mr_ReliefMap {
    vec2 size;           // the map's size in texels: W, H, or N W by M H tiled N x M
    ivec2 pyramidSize;   // finest pyramid level size: a tile's W, H (the windows); maxmip W, H rounded up to powers of two
    int levelCount;      // number of pyramid levels, the last one 1x1
    float maxHeight;     // the map's maximum height (the pyramid's top texel), in map units
    ivec2 tiles;         // N, M: the textures hold one tile, size / tiles texels, repeated
                         // N x M times over the base (MICRORELIEF_TILING; else 1, 1)
};

// Tiling (--tile N,M): the map is its tile repeated N x M times, as if the N x M larger
// image made by repeating it had been uploaded, and addressed so (map_addressing.glsl,
// max_pyramid.glsl): a compile-time choice, so that an untiled map's reads stay as they
// were.
#ifndef MICRORELIEF_TILING
#define MICRORELIEF_TILING 0
#endif

// The size of one tile in texels: the textures' size.
vec2 mr_tileSize(mr_ReliefMap map) {
#if MICRORELIEF_TILING
    return map.size / vec2(map.tiles);
#else
    return map.size;
#endif
}

struct mr_ReliefPlacement {
    mat4 objectToWorld;  // the model transform, affine (the last row 0, 0, 0, 1)
    mat4 worldToObject;  // its inverse
    float heightScale;   // s: object height of map height 1 (plane); radius fraction (curved)
    vec3 frameScale;     // curved bases: object size of the canonical frame's unit,
                         // (R, L / 2, R) for a cylinder, (A, B, C) for an ellipsoid
};

struct mr_Relief {
    mr_ReliefMap map;
    mr_ReliefPlacement placement;
};

// A ray parameter that is never reached: a crossing that does not happen, a turn that
// does not exist.
const float MR_NEVER = 1e30;

// What a ray meets: the kinds of mr_ReliefHit (relief_hit.glsl), also naming the face of the
// bounding shell a ray enters through (MR_RELIEF_MISS there: the top face or the curved
// shell, where the traversal starts).
const int MR_RELIEF_MISS = 0;
const int MR_RELIEF_TOP = 1;     // the relief surface
const int MR_RELIEF_WALL_X = 2;  // the plane: a side wall X = 0 or X = W
const int MR_RELIEF_WALL_Y = 3;  // the plane: a side wall Y = 0 or Y = H
const int MR_RELIEF_BOTTOM = 4;  // the plane: the bottom face h = 0
const int MR_RELIEF_CAP = 5;     // the cylinder: a flat cap, y = +-1 in the frame

// What the traversal knows of a segment of the ray (base_surface.glsl): a rectangle of
// map space that holds its path (hi.x may exceed W on a curved base: the rectangle wraps
// across u = 0), its lowest height above the base, and how much its height changes.
struct mr_BaseFootprint {
    vec2 lo;
    vec2 hi;
    float lowest;
    float drop;
};

#endif
