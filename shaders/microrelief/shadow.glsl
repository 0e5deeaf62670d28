// shadow.glsl: how much of a light reaches a hit on the relief, by a second trace from
// the hit towards the light through the same tracer (mr_traceMultilevel, an any-hit query
// over the ray's range to the light): hard shadows, exact; and soft ones, estimated from
// the same pyramid for a light of some angular size.
//
// All in the base's frame (relief_map.glsl): the hit's position and normal as the tracer
// reports them (mr_ReliefHit), the direction towards the light from mr_baseFrameVector.
#ifndef MICRORELIEF_SHADOW_GLSL
#define MICRORELIEF_SHADOW_GLSL

#include "base_surface.glsl"
#include "leaf_walk.glsl"
#include "multilevel_trace.glsl"
#include "relief_hit.glsl"
#include "relief_map.glsl"
#include "relief_query.glsl"
#include "segment_walk.glsl"
#include "texture_reads.glsl"

// How far above the surface a shadow ray starts, in map units of height (the plane's h;
// on a curved base the distance from the axis or the centre, less 1, over s): enough that
// the tracer, evaluating the surface and the ray's height at the start again, finds the
// start above the surface, and no more. Two evaluations of one patch at one point differ by
// a few ulp of its samples, under 2^-21 of the largest (MR_PATCH_TOP_MARGIN is 2^-20); on a
// curved base the height (|q| - 1) / s carries a few ulp of the radius 1 + s maxHeight
// (float's 2^-23 of it, over s). Each term is taken 4 to 8 times over; 1e-30 keeps a map
// that is 0 everywhere clear of its floor.
float mr_shadowClearance(mr_Relief relief) {
    float clearance = 2.0 * MR_PATCH_TOP_MARGIN * relief.map.maxHeight + 1e-30;
    // A curved base: the height is a radius, rounded there.
#if !MICRORELIEF_BASE_STRAIGHT_PATH
    float s = relief.placement.heightScale;
    clearance += MR_PATCH_TOP_MARGIN * (1.0 + s * relief.map.maxHeight) / s;
#endif
    return clearance;
}

// Where a shadow ray from a top-surface hit starts: the hit raised along the base's height
// axis until the surface under it lies between one and about two clearances below (one
// round on the plane, where X and Y stay as they are; on a curved base the raised point's
// X and Y may round to a neighbouring float, where the surface differs by its slope times
// that: another round). A point on the surface is in the closed solid, so a ray started
// there would meet its own surface at once; a start any higher passes over occluders that
// the exact ray meets: a start 1/256 of a map unit up (an earlier version: about 0.1 texel
// of world height at scale 0.1 on a 256 map) let light through to 1 % to 2 % of the hits
// under grazing lights (ShadowTest's grazing sweep, from the renderer's own hits).
vec3 mr_shadowRayStart(mr_Relief relief, MICRORELIEF_SAMPLER heights, vec3 position) {
    float clearance = mr_shadowClearance(relief);
    vec3 start = position;
    for (int attempt = 0; attempt < 4; ++attempt) {
        vec3 m = mr_baseMapPoint(relief, start);
        float gap = m.z - mr_reliefHeight(relief, heights, m.xy);
        if (gap >= clearance) break;
        start = mr_baseRaise(relief, start, 2.0 * clearance - gap);
    }
    return start;
}

// Whether a hit that faces the light needs a shadow ray at all: one on a face of the
// bounding shell (a side wall or the bottom of the plane's box, a cylinder's cap) lies on
// a face of a convex shell, and a ray leaving through it never comes back.
bool mr_shadowRayNeeded(mr_ReliefHit hit) { return hit.kind == MR_RELIEF_TOP; }

// 1 where the light reaches `hit` (its frame position and normal), 0 where the relief
// blocks it: a surface facing away from the light (its frame normal against `toLight`)
// is in its own shadow; else an any-hit trace from mr_shadowRayStart along `toLight`,
// t in [0, tMax] (the light at tMax; a directional light at MR_T_INFINITY). `exhausted`
// is set when the shadow ray runs out of its budget (reported, as a primary ray's is).
float mr_hardShadow(mr_Relief relief, MICRORELIEF_SAMPLER windows, MICRORELIEF_SAMPLER heights, mr_ReliefHit hit, vec3 toLight,
                    float tMax, inout bool exhausted) {
    if (dot(hit.normal, toLight) <= 0.0) return 0.0;
    if (!mr_shadowRayNeeded(hit)) return 1.0;
    mr_ReliefHit blocker = mr_traceMultilevel(relief, mr_anyHitQuery(relief.map, 0.0, tMax), windows, heights,
                                              mr_shadowRayStart(relief, heights, hit.position), toLight);
    exhausted = exhausted || blocker.exhausted;
    return blocker.kind == MR_RELIEF_MISS ? 1.0 : 0.0;
}

// The fraction of a disk of unit radius above the line y = -x (x clamped to [-1, 1]): the
// part of a round light left visible by a straight occluding edge x radii below its centre.
float mr_diskAbove(float x) {
    x = clamp(x, -1.0, 1.0);
    return (acos(-x) + x * sqrt(1.0 - x * x)) / 3.14159265;
}

