// relief_hit.glsl: the answer every relief tracer of the library gives (mr_ReliefHit), and
// the pieces they share to fill it: the ray's interval in the relief's bounding shell
// (base_surface.glsl), the empty answer, a hit on a side wall, the bottom face or a cap
// where the ray enters, a hit on the top surface (relief_patch.glsl) with its normal, and
// how an exact walk ends (mr_finishWalk: the multilevel, maxmip and cone tracers').
//
// Inputs are in the base's frame (relief_map.glsl): map space on the plane, the canonical
// frame on a curved base; t is the ray parameter, the same in world and frame. The normal
// a hit carries is in the frame and not unit (mr_baseTopNormal, mr_baseFaceNormal);
// mr_reliefWorldNormal() turns it into a world unit vector.
#ifndef MICRORELIEF_RELIEF_HIT_GLSL
#define MICRORELIEF_RELIEF_HIT_GLSL

#include "base_surface.glsl"
#include "relief_map.glsl"
#include "relief_patch.glsl"
#include "relief_query.glsl"
#include "texture_reads.glsl"

struct mr_ReliefHit {
    int kind;         // MR_RELIEF_MISS, MR_RELIEF_TOP, ... (relief_map.glsl)
    float t;          // ray parameter of the hit (the same in world and frame)
    vec3 position;    // the hit point in the base's frame
    vec3 normal;      // outward normal in the frame, not unit: use mr_reliefWorldNormal
    int iterations;   // segments visited
    int stopLevel;    // pyramid level of the last segment examined
    bool exhausted;   // the iteration budget ran out: the result is not trustworthy
};

// No hit yet, nothing read.
mr_ReliefHit mr_reliefMissHit() {
    mr_ReliefHit hit;
    hit.kind = MR_RELIEF_MISS;
    hit.t = -1.0;
    hit.position = vec3(0.0);
    hit.normal = vec3(0.0, 0.0, 1.0);
    hit.iterations = 0;
    hit.stopLevel = -1;
    hit.exhausted = false;
    return hit;
}

// Fills `hit` as a hit on the top surface at parameter t, in the patch `cellPatch` of `cell`.
void mr_setTopHit(inout mr_ReliefHit hit, mr_Relief relief, vec3 origin, vec3 dir, float t, mr_ReliefPatch cellPatch, ivec2 cell) {
    hit.kind = MR_RELIEF_TOP;
    hit.t = t;
    hit.position = origin + t * dir;
    hit.normal = mr_baseTopNormal(relief, hit.position, mr_reliefSlope(relief, cellPatch, cell, mr_baseMapPoint(relief, hit.position).xy));
}

// A top-surface hit reported at frame point `position` with ray parameter `t`, the normal
// taken from the surface's gradient there (what a normal map would give).
void mr_setTopHitAt(inout mr_ReliefHit hit, mr_Relief relief, MICRORELIEF_SAMPLER heights, float t, vec3 position) {
    ivec2 cell = mr_patchCellAt(relief, mr_baseMapPoint(relief, position).xy);
    // mr_setTopHit with a zero direction reports `position` itself.
    mr_setTopHit(hit, relief, position, vec3(0.0), 0.0, mr_patchAt(relief, heights, cell), cell);
    hit.t = t;
}

// A top-surface hit of a tracer that works in map space (X, Y, h) whatever the base: the
// step-based peers, which march in the tangent frame of the base (on a curved base blind
// to its curvature: relief.frag maps their answer onto the base). `mapPoint` is reported
// with the map-space normal (-dh/dX, -dh/dY, 1) of the bilinear surface there. On the
// plane, map space is the frame, and this is mr_setTopHitAt.
void mr_setMapTopHitAt(inout mr_ReliefHit hit, mr_Relief relief, MICRORELIEF_SAMPLER heights, float t, vec3 mapPoint) {
    ivec2 cell = mr_patchCellAt(relief, mapPoint.xy);
    vec2 g = mr_reliefSlope(relief, mr_patchAt(relief, heights, cell), cell, mapPoint.xy);
    hit.kind = MR_RELIEF_TOP;
    hit.t = t;
    hit.position = mapPoint;
    hit.normal = vec3(-g, 1.0);
}

// The end of an exact walk over start + t dir, t in [0, tExit], that found no hit: a ray
// that leaves the plane's box through its floor hits it at the exit point (where the
// surface is 0). The exact root lies right at the end of the walk, where rounding can push
// it out of the last leaf's range; this is where it is caught. Any other ray misses.
void mr_setWalkEndHit(inout mr_ReliefHit hit, mr_Relief relief, MICRORELIEF_SAMPLER heights, vec3 start, vec3 dir, float tExit,
                   bool floorExit) {
    if (floorExit) mr_setTopHitAt(hit, relief, heights, tExit, start + tExit * dir);
}

// A ray entering the shell through a side wall, the bottom face or a cap at a point on or
// under the surface, within the query's range, hits the solid right there. True, with
// `hit` filled, in that case.
bool mr_entryFaceHit(mr_Relief relief, MICRORELIEF_SAMPLER heights, vec3 origin, vec3 dir, float tEnter, int entryFace,
                  float tMin, inout mr_ReliefHit hit) {
    if (tEnter < tMin || entryFace == MR_RELIEF_MISS) return false;
    vec3 entry = origin + tEnter * dir;
    vec3 m = mr_baseMapPoint(relief, entry);
    bool throughBottom = entryFace == MR_RELIEF_BOTTOM;  // h = 0: always in the solid
    if (!throughBottom && m.z > mr_reliefHeight(relief, heights, m.xy)) return false;
    hit.kind = entryFace;
    hit.t = tEnter;
    hit.position = entry;
    hit.normal = mr_baseFaceNormal(relief, entryFace, entry, dir);
    hit.stopLevel = 0;
    return true;
}

