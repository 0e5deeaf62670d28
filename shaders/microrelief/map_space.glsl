// map_space.glsl: the transformation G of the paper (eq. 5-7) between the world frame
// of the base surface and map space, in one place so that other base surfaces
// (cylinders, ellipsoids: section II) can replace it.
//
// Base surface here: the plane y = 0, world x = (u - 0.5) a, z = (v - 0.5) b, y = s h,
// with a = W / max(W, H), b = H / max(W, H) (the longer side spans one world unit).
// G is affine, so a ray keeps its parameter t: world o + t d maps to map o' + t d'.
#ifndef MICRORELIEF_MAP_SPACE_GLSL
#define MICRORELIEF_MAP_SPACE_GLSL

#include "relief_map.glsl"

// World point -> map point (X, Y, h).
vec3 mr_worldToMapPoint(mr_ReliefMap map, vec3 p) {
    float texelsPerUnit = max(map.size.x, map.size.y);
    return vec3(p.x * texelsPerUnit + 0.5 * map.size.x, p.z * texelsPerUnit + 0.5 * map.size.y,
                p.y / map.heightScale);
}

// World direction -> map direction (the linear part of G).
vec3 mr_worldToMapVector(mr_ReliefMap map, vec3 v) {
    float texelsPerUnit = max(map.size.x, map.size.y);
    return vec3(v.x * texelsPerUnit, v.z * texelsPerUnit, v.y / map.heightScale);
}

// Map point -> world point (G^-1).
vec3 mr_mapToWorldPoint(mr_ReliefMap map, vec3 m) {
    float unitsPerTexel = 1.0 / max(map.size.x, map.size.y);
    return vec3((m.x - 0.5 * map.size.x) * unitsPerTexel, m.z * map.heightScale,
                (m.y - 0.5 * map.size.y) * unitsPerTexel);
}

// Map-space surface gradient (dh/dX, dh/dY) -> world normal of y = s h(u, v).
vec3 mr_mapGradientToWorldNormal(mr_ReliefMap map, vec2 gradient) {
    float slope = map.heightScale * max(map.size.x, map.size.y);
    return normalize(vec3(-slope * gradient.x, 1.0, -slope * gradient.y));
}

#endif
