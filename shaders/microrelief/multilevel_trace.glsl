// multilevel_trace.glsl: multilevel ray tracing of microrelief by binary subdivision of
// the ray segment (Vyatkin & Romaniuk, section III, eq. 5-8, fig. 5-6).
//
// Inputs, all in the base's frame (base_surface.glsl): the ray origin and direction, the
// overlapping max pyramid (`windows`, max_pyramid.glsl) and the samples
// (bilinear_patch.glsl). Output: the first point t >= 0 of the ray inside the solid: over
// the plane 0 <= h <= h(X, Y) on the map rectangle, on the top surface, a side wall or the
// bottom face; over a curved base the column or the star-shaped body, on its surface or a
// cap.
//
// The segment inside the relief's bounding shell is the root voxel V0 = {Pn, Pf}. Each
// step takes a segment, chooses the level of detail from its (X, Y) footprint, reads
// with one textureLod the max over a window of the pyramid that holds the footprint,
// and discards the segment when its lowest point lies above that max (it cannot hold a
// hit). Otherwise it is split, near half first (eq. 8: Pn_i = Pn_i-1,
// Pf_i = (Pn_i-1 + Pf_i-1) / 2), until the footprint is a few texels wide at most
// (MICRORELIEF_LEAF_TEXELS); there the ray is solved exactly against the bilinear patches
// it crosses (mr_baseIntersectLeaf). The footprint and the lowest point come from the base
// surface (mr_baseFootprint): on the plane the ends of the segment, on a curved base bounds
// of the curve the segment's path draws in (X, Y, h).
//
// GLSL has no recursion. A segment is named by its depth d and index k along the
// root (t range [k, k+1] / 2^d of the root's), and the in-order walk needs no stack:
// after a segment is done, k + 1 names the next one at depth d, or, halved, its parent.
#ifndef MICRORELIEF_MULTILEVEL_TRACE_GLSL
#define MICRORELIEF_MULTILEVEL_TRACE_GLSL

#include "base_surface.glsl"
#include "leaf_walk.glsl"
#include "relief_patch.glsl"
#include "max_pyramid.glsl"
#include "relief_hit.glsl"
#include "relief_map.glsl"
#include "relief_query.glsl"
#include "texture_reads.glsl"

// Deeper than any footprint needs (2^24 texels); segment ends stay exact in float.
#ifndef MICRORELIEF_MAX_DEPTH
#define MICRORELIEF_MAX_DEPTH 24
#endif

// The subdivision stops at segments whose footprint is at most this many texels wide and
// solves them exactly against the patches they cross (mr_baseIntersectLeaf). 1 is the
// paper's order (down to the finest level); a few texels cost fewer segments and fewer
// leaves for the same exact hit (README, "Performance": 4 was the best across map sizes).
#ifndef MICRORELIEF_LEAF_TEXELS
#define MICRORELIEF_LEAF_TEXELS 4.0
#endif

// A segment's bound when its parent's is not known (the root, and a near half reached
// from the far half before it).
const float MR_NO_BOUND = 3.4e38;

// The walk past segment (depth, index), done with: on to index + 1 at this depth. After
// a near half that is its sibling, under the same parent. After a far half it is a near
// half under another parent, whose bound is not known, and the walk climbs to that
// parent, twice as long, when `climb` says so. False past the root's end.
bool mr_nextSegment(inout int depth, inout uint index, inout float parentBound, bool climb) {
    bool farHalf = (index & 1u) == 1u;
    index += 1u;
    if ((index >> depth) != 0u) return false;
    if (farHalf) {
        parentBound = MR_NO_BOUND;
        if (climb) {
            index >>= 1;
            depth -= 1;
        }
    }
    return true;
}

