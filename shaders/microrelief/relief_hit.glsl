// relief_hit.glsl: the answer every relief tracer of the library gives (ReliefHit), and
// the pieces they share to fill it: the ray's interval in the relief's box, the empty
// answer, a hit on a side wall or the bottom face where the ray enters, and a hit on the
// top surface with its normal.
//
// Inputs are in map space (relief_map.glsl): X, Y in texels, h in map height units; t is
// the ray parameter, the same in world and map space. The top normal is the unnormalised
// (-dh/dX, -dh/dY, 1) of the bilinear surface (bilinear_patch.glsl); reliefWorldNormal()
// turns any hit's normal into a world unit vector.
#ifndef MICRORELIEF_RELIEF_HIT_GLSL
#define MICRORELIEF_RELIEF_HIT_GLSL

#include "bilinear_patch.glsl"
#include "map_space.glsl"
#include "relief_map.glsl"

const int RELIEF_MISS = 0;
const int RELIEF_TOP = 1;     // the bilinear top surface
const int RELIEF_WALL_X = 2;  // a side wall X = 0 or X = W
const int RELIEF_WALL_Y = 3;  // a side wall Y = 0 or Y = H
const int RELIEF_BOTTOM = 4;  // the bottom face h = 0

struct ReliefHit {
    int kind;         // RELIEF_MISS, RELIEF_TOP, ...
    float t;          // ray parameter of the hit (the same in world and map space)
    vec3 position;    // map-space hit point
    vec3 normal;      // map-space unit normal for walls and bottom; for the top
                      // surface (-dh/dX, -dh/dY, 1) unnormalised: use surfaceNormal
    int iterations;   // segments visited
    int fetches;      // texels read (pyramid and samples)
    int stopLevel;    // pyramid level of the last segment examined
    bool exhausted;   // the iteration budget ran out: the result is not trustworthy
};

// No hit yet, nothing read.
ReliefHit reliefMissHit() {
    ReliefHit hit;
    hit.kind = RELIEF_MISS;
    hit.t = -1.0;
    hit.position = vec3(0.0);
    hit.normal = vec3(0.0, 0.0, 1.0);
    hit.iterations = 0;
    hit.fetches = 0;
    hit.stopLevel = -1;
    hit.exhausted = false;
    return hit;
}

