// segment_walk.glsl: the walk over the binary subdivision of a ray segment (Vyatkin &
// Romaniuk, section III, eq. 8, fig. 5-6) that the multilevel traversal
// (multilevel_trace.glsl: mr_subdivideSegment) and the soft shadow (shadow.glsl:
// mr_softShadow) share: naming the segments, placing one on the ray, its footprint and
// bound, the leaf test, descending into a half and stepping on. What a walk does with a
// segment (discard it, descend, solve a leaf, measure a penumbra) is its own; the
// mechanics are here once, so the two walks visit segments by the same rules.
//
// GLSL has no recursion. A segment is named by its depth d and index k along the root
// (t range [k, k+1] / 2^d of the root's), and the in-order walk needs no stack: after a
// segment is done, k + 1 names the next one at depth d, or, halved, its parent. The state
// is a small struct passed inout; the compilers inline every call, so it costs nothing
// over the loop's own variables.
#ifndef MICRORELIEF_SEGMENT_WALK_GLSL
#define MICRORELIEF_SEGMENT_WALK_GLSL

#include "base_surface.glsl"
#include "max_pyramid.glsl"
#include "relief_map.glsl"
#include "texture_reads.glsl"

// Deeper than any footprint needs (2^24 texels); segment ends stay exact in float.
#ifndef MICRORELIEF_MAX_DEPTH
#define MICRORELIEF_MAX_DEPTH 24
#endif

// The subdivision stops at segments whose footprint is at most this many texels wide and
// solves them exactly against the patches they cross (mr_baseIntersectLeaf). 1 is the
// paper's order (down to the finest level); a few texels cost fewer segments and fewer
// leaves for the same exact hit (docs/performance.md: 4 was the best across map sizes).
#ifndef MICRORELIEF_LEAF_TEXELS
#define MICRORELIEF_LEAF_TEXELS 4.0
#endif

// A segment's bound when its parent's is not known (the root, and a near half reached
// from the far half before it).
const float MR_NO_BOUND = 3.4e38;

// A walk over the subdivision of the segment [0, span] of a ray: the current segment and
// what the next step needs.
struct mr_SegmentWalk {
    int depth;          // the segment's name: t in [index, index + 1] * span / 2^depth
    uint index;
    float parentBound;  // a bound over the parent's path, so over this segment's too (MR_NO_BOUND: not known)
    float ta, tb;       // the segment's ends in t, set by mr_walkFootprint
    // The last segment's ends and what the footprint needs of them (mr_baseEnd, curved
    // bases: transcendental): the walk's next segment starts where the last one started
    // (its near half) or ended.
    float lastA, lastB;
    vec3 endA, endB;
};

// The walk at the root, the whole segment, its bound not known.
mr_SegmentWalk mr_segmentWalk() {
    return mr_SegmentWalk(0, 0u, MR_NO_BOUND, 0.0, 0.0, -1.0, -1.0, vec3(0.0), vec3(0.0));
}

// Places the walk's segment on the ray start + t dir, t in [0, span] (walk.ta, walk.tb), and
// returns its footprint (mr_baseFootprintOf). The ends are integer positions along the root
// in units of 2^-MICRORELIEF_MAX_DEPTH: the float conversions and the power-of-two scale
// are exact, so neighbouring segments share their end parameter bit for bit and no gap
// can open between them.
mr_BaseFootprint mr_walkFootprint(mr_Relief relief, inout mr_SegmentWalk walk, vec3 start, vec3 dir, float span) {
    const float kUnit = 1.0 / float(1 << MICRORELIEF_MAX_DEPTH);
    int shift = MICRORELIEF_MAX_DEPTH - walk.depth;
    walk.ta = span * (float(walk.index << shift) * kUnit);
    walk.tb = span * (float((walk.index + 1u) << shift) * kUnit);
    // A curved path: its ends cost a map point each, kept.
#if !MICRORELIEF_BASE_STRAIGHT_PATH
    vec3 ea = walk.ta == walk.lastA ? walk.endA : walk.ta == walk.lastB ? walk.endB : mr_baseEnd(relief, start + walk.ta * dir);
    vec3 eb = walk.tb == walk.lastB ? walk.endB : mr_baseEnd(relief, start + walk.tb * dir);
    walk.lastA = walk.ta;
    walk.lastB = walk.tb;
    walk.endA = ea;
    walk.endB = eb;
#else
    vec3 ea = start + walk.ta * dir, eb = start + walk.tb * dir;  // on the plane, the ends are all
#endif
    return mr_baseFootprintOf(relief, start, dir, walk.ta, walk.tb, ea, eb);
}

// The segment's bound: the pyramid's over its footprint, one window at the level the
// footprint chooses (paper, fig. 6; two where a curved base's footprint crosses the
// seam), and no more than its parent's.
float mr_walkBound(mr_Relief relief, MICRORELIEF_SAMPLER windows, mr_SegmentWalk walk, mr_BaseFootprint footprint,
                   out int level) {
    return min(walk.parentBound, mr_footprintBound(relief, windows, footprint.lo, footprint.hi, level));
}

// Whether the segment is a leaf, to be solved exactly rather than split: its footprint at
// most MICRORELIEF_LEAF_TEXELS wide, or the walk at its deepest.
bool mr_walkAtLeaf(mr_SegmentWalk walk, mr_BaseFootprint footprint) {
    vec2 extents = footprint.hi - footprint.lo;
    return max(extents.x, extents.y) <= float(MICRORELIEF_LEAF_TEXELS) || walk.depth >= MICRORELIEF_MAX_DEPTH;
}

// Down into the segment's near half (eq. 8: Pn_i = Pn_i-1, Pf_i = (Pn_i-1 + Pf_i-1) / 2),
// or its far half with `farHalf`; `bound` (the segment's) becomes the parent's.
void mr_walkDescend(inout mr_SegmentWalk walk, float bound, bool farHalf) {
    walk.depth += 1;
    walk.index = 2u * walk.index + (farHalf ? 1u : 0u);
    walk.parentBound = bound;
}

// Past the segment, done with: on to index + 1 at this depth. After a near half that is
// its sibling, under the same parent. After a far half it is a near half under another
// parent, whose bound is not known, and the walk climbs to that parent, twice as long,
// when `climb` says so. False past the root's end.
bool mr_walkNext(inout mr_SegmentWalk walk, bool climb) {
    bool farHalf = (walk.index & 1u) == 1u;
    walk.index += 1u;
    if ((walk.index >> walk.depth) != 0u) return false;
    if (farHalf) {
        walk.parentBound = MR_NO_BOUND;
        if (climb) {
            walk.index >>= 1;
            walk.depth -= 1;
        }
    }
    return true;
}

#endif