// The binary subdivision of the segment start + t dir, t in [0, span] (`floorExit`: a ray
// that leaves the plane's box through its floor); tStart is the segment's distance from
// the eye in t, for the level-of-detail cone. Fills `hit` with frame positions and local t.
//
// Two loops, one inside the other (the "while-while" shape of Aila and Laine, "Understanding
// the Efficiency of Ray Traversal on GPUs", HPG 2009): the inner one walks segments until
// it reaches a leaf that may hold a hit, the outer one solves that leaf. Pixels that run
// together in SIMD lanes reach their leaves at different steps; with the leaf inside a
// single loop, every step would pay for the leaf of any lane that needs one (llvmpipe runs
// both sides of every branch, a GPU's warp the taken ones), here a block of pixels pays
// for its leaves once per outer pass.
void mr_subdivideSegment(mr_Relief relief, mr_RayQuery query, MICRORELIEF_SAMPLER windows, MICRORELIEF_SAMPLER heights, vec3 start,
                         vec3 dir, float span, float tStart, bool floorExit, inout mr_ReliefHit hit) {
    // Segment ends as integer positions along the root in units of 2^-MAX_DEPTH: the
    // float conversions and the power-of-two scale are exact, so neighbouring segments
    // share their end parameter bit for bit and no gap can open between them.
    const float kUnit = 1.0 / float(1 << MICRORELIEF_MAX_DEPTH);
    int depth = 0;
    uint index = 0u;
    // A bound over the parent's path, so over this segment's too (MR_NO_BOUND: not known).
    float parentBound = MR_NO_BOUND;
    // The outcome, reported after the loops (which keeps their bodies small): a hit at
    // tHit >= 0, solved exactly on the patch `corners` of `cell` or else taken as is.
    bool finished = false, solved = false;
    float tHit = -1.0;
    mr_ReliefPatch corners;
    ivec2 cell;
    int iteration = 0;
    float ta = 0.0, tb = 0.0;  // the current segment
    float leafBound = 0.0;     // the bound of the leaf the inner loop stopped at
    // The last segment's ends and what the footprint needs of them (mr_baseEnd, curved bases:
    // transcendental): the walk's next segment starts where the last one started (its
    // near half) or ended.
    float lastA = -1.0, lastB = -1.0;
    vec3 endA = vec3(0.0), endB = vec3(0.0);
    while (!finished) {
        // Down the walk to a leaf that may hold a hit, or to the walk's end.
        bool atLeaf = false;
        while (iteration < query.maxIterations) {
            iteration += 1;
            int shift = MICRORELIEF_MAX_DEPTH - depth;
            ta = span * (float(index << shift) * kUnit);
            tb = span * (float((index + 1u) << shift) * kUnit);
#if MICRORELIEF_BASE != 0
            vec3 ea = ta == lastA ? endA : ta == lastB ? endB : mr_baseEnd(relief, start + ta * dir);
            vec3 eb = tb == lastB ? endB : mr_baseEnd(relief, start + tb * dir);
            lastA = ta;
            lastB = tb;
            endA = ea;
            endB = eb;
#else
            vec3 ea = start + ta * dir, eb = start + tb * dir;  // on the plane, the ends are all
#endif
            mr_BaseFootprint footprint = mr_baseFootprintOf(relief, start, dir, ta, tb, ea, eb);
            // A segment down to the floor (h = 0, in the solid) may hit; one above its
            // parent's bound cannot; any other is bounded by one window of the pyramid at
            // the level its footprint chooses (paper, fig. 6), two where a curved base's
            // footprint crosses the seam. Only a segment that ends where the ray leaves
            // the plane's box through the floor reaches it; that is tested exactly, since
            // the height there rounds to either side of 0.
            bool mayHit = floorExit && tb == span;
            int level = -1;
            float bound = parentBound;
            if (!mayHit && footprint.lowest <= parentBound) {
                bound = min(bound, mr_footprintBound(relief, windows, footprint.lo, footprint.hi, level));
                hit.stopLevel = level;
                mayHit = footprint.lowest <= bound;
            }
            if (mayHit) {
                if (query.lodCone > 0.0 && level >= 0 && exp2(float(level + 1)) <= query.lodCone * (tStart + ta)) {
                    // Accuracy-controlled level of detail (paper, section II: "under
                    // criterion of required accuracy"): the window read, 2^(level+1)
                    // texels wide, projects to less than the tolerated pixel error, so its
                    // max box stands for the surface here: the hit is where the ray comes
                    // down to it.
                    tHit = mr_baseDescendTo(relief, start, dir, ta, tb, bound);
                    finished = true;
                    break;
                }
                vec2 extents = footprint.hi - footprint.lo;
                if (max(extents.x, extents.y) <= float(MICRORELIEF_LEAF_TEXELS) || depth >= MICRORELIEF_MAX_DEPTH) {
                    atLeaf = true;
                    leafBound = bound;
                    break;
                }
                // Descend into the near half (eq. 8), or straight into the far half when
                // the near one lies wholly above this segment's bound (a falling ray that
                // reaches the bound only past the midpoint).
                depth += 1;
                index *= 2u;
                parentBound = bound;
                if (mr_baseLowest(relief, start, dir, ta, 0.5 * (ta + tb)) > bound) index += 1u;
                continue;
            }
            // Discarded. After a far half the walk climbs when the segment cleared its
            // bound by more than twice its own drop in height, so that the parent likely
            // clears its bound too and crosses empty space in one step; close to the
            // surface it stays at this depth. (The paper's recursion would climb to the
            // coarsest segment starting there, and so near the surface come back down
            // through levels whose bounds seldom reject.)
            if (!mr_nextSegment(depth, index, parentBound, footprint.lowest - bound > 2.0 * footprint.drop)) {
                finished = true;
                break;
            }
        }
        if (!atLeaf) break;  // finished, or out of iterations
        // No hit before the ray comes down to the leaf's bound: solve from there.
        float tFrom = mr_baseDescendTo(relief, start, dir, ta, tb, leafBound);
        tHit = mr_baseIntersectLeaf(relief, heights, start, dir, tFrom, tb, corners, cell);
        if (tHit >= 0.0) {
            finished = solved = true;
        } else if (!mr_nextSegment(depth, index, parentBound, false)) {
            finished = true;
        }
    }
    hit.iterations = iteration;
    if (!finished) {
        hit.exhausted = true;
    } else if (query.anyHit && tHit >= 0.0) {
        mr_setAnyHit(hit, start, dir, tHit);
    } else if (solved) {
        mr_setTopHit(hit, relief, start, dir, tHit, corners, cell);
    } else if (tHit >= 0.0) {
        mr_setTopHitAt(hit, relief, heights, tHit, start + tHit * dir);
    } else {
        mr_setWalkEndHit(hit, relief, heights, start, dir, span, floorExit);  // past the root's end
    }
}

// The first hit of the ray origin + t dir (in the base's frame: mr_baseFramePoint,
// mr_baseFrameVector) with the relief's solid that `query` asks for.
mr_ReliefHit mr_traceMultilevel(mr_Relief relief, mr_RayQuery query, MICRORELIEF_SAMPLER windows, MICRORELIEF_SAMPLER heights,
                                vec3 origin, vec3 dir) {
    mr_ReliefHit hit = mr_reliefMissHit();
    vec3 start;
    float tStart, span;
    bool floorExit;
    if (mr_enterReliefShell(relief, query, heights, origin, dir, hit, start, tStart, span, floorExit)) {
        mr_subdivideSegment(relief, query, windows, heights, start, dir, span, tStart, floorExit, hit);
        mr_measureFromEye(hit, tStart);
    }
    return hit;
}

#endif
