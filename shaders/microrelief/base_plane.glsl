// base_plane.glsl: the plane y = 0 as a base surface (base_surface.glsl; the C++ copy is
// src/base/PlaneSurface.cpp). Its frame is map space (map_space.glsl), where the ray is a
// straight line in (X, Y, h): a segment's footprint is the rectangle of its ends, its
// lowest height the lower end, the bounding shell the box [0, W] x [0, H] x [0, maxHeight],
// and the leaf's patches are met along a straight path (mr_planeIntersectLeaf).
#ifndef MICRORELIEF_BASE_PLANE_GLSL
#define MICRORELIEF_BASE_PLANE_GLSL

#include "bilinear_patch.glsl"
#include "map_space.glsl"
#include "relief_map.glsl"
#include "texture_reads.glsl"

// Ray against the box [0, W] x [0, H] x [0, maxHeight]: the parameter interval inside
// it, and which slab the entry and the exit cross (0: X, 1: Y, 2: h). Empty when x > y.
// Under a curved base (the step-based peers' local frame, layer_march.glsl) X wraps and
// has no walls.
vec2 mr_clipToReliefBox(mr_Relief relief, vec3 origin, vec3 dir, out int entryAxis, out int exitAxis) {
    vec3 lo = vec3(0.0), hi = vec3(relief.map.size, relief.map.maxHeight);
    float tEnter = -1e30, tExit = 1e30;
    entryAxis = -1;
    exitAxis = -1;
    for (int axis = MICRORELIEF_BASE != 0 ? 1 : 0; axis < 3; ++axis) {
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

// The box as the bounding shell: the face the ray enters through (a wall, the bottom, or
// MR_RELIEF_MISS for the top face, where the traversal starts) and whether it leaves through
// the floor going down (it meets h = 0, inside the solid, there).
vec2 mr_planeClipToShell(mr_Relief relief, vec3 origin, vec3 dir, out int entryFace, out bool floorExit) {
    int entryAxis, exitAxis;
    vec2 range = mr_clipToReliefBox(relief, origin, dir, entryAxis, exitAxis);
    entryFace = entryAxis == 0   ? MR_RELIEF_WALL_X
                : entryAxis == 1 ? MR_RELIEF_WALL_Y
                : entryAxis == 2 && dir.z > 0.0 ? MR_RELIEF_BOTTOM
                                                : MR_RELIEF_MISS;
    floorExit = exitAxis == 2 && dir.z < 0.0;
    return range;
}

// The footprint of a segment from its ends pa, pb (map points).
mr_BaseFootprint mr_planeFootprint(vec3 pa, vec3 pb) {
    return mr_BaseFootprint(min(pa.xy, pb.xy), max(pa.xy, pb.xy), min(pa.z, pb.z), abs(pb.z - pa.z));
}

float mr_planeLowest(vec3 origin, vec3 dir, float ta, float tb) {
    return min(origin.z + ta * dir.z, origin.z + tb * dir.z);
}

// The first t in [ta, tb] at which the ray is at or below height h (ta if it starts so).
float mr_planeDescendTo(vec3 origin, vec3 dir, float ta, float tb, float h) {
    return dir.z < 0.0 ? clamp((h - origin.z) / dir.z, ta, tb) : ta;
}

// Where the straight path crosses the cell boundary X = boundary (Y = boundary), any t; 1e30
// where it runs parallel to it.
float mr_planeCrossX(vec3 origin, vec3 dir, float boundary) {
    return dir.x == 0.0 ? 1e30 : (boundary - origin.x) / dir.x;
}
float mr_planeCrossY(vec3 origin, vec3 dir, float boundary) {
    return dir.y == 0.0 ? 1e30 : (boundary - origin.y) / dir.y;
}

// Frame point q moved `by` map units of height up (map space: h itself).
vec3 mr_planeRaise(vec3 q, float by) { return vec3(q.xy, q.z + by); }

// Map space normals: (-dh/dX, -dh/dY, 1) on top, the axis of a face.
vec3 mr_planeTopNormal(vec2 gradient) { return vec3(-gradient, 1.0); }

vec3 mr_planeFaceNormal(int face, vec3 dir) {
    int axis = face == MR_RELIEF_WALL_X ? 0 : face == MR_RELIEF_WALL_Y ? 1 : 2;
    vec3 n = vec3(0.0);
    n[axis] = dir[axis] > 0.0 ? -1.0 : 1.0;
    return n;
}

// A map-space normal in object space: the inverse transpose of G's scales, (X, Y, h) ->
// (x, z, y); not unit.
vec3 mr_planeObjectNormal(mr_Relief relief, vec3 n) {
    float texelsPerUnit = max(relief.map.size.x, relief.map.size.y);
    return vec3(n.x * texelsPerUnit, n.z / relief.placement.heightScale, n.y * texelsPerUnit);
}

// Exact first hit on the bilinear surface along [ta, tb], or -1 (the plane's own leaf for
// the bilinear surface; the biquadratic one walks texel squares, base_surface.glsl): the
// patches (cells
// between four samples) the segment crosses, in ray order, each solved as a quadratic,
// from one cell to its neighbour across the boundary the ray meets first (a 2D DDA, as
// in the reference tracer). Neighbouring patches share an edge (mr_neighbourCorners).
// `corners` and `cell` are the patch of the hit.
float mr_planeIntersectLeaf(mr_Relief relief, MICRORELIEF_SAMPLER heights, vec3 origin, vec3 dir, float ta, float tb,
                         out vec4 corners, out ivec2 cell) {
    cell = mr_cellAt((origin + ta * dir).xy);
    ivec2 lastCell = mr_cellAt((origin + tb * dir).xy);
    ivec2 toward = ivec2(sign(vec2(lastCell - cell)));
    ivec2 cells = abs(lastCell - cell);
    corners = mr_cellCorners(relief, heights, cell);
    float t0 = ta;
    for (int piece = 0; piece <= cells.x + cells.y; ++piece) {
        // Where the ray leaves this cell towards lastCell, per axis (tb: it does not).
        vec2 exits = vec2(tb);
        for (int axis = 0; axis < 2; ++axis) {
            if (cell[axis] != lastCell[axis] && dir[axis] != 0.0) {
                float boundary = float(cell[axis] + max(toward[axis], 0)) + 0.5;
                exits[axis] = clamp((boundary - origin[axis]) / dir[axis], t0, tb);
            }
        }
        float t1 = min(exits.x, exits.y);
        float tau = mr_intersectPatch(corners, vec2(cell) + 0.5, origin + t0 * dir, dir, t1 - t0);
        if (tau >= 0.0) return t0 + tau;
        if (t1 >= tb) break;
        int axis = exits.x <= exits.y ? 0 : 1;
        corners = mr_neighbourCorners(relief, heights, cell, axis, toward[axis], corners);
        t0 = t1;
    }
    return -1.0;
}

#endif