// Ray against the box [0, W] x [0, H] x [0, maxHeight]: the parameter interval inside
// it, and which slab the entry and the exit cross (0: X, 1: Y, 2: h). Empty when x > y.
vec2 clipToReliefBox(ReliefMap map, vec3 origin, vec3 dir, out int entryAxis, out int exitAxis) {
    vec3 lo = vec3(0.0), hi = vec3(map.size, map.maxHeight);
    float tEnter = -1e30, tExit = 1e30;
    entryAxis = -1;
    exitAxis = -1;
    for (int axis = 0; axis < 3; ++axis) {
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

// Fills `hit` as a hit on the top surface at parameter t, in the patch `cell` with
// corner samples `corners`.
void setTopHit(inout ReliefHit hit, ReliefMap map, vec3 origin, vec3 dir, float t, vec4 corners, ivec2 cell) {
    hit.kind = RELIEF_TOP;
    hit.t = t;
    hit.position = origin + t * dir;
    vec2 g = patchGradient(corners, clamp(hit.position.xy - (vec2(cell) + 0.5), 0.0, 1.0));
    // Clamped border cells are flat across the edge.
    if (cell.x < 0 || cell.x >= int(map.size.x) - 1) g.x = 0.0;
    if (cell.y < 0 || cell.y >= int(map.size.y) - 1) g.y = 0.0;
    hit.normal = vec3(-g, 1.0);
}

// A top-surface hit reported at `position` with ray parameter `t`, the normal taken from
// the bilinear gradient at position.xy (what a normal map would give there). The point
// need not lie on the ray: the offset methods report one that does not.
void setTopHitAt(inout ReliefHit hit, ReliefMap map, sampler2D heights, float t, vec3 position) {
    ivec2 cell = cellAt(position.xy);
    vec4 corners = cellCorners(map, heights, cell, hit.fetches);
    // setTopHit with a zero direction reports `position` itself, with its border rule.
    setTopHit(hit, map, position, vec3(0.0), 0.0, corners, cell);
    hit.t = t;
}

// A ray that leaves the box through its floor going down reaches h = 0 inside the map,
// which belongs to the solid.
bool leavesThroughFloor(vec3 dir, int exitAxis) {
    return exitAxis == 2 && dir.z < 0.0;
}

// The end of an exact walk over start + t dir, t in [0, tExit], that found no hit: a ray
// that leaves through the floor hits it at the exit point (where the surface is 0). The
// exact root lies right at the end of the walk, where rounding can push it out of the
// last leaf's range; this is where it is caught. Any other ray misses.
void setWalkEndHit(inout ReliefHit hit, ReliefMap map, sampler2D heights, vec3 start, vec3 dir, float tExit,
                   int exitAxis) {
    if (leavesThroughFloor(dir, exitAxis)) setTopHitAt(hit, map, heights, tExit, start + tExit * dir);
}

// A ray entering the box through a side wall or the bottom face below the surface hits
// the solid right there (as in traceMultilevel). True, with `hit` filled, in that case.
bool entryFaceHit(ReliefMap map, sampler2D heights, vec3 origin, vec3 dir, float tEnter,
                  int entryAxis, inout ReliefHit hit) {
    if (tEnter < 0.0 || entryAxis < 0 || (entryAxis == 2 && dir.z < 0.0)) return false;
    vec3 entry = origin + tEnter * dir;
    bool throughBottom = entryAxis == 2;  // h = 0: always in the solid
    if (!throughBottom && entry.z > surfaceHeight(map, heights, entry.xy, hit.fetches)) {
        return false;
    }
    hit.kind = entryAxis == 0 ? RELIEF_WALL_X : entryAxis == 1 ? RELIEF_WALL_Y : RELIEF_BOTTOM;
    hit.t = tEnter;
    hit.position = entry;
    hit.normal = vec3(0.0);
    hit.normal[entryAxis] = dir[entryAxis] > 0.0 ? -1.0 : 1.0;
    hit.stopLevel = 0;
    return true;
}

// The start every exact tracer shares. Clips the ray to the relief's box and, when it
// comes in from outside through a side wall or the bottom face at a point below the
// surface, fills `hit` with that entry (the solid is hit right there; entering through
// the top face is a question for the traversal, and from inside the box the eye is above
// the surface, by the spec). Returns true when there is a segment left to trace: `start`
// is where the ray enters the box (or the eye, inside it), and the ray goes on as
// start + t dir for t in [0, span]; its parameter from the eye is tStart + t. Working
// from the entry keeps positions near the box exact however far away the eye is.
bool enterReliefBox(ReliefMap map, sampler2D heights, vec3 origin, vec3 dir, inout ReliefHit hit, out vec3 start,
                    out float tStart, out float span, out int exitAxis) {
    int entryAxis;
    vec2 range = clipToReliefBox(map, origin, dir, entryAxis, exitAxis);
    tStart = max(range.x, 0.0);
    span = range.y - tStart;
    start = origin + tStart * dir;
    if (span < 0.0) return false;
    return !entryFaceHit(map, heights, origin, dir, range.x, entryAxis, hit);
}

// A hit found from `start` (enterReliefBox) as a parameter from the eye.
void measureFromEye(inout ReliefHit hit, float tStart) {
    if (hit.kind != RELIEF_MISS) hit.t += tStart;
}

// The world-space unit normal of a hit.
vec3 reliefWorldNormal(ReliefMap map, ReliefHit hit) {
    if (hit.kind == RELIEF_TOP) return mapGradientToWorldNormal(map, -hit.normal.xy);
    return vec3(hit.normal.x, hit.normal.z, hit.normal.y);  // map (X, Y, h) -> world (x, z, y)
}

#endif