// The start every exact tracer shares. Clips the ray to the relief's bounding shell and to
// the query's range [tMin, tMax]. When the ray comes in from outside through a side wall,
// the bottom face or a cap at a point on or under the surface, fills `hit` with that entry
// (the solid is hit right there; entering through the top face or the curved shell is a
// question for the traversal). A range that starts inside the shell at a point in the
// solid (an eye under the surface, a shadow ray started on it) is hit at that start: the
// traversal finds it with no test of its own, the start lying under every bound and each
// leaf solver reporting the first point of its stretch in the solid, its start included
// (a GL test holds every base and last level to it). Returns true when there is a segment left to trace: `start` is
// where the range enters the shell, and the ray goes on as start + t dir for t in
// [0, span]; its parameter from the ray's origin is tStart + t. Working from the entry
// keeps positions near the relief exact however far away the eye is. `floorExit`: the
// ray leaves the plane's box through the floor going down within the range
// (mr_setWalkEndHit).
bool mr_enterReliefShell(mr_Relief relief, mr_RayQuery query, MICRORELIEF_SAMPLER heights, vec3 origin, vec3 dir,
                         inout mr_ReliefHit hit, out vec3 start, out float tStart, out float span,
                         out bool floorExit) {
    int entryFace;
    vec2 range = mr_baseClipToShell(relief, origin, dir, entryFace, floorExit);
    tStart = max(range.x, query.tMin);
    float tEnd = min(range.y, query.tMax);
    floorExit = floorExit && tEnd == range.y;
    span = tEnd - tStart;
    start = origin + tStart * dir;
    if (span < 0.0) return false;
    return !mr_entryFaceHit(relief, heights, origin, dir, range.x, entryFace, query.tMin, hit);
}

// A hit at `t` (from `start`, as mr_measureFromEye will count it) as an any-hit query
// reports it: the point, no normal.
void mr_setAnyHit(inout mr_ReliefHit hit, vec3 start, vec3 dir, float t) {
    hit.kind = MR_RELIEF_TOP;
    hit.t = t;
    hit.position = start + t * dir;
}

// Where an exact walk (the multilevel, maxmip and cone walks) stands when it stops, filled
// as it goes and read by mr_finishWalk.
struct mr_WalkEnd {
    int iterations;            // segments, nodes or texels visited (the query's budget)
    bool finished;             // the walk ran to its end or to a hit; false: out of iterations
    bool solved;               // a leaf solved the hit exactly, on `cellPatch` of `cell`
    float tHit;                // ray parameter of the hit (from the walk's start); < 0: none
    mr_ReliefPatch cellPatch;  // the patch that solved it (when `solved`)
    ivec2 cell;                // that patch's cell, in map samples
};

// A walk about to start: nothing visited, no hit.
mr_WalkEnd mr_walkEnd() {
    mr_WalkEnd end;
    end.iterations = 0;
    end.finished = false;
    end.solved = false;
    end.tHit = -1.0;
    return end;
}

// How an exact walk over start + t dir, t in [0, tEnd], ends: the multilevel, maxmip and cone
// walks' common last step. Out of iterations before the walk `finished`, the answer is not
// trustworthy (exhausted). Otherwise a hit at tHit >= 0: as an any-hit query reports it, or
// with its normal, from the patch that solved it (`solved`), else from the surface there (a
// hit no patch solved: the multilevel method's level of detail, mr_baseDescendTo); or no hit
// before tEnd (mr_setWalkEndHit).
void mr_finishWalk(inout mr_ReliefHit hit, mr_Relief relief, mr_RayQuery query, MICRORELIEF_SAMPLER heights, vec3 start,
                   vec3 dir, float tEnd, bool floorExit, mr_WalkEnd end) {
    hit.iterations = end.iterations;
    if (!end.finished) {
        hit.exhausted = true;
    } else if (query.anyHit && end.tHit >= 0.0) {
        mr_setAnyHit(hit, start, dir, end.tHit);
    } else if (end.solved) {
        mr_setTopHit(hit, relief, start, dir, end.tHit, end.cellPatch, end.cell);
    } else if (end.tHit >= 0.0) {
        mr_setTopHitAt(hit, relief, heights, end.tHit, start + end.tHit * dir);
    } else {
        mr_setWalkEndHit(hit, relief, heights, start, dir, tEnd, floorExit);  // past the walk's end
    }
}

// A hit found from `start` (mr_enterReliefShell) as a parameter from the eye.
void mr_measureFromEye(inout mr_ReliefHit hit, float tStart) {
    if (hit.kind != MR_RELIEF_MISS) hit.t += tStart;
}

// The world-space unit normal of a hit.
vec3 mr_reliefWorldNormal(mr_Relief relief, mr_ReliefHit hit) { return mr_baseWorldNormal(relief, hit.normal); }

#endif