// A soft shadow: an estimate of the fraction of a round light of angular radius atan(tanRadius)
// that reaches `hit`. It approximates the light as seen past a single straight occluding
// edge: the smallest angle m by which the shadow ray (towards the light's centre) clears
// the surface below it, over its whole length, the occluder's edge m below the light's
// centre, and the visible fraction that of a disk cut by a straight line there
// (mr_diskAbove(m / radius)). It takes in what lies under the central ray (a horizon along
// the light's azimuth), not the occluders beside it; the angles are object-space heights
// over distances (`heightToObject`: object units per map unit of height; `objectPerT`: the
// object length of the ray's direction).
//
// The walk is the multilevel traversal's, through the same pieces (segment_walk.glsl:
// mr_SegmentWalk), with the penumbra cone for a hit: a segment whose lowest point clears
// the pyramid's bound by more than the light's radius at its distance cannot change the
// result and is discarded. Here the clearance itself counts, not only whether there is
// one, so every segment reads its bound (the traversal skips the read for a segment that
// clears its parent's), and the walk goes near half first and never climbs. A leaf is
// measured at five points and solved exactly (mr_baseIntersectLeaf), so that a blocked
// ray always counts as below the surface. As the radius goes to 0 every lit point sees the
// whole light and every blocked one none: the hard shadow (a GL test holds it to that).
float mr_softShadow(mr_Relief relief, MICRORELIEF_SAMPLER windows, MICRORELIEF_SAMPLER heights, mr_ReliefHit hit, vec3 toLight,
                    float tMax, float tanRadius, float heightToObject, float objectPerT,
                    inout bool exhausted) {
    if (dot(hit.normal, toLight) <= 0.0) return 0.0;
    if (!mr_shadowRayNeeded(hit)) return 1.0;
    mr_RayQuery query = mr_anyHitQuery(relief.map, 0.0, tMax);
    mr_ReliefHit entry = mr_reliefMissHit();
    vec3 start;
    float tStart, span;
    bool floorExit;
    vec3 from = mr_shadowRayStart(relief, heights, hit.position);
    if (!mr_enterReliefShell(relief, query, heights, from, toLight, entry, start, tStart, span, floorExit)) {
        return entry.kind == MR_RELIEF_MISS ? 1.0 : 0.0;  // out of the shell at once, or in through a wall
    }
    float margin = 3.4e38;  // the smallest clearance angle found so far (tangent)
    float descent = 0.0;    // the last leaf's slope, where it goes down (tangent)
    mr_SegmentWalk walk = mr_segmentWalk();
    for (int iteration = 0; iteration < query.maxIterations; ++iteration) {
        if (margin <= -tanRadius) return 0.0;  // the whole light is behind the surface
        mr_BaseFootprint footprint = mr_walkFootprint(relief, walk, start, toLight, span);
        float ta = walk.ta, tb = walk.tb;
        int level;
        float bound = mr_walkBound(relief, windows, walk, footprint, level);
        // The clearance over this segment is at least (lowest - bound) over the distance
        // (the far end's when that is positive, the near end's when not).
        float clear = footprint.lowest - bound;
        float near = max(tStart + ta, 1e-30) * objectPerT, far = (tStart + tb) * objectPerT;
        float lowestAngle = clear * heightToObject / (clear >= 0.0 ? far : near);
        bool matters = lowestAngle < tanRadius;
        if (matters && !mr_walkAtLeaf(walk, footprint)) {
            mr_walkDescend(walk, bound, false);
            continue;
        }
        if (matters) {
            // A leaf: measured at five points, and solved exactly for a hit.
            float heightA = 0.0, heightB = 0.0;
            for (int k = 0; k <= 4; ++k) {
                float t = mix(ta, tb, 0.25 * float(k));
                vec3 m = mr_baseMapPoint(relief, start + t * toLight);
                float gap = m.z - mr_reliefHeight(relief, heights, m.xy);
                margin = min(margin, gap * heightToObject / max((tStart + t) * objectPerT, 1e-30));
                if (k == 0) heightA = m.z;
                if (k == 4) heightB = m.z;
            }
            // The ray's own slope over the leaf (negative going down): where it leaves
            // through the floor, the light's centre is that far below the floor's horizon.
            descent = min((heightB - heightA) * heightToObject / max((tb - ta) * objectPerT, 1e-30), 0.0);
            mr_ReliefPatch cellPatch;
            ivec2 cell;
            float tHit = mr_baseIntersectLeaf(relief, heights, start, toLight, ta, tb, cellPatch, cell);
            if (tHit >= 0.0) {
                // Blocked, though the five points may all lie above a surface thinner
                // than their spacing: the ray passes at least as far below the occluder as
                // the hit lies below the top of the patch it hit (never above it), so the
                // light's centre is hidden by that angle, and as the light shrinks every
                // blocked ray sees none of it.
                float below = mr_baseMapPoint(relief, start + tHit * toLight).z -
                              mr_patchTop(cellPatch, vec2(0.0), vec2(1.0));
                margin = min(margin, min(below, 0.0) * heightToObject / max((tStart + tHit) * objectPerT, 1e-30));
            }
        }
        if (!mr_walkNext(walk, false)) {
            if (floorExit) margin = min(margin, descent);  // down through the floor
            return mr_diskAbove(margin / tanRadius);
        }
    }
    exhausted = true;
    return mr_diskAbove(margin / tanRadius);
}

#endif
