// coarse_start.glsl: work that pixels share (issue 52), a conservative coarse pass. One
// frustum per tile of pixels (shaders/coarse_start.frag: 8 x 8 by default) is walked
// through the overlapping max pyramid (max_pyramid.glsl) by the multilevel method's
// binary subdivision (segment_walk.glsl's naming and stepping), and the first distance t
// where any of the tile's rays may meet the solid is written to a small texture; each
// pixel's multilevel walk then starts there (relief.frag raises its query's tMin to it)
// instead of where its ray enters the bounding box.
//
// The plane base only (its frame is map space, an affine image of the world); the curved
// bases' frames are not, and their tiles would need the path's curvature bounded too:
// later.
//
// Why the start never passes a hit (map units: X, Y in texels, h in map heights; t the
// ray parameter, the same in the world and the frame):
//  * The pixels' rays share the eye o; pixel p's direction is F + nx R + ny U with (nx, ny)
//    affine in the pixel's centre (relief.frag), so over the tile's rectangle of centres it
//    is bilinear in them: a convex combination sum w_i d_i of the four corner pixels'
//    directions d_i (weights (1 - a)(1 - b), a (1 - b), ..., all >= 0, summing to 1). Map
//    space is an affine image of the world on the plane (the model transform, then G:
//    map_space.glsl), which keeps convex combinations, so in the frame too the point at t
//    of pixel p's ray is sum w_i (o + t d_i): at each t, in the quadrilateral of the four
//    corner rays' points.
//  * Over t in [ta, tb] every point of every pixel's ray is then a convex combination of the
//    eight points o + ta d_i, o + tb d_i: inside their hull, so inside the box of their
//    (X, Y) (the footprint) and no lower than the least h of the eight.
//  * A segment [ta, tb] is skipped only when that least h, less a rounding margin, is above
//    the pyramid's bound over the footprint grown by a rounding margin (mr_footprintBound:
//    a window that holds those texels, at least the surface's max over them, bilinear or
//    biquadratic). Every pixel's ray is then above the surface there (and off the map
//    past its edges, where there is no solid): no hit, no side-wall or floor entry (the
//    floor is h = 0 <= every bound). The walk visits segments in order along t, so
//    everything before the segment it stops at was skipped: the start it writes is never
//    after any of the tile's first hits.
//  * The margins cover float rounding between the tile's arithmetic and each pixel's
//    own (its direction, its clip to the box): 1e-5 of the coordinates' magnitude, about
//    a hundred float ulps, plus an absolute 1e-3 texel and 1e-6 of the map's top.
//  * The root segment starts no later than any pixel's entry into the box (per slab, a
//    direction's component lies between the corners' least and greatest: see
//    mr_coarseRange) pulled back by the margin; when the walk skips nothing, the pixel's
//    own start is kept (MR_COARSE_KEEP), so an entry through a side wall is tested as
//    without the pass.
#ifndef MICRORELIEF_COARSE_START_GLSL
#define MICRORELIEF_COARSE_START_GLSL

#include "base_surface.glsl"
#include "max_pyramid.glsl"
#include "relief_map.glsl"
#include "segment_walk.glsl"
#include "texture_reads.glsl"

// Segments a tile's walk visits at most; out of them, it writes the start of the segment
// it stands at (everything before was skipped), which is still safe.
#ifndef MICRORELIEF_COARSE_MAX_STEPS
#define MICRORELIEF_COARSE_MAX_STEPS 64
#endif

// The tile's answers besides a distance: no ray of the tile meets the solid (the pixels'
// range starts past every hit), and nothing skipped (the pixels keep their own start).
const float MR_COARSE_MISS = 3.4e38;
const float MR_COARSE_KEEP = -1.0;

// Relative rounding margin (see above).
const float MR_COARSE_MARGIN = 1e-5;

// The range [x, y] of t that holds every pixel ray's part inside the box [0, W] x [0, H] x
// [0, top], the rays from `origin` along convex combinations of directions whose
// components lie in [dLo, dHi], clipped to [tMin, tMax]; x > y when none meets it. Per
// slab: a ray from below it enters once t D >= lo - o > 0, and D <= dHi, so not before
// (lo - o) / dHi (from above, symmetrically); inside it, a ray going up leaves it by
// (hi - o) / D <= (hi - o) / dLo (going down, symmetrically).
vec2 mr_coarseRange(mr_Relief relief, vec3 origin, vec3 dLo, vec3 dHi, float tMin, float tMax) {
    vec3 lo = vec3(0.0), hi = vec3(relief.map.size, relief.map.maxHeight);
    float tLow = tMin, tHigh = tMax;
    for (int axis = 0; axis < 3; ++axis) {
        float o = origin[axis];
        if (o < lo[axis]) {
            if (dHi[axis] <= 0.0) return vec2(1.0, 0.0);
            tLow = max(tLow, (lo[axis] - o) / dHi[axis]);
        } else if (o > hi[axis]) {
            if (dLo[axis] >= 0.0) return vec2(1.0, 0.0);
            tLow = max(tLow, (hi[axis] - o) / dLo[axis]);
        }
        if (dLo[axis] > 0.0) {
            tHigh = min(tHigh, (hi[axis] - o) / dLo[axis]);
        } else if (dHi[axis] < 0.0) {
            tHigh = min(tHigh, (lo[axis] - o) / dHi[axis]);
        }
    }
    return vec2(tLow, tHigh);
}

