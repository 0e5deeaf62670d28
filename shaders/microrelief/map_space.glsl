// map_space.glsl: the transformation G of the paper (eq. 5-7) between the relief's
// object space over the plane and map space, in one place so that other base surfaces
// (cylinders, ellipsoids: section II, base_curved.glsl) can replace it.
//
// Base surface here: the plane y = 0, object x = (u - 0.5) a, z = (v - 0.5) b, y = s h,
// with a = W / max(W, H), b = H / max(W, H) (the longer side spans one unit).
// G is affine, so a ray keeps its parameter t: object o + t d maps to map o' + t d'. (The
// model transform between object space and the world is base_surface.glsl's.)
#ifndef MICRORELIEF_MAP_SPACE_GLSL
#define MICRORELIEF_MAP_SPACE_GLSL

#include "relief_map.glsl"

// Object point -> map point (X, Y, h).
vec3 mr_objectToMapPoint(mr_Relief relief, vec3 p) {
    float texelsPerUnit = max(relief.map.size.x, relief.map.size.y);
    return vec3(p.x * texelsPerUnit + 0.5 * relief.map.size.x, p.z * texelsPerUnit + 0.5 * relief.map.size.y,
                p.y / relief.placement.heightScale);
}

// Object direction -> map direction (the linear part of G).
vec3 mr_objectToMapVector(mr_Relief relief, vec3 v) {
    float texelsPerUnit = max(relief.map.size.x, relief.map.size.y);
    return vec3(v.x * texelsPerUnit, v.z * texelsPerUnit, v.y / relief.placement.heightScale);
}

// Map point -> object point (G^-1).
vec3 mr_mapToObjectPoint(mr_Relief relief, vec3 m) {
    float unitsPerTexel = 1.0 / max(relief.map.size.x, relief.map.size.y);
    return vec3((m.x - 0.5 * relief.map.size.x) * unitsPerTexel, m.z * relief.placement.heightScale,
                (m.y - 0.5 * relief.map.size.y) * unitsPerTexel);
}

// Ray against the map-space box [0, W] x [0, H] x [0, maxHeight]: the parameter interval
// inside it, and which slab the entry and the exit cross (0: X, 1: Y, 2: h). Empty when
// x > y. The plane's bounding shell (base_plane.glsl), and the step-based peers' box in
// their local frame (layer_march.glsl). `wrapsX`: X wraps, the box has no walls in X (the
// peers' box under a base whose map wraps in u, MICRORELIEF_BASE_WRAPS_U; a parameter, since
// this file comes before the base's, base_surface.glsl).
vec2 mr_clipToReliefBox(mr_Relief relief, vec3 origin, vec3 dir, bool wrapsX, out int entryAxis, out int exitAxis) {
    vec3 lo = vec3(0.0), hi = vec3(relief.map.size, relief.map.maxHeight);
    float tEnter = -1e30, tExit = 1e30;
    entryAxis = -1;
    exitAxis = -1;
    for (int axis = wrapsX ? 1 : 0; axis < 3; ++axis) {
        if (dir[axis] == 0.0) {
            if (origin[axis] < lo[axis] || origin[axis] > hi[axis]) return vec2(1.0, 0.0);
            continue;
        }
        float t0 = (lo[axis] - origin[axis]) / dir[axis];
        float t1 = (hi[axis] - origin[axis]) / dir[axis];
        if (t0 > t1) { float s = t0; t0 = t1; t1 = s; }
        if (t0 > tEnter) { tEnter = t0; entryAxis = axis; }
        if (t1 < tExit) { tExit = t1; exitAxis = axis; }
    }
    return vec2(tEnter, tExit);
}

#endif
