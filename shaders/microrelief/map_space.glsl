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

#endif
