// base_plane.glsl: the plane y = 0 as the base surface (MICRORELIEF_BASE 0), one of the
// files that define base_surface.glsl's set of mr_base* functions (the C++ twin is
// src/core/base/PlaneSurface.cpp). Its frame is map space (map_space.glsl), where the ray is a
// straight line in (X, Y, h): a segment's footprint is the rectangle of its ends, its
// lowest height the lower end, the bounding shell the box [0, W] x [0, H] x [0, maxHeight],
// and a leaf's patches are met along a straight path (leaf_walk.glsl).
#ifndef MICRORELIEF_BASE_PLANE_GLSL
#define MICRORELIEF_BASE_PLANE_GLSL

#include "map_space.glsl"
#include "relief_map.glsl"

// The plane's traits (base_surface.glsl): the map's edges clamp in u and in v, and the
// frame is map space, where the ray's path over the map is the straight line o + t d
// (leaf_walk.glsl solves a leaf's patches as polynomials along it).
#define MICRORELIEF_BASE_WRAPS_U 0
#define MICRORELIEF_BASE_WRAPS_V 0
#define MICRORELIEF_BASE_STRAIGHT_PATH 1

// Object space and the frame: G of the paper (map_space.glsl).
vec3 mr_baseObjectToFrame(mr_Relief relief, vec3 object) { return mr_objectToMapPoint(relief, object); }
vec3 mr_baseObjectToFrameVector(mr_Relief relief, vec3 object) { return mr_objectToMapVector(relief, object); }
vec3 mr_baseFrameToObject(mr_Relief relief, vec3 q) { return mr_mapToObjectPoint(relief, q); }

// A map-space normal in object space: the inverse transpose of G's scales, (X, Y, h) ->
// (x, z, y); not unit.
vec3 mr_baseObjectNormal(mr_Relief relief, vec3 n) {
    float texelsPerUnit = max(relief.map.size.x, relief.map.size.y);
    return vec3(n.x * texelsPerUnit, n.z / relief.placement.heightScale, n.y * texelsPerUnit);
}

// The frame is map space: a point is its own map point, exact (no margin on X and Y).
float mr_baseMapY(mr_Relief relief, vec3 q) { return q.y; }
vec3 mr_baseMapPoint(mr_Relief relief, vec3 q) { return q; }
vec2 mr_baseMapMargin(mr_Relief relief) { return vec2(0.0); }
vec3 mr_baseRaise(mr_Relief relief, vec3 q, float by) { return vec3(q.xy, q.z + by); }

// The box as the bounding shell: the face the ray enters through (a wall, the bottom, or
// MR_RELIEF_MISS for the top face, where the traversal starts) and whether it leaves through
// the floor going down (it meets h = 0, inside the solid, there).
vec2 mr_baseClipToShell(mr_Relief relief, vec3 origin, vec3 dir, out int entryFace, out bool floorExit) {
    int entryAxis, exitAxis;
    vec2 range = mr_clipToReliefBox(relief, origin, dir, MICRORELIEF_BASE_WRAPS_U == 1, entryAxis, exitAxis);
    entryFace = entryAxis == 0   ? MR_RELIEF_WALL_X
                : entryAxis == 1 ? MR_RELIEF_WALL_Y
                : entryAxis == 2 && dir.z > 0.0 ? MR_RELIEF_BOTTOM
                                                : MR_RELIEF_MISS;
    floorExit = exitAxis == 2 && dir.z < 0.0;
    return range;
}

// A segment's end is its map point; the footprint of [ta, tb] the rectangle of its ends
// `ea`, `eb`, its lowest height the lower end's.
vec3 mr_baseEnd(mr_Relief relief, vec3 q) { return q; }

mr_BaseFootprint mr_baseFootprintOf(mr_Relief relief, vec3 origin, vec3 dir, float ta, float tb, vec3 ea, vec3 eb) {
    return mr_BaseFootprint(min(ea.xy, eb.xy), max(ea.xy, eb.xy), min(ea.z, eb.z), abs(eb.z - ea.z));
}

float mr_baseLowest(mr_Relief relief, vec3 origin, vec3 dir, float ta, float tb) {
    return min(origin.z + ta * dir.z, origin.z + tb * dir.z);
}

float mr_baseDescendTo(mr_Relief relief, vec3 origin, vec3 dir, float ta, float tb, float h) {
    return dir.z < 0.0 ? clamp((h - origin.z) / dir.z, ta, tb) : ta;
}

// Y is linear along a line: it never turns.
float mr_baseTurnY(vec3 origin, vec3 dir) { return MR_NEVER; }

// Map space normals: (-dh/dX, -dh/dY, 1) on top, the axis of a face.
vec3 mr_baseTopNormal(mr_Relief relief, vec3 q, vec2 gradient) { return vec3(-gradient, 1.0); }

vec3 mr_baseFaceNormal(mr_Relief relief, int face, vec3 q, vec3 dir) {
    int axis = face == MR_RELIEF_WALL_X ? 0 : face == MR_RELIEF_WALL_Y ? 1 : 2;
    vec3 n = vec3(0.0);
    n[axis] = dir[axis] > 0.0 ? -1.0 : 1.0;
    return n;
}

// Map point m is the frame point; the tangent frame map space's axes.
vec3 mr_baseSurfacePoint(mr_Relief relief, vec3 m) { return m; }

void mr_baseTangentFrame(mr_Relief relief, vec3 m, out vec3 alongX, out vec3 alongY, out vec3 alongH) {
    alongX = vec3(1.0, 0.0, 0.0);
    alongY = vec3(0.0, 1.0, 0.0);
    alongH = vec3(0.0, 0.0, 1.0);
}

// Where the straight path crosses the cell boundary X = boundary (Y = boundary), any t;
// 1e30 where it runs parallel to it. (`after`: the walk's t, which a curved base's needs.)
bool mr_baseXIncreases(vec3 origin, vec3 dir) { return dir.x > 0.0; }

float mr_baseCrossX(mr_Relief relief, vec3 origin, vec3 dir, float boundary, float after) {
    return dir.x == 0.0 ? 1e30 : (boundary - origin.x) / dir.x;
}

float mr_baseCrossY(mr_Relief relief, vec3 origin, vec3 dir, float boundary, float from, float to) {
    return dir.y == 0.0 ? 1e30 : (boundary - origin.y) / dir.y;
}

// The path has no curvature: no piece of a leaf needs to be short to be final.
const float MR_BASE_FINAL_LENGTH = 1e30;

#endif