// The distance t from which the rays origin + t sum w_i d[i] (w_i >= 0, sum 1; the frame,
// plane base) are to be traced: no point of any of them before it, within [tMin, tMax],
// is in the solid. MR_COARSE_KEEP where nothing was skipped, MR_COARSE_MISS where no ray
// meets the solid in the range. `reads`: the pyramid texels read; `leafLength`: the t length
// of the segment the walk stopped at, the first that may hold a hit (0: out of steps), a
// hint for the pixels' first segment (relief.frag: any first depth walks the same ray).
float mr_coarseStart(mr_Relief relief, MICRORELIEF_SAMPLER windows, vec3 origin, vec3 d[4], float tMin, float tMax,
                     out int reads, out float leafLength) {
    reads = 0;
    leafLength = 0.0;
    vec3 dLo = min(min(d[0], d[1]), min(d[2], d[3]));
    vec3 dHi = max(max(d[0], d[1]), max(d[2], d[3]));
    vec2 range = mr_coarseRange(relief, origin, dLo, dHi, tMin, tMax);
    // Grown by the margin both ways: the pixels clip their rays in their own rounding.
    float tFrom = max(tMin, range.x - MR_COARSE_MARGIN * abs(range.x));
    float tTo = min(tMax, range.y + MR_COARSE_MARGIN * abs(range.y));
    if (!(tFrom <= tTo)) return MR_COARSE_MISS;
    float span = tTo - tFrom;
    vec3 dAbs = max(abs(dLo), abs(dHi));
    float padRef = max(abs(origin.x), abs(origin.y)), hRef = abs(origin.z);
    mr_SegmentWalk walk = mr_segmentWalk();
    const float kUnit = 1.0 / float(1 << MICRORELIEF_MAX_DEPTH);
    for (int step = 0; step < MICRORELIEF_COARSE_MAX_STEPS; ++step) {
        // The segment's ends, as segment_walk.glsl names them: neighbours share theirs
        // bit for bit.
        int shift = MICRORELIEF_MAX_DEPTH - walk.depth;
        float ta = tFrom + span * (float(walk.index << shift) * kUnit);
        float tb = tFrom + span * (float((walk.index + 1u) << shift) * kUnit);
        vec3 lo = origin + ta * d[0], hi = lo;
        vec2 crossLo = (origin + tb * d[0]).xy, crossHi = crossLo;
        for (int i = 0; i < 4; ++i) {
            vec3 a = origin + ta * d[i], b = origin + tb * d[i];
            lo = min(lo, min(a, b));
            hi = max(hi, max(a, b));
            crossLo = min(crossLo, b.xy);
            crossHi = max(crossHi, b.xy);
        }
        float padXY = MR_COARSE_MARGIN * (padRef + tb * max(dAbs.x, dAbs.y)) + 1e-3;
        float padH = MR_COARSE_MARGIN * (hRef + tb * dAbs.z) + 1e-6 * relief.map.maxHeight;
        int level;
        float bound = min(walk.parentBound, mr_footprintBound(relief, windows, lo.xy - padXY, hi.xy + padXY, level));
        reads += 1;
        float clearance = lo.z - padH - bound;
        if (clearance > 0.0) {
            // Skipped: every ray of the tile is above the surface here. Climb, as the
            // pixels' walk does, when the segment cleared its bound by more than twice its
            // drop.
            if (!mr_walkNext(walk, clearance > 2.0 * (hi.z - lo.z))) return MR_COARSE_MISS;
            continue;
        }
        // May hold a hit. Stop where the segment's travel is down to a quarter of the
        // tile's cross-section (halving it would shrink its footprint by an eighth at
        // most: 1.25 measured better than 2 in docs/perf/2026-12-07-coarse-pass.md), or at
        // the pixels' leaf size; else descend into the near half.
        vec2 extent = hi.xy - lo.xy, cross = crossHi - crossLo;
        if (max(extent.x, extent.y) <= max(2.0 * float(MICRORELIEF_LEAF_TEXELS), 1.25 * max(cross.x, cross.y)) ||
            walk.depth >= MICRORELIEF_MAX_DEPTH - 4) {
            leafLength = tb - ta;
            return ta == tFrom ? MR_COARSE_KEEP : ta;
        }
        mr_walkDescend(walk, bound, false);
    }
    // Out of steps: everything before the segment the walk stands at was skipped.
    int shift = MICRORELIEF_MAX_DEPTH - walk.depth;
    float ta = tFrom + span * (float(walk.index << shift) * kUnit);
    return ta == tFrom ? MR_COARSE_KEEP : ta;
}

#endif
