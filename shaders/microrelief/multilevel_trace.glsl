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
// The walk's mechanics (naming a segment by depth and index, placing it, its footprint and
// bound, the leaf test, descending, stepping on) are segment_walk.glsl's, shared with the
// soft shadow (shadow.glsl); what it does with each segment is here.
#ifndef MICRORELIEF_MULTILEVEL_TRACE_GLSL
#define MICRORELIEF_MULTILEVEL_TRACE_GLSL

#include "base_surface.glsl"
#include "leaf_walk.glsl"
#include "relief_patch.glsl"
#include "max_pyramid.glsl"
#include "relief_hit.glsl"
#include "relief_map.glsl"
#include "relief_query.glsl"
#include "segment_walk.glsl"
#include "texture_reads.glsl"

#ifdef MICRORELIEF_COARSE_TILE
// The coarse pass's hint (relief.frag, coarse_start.glsl): the t length of the first
// segment that may hold a hit in the pixel's tile; 0: none. The walk then starts at the
// depth whose segments are about that long rather than at the root: segments at any depth,
// walked in order from index 0, cover [0, span] as the root does (mr_walkNext ends past
// the root's end at any depth), so the hit found is the same; the root's bounds above a
// first segment are only read later, where the walk climbs.
float mr_coarseFirstLength = 0.0;
#endif

// The level of detail's normal (the hit that a window's max box stands for): the map
// gradient at map point xy as the windows of level k see it, not the samples'. Windows
// p - 1 and p (p = the level-k block holding xy) are centred at p 2^k and (p + 1) 2^k,
// either side of xy, so their difference over 2^k is the slope along each axis, read from
// the level the walk stopped at. A pixel that cannot tell that level's windows apart
// cannot tell the samples' slope apart either; and this way an LOD frame reads nothing
// finer than its level (a paged map, paged_map.glsl, wants only pages of that level, not
// the samples' page under every pixel). Clamped to the level's windows at the map's edges
// (a slope of 0 there, and in a row's last, partial block and at a curved base's seam
// u = 0); a tiled map's windows are a tile's, so a tile's first block has a slope of 0 too.
// Only the shading normal: the hit's position is the LOD's, as before. The CPU twin (the
// core's MultilevelTracer) has no level of detail, so nothing there matches this.
vec2 mr_lodSlope(mr_Relief relief, MICRORELIEF_SAMPLER windows, vec2 xy, int k) {
    ivec2 texel = mr_finestTexelAt(relief, xy);
#if MICRORELIEF_TILING
    ivec2 tile = ivec2(mr_tileSize(relief.map));
    texel -= tile * (texel / tile);
#endif
    ivec2 last = max(ivec2(1), relief.map.pyramidSize >> k) - 1;
    ivec2 p = clamp(texel >> k, ivec2(0), last), q = clamp((texel >> k) - 1, ivec2(0), last);
    float width = exp2(float(k));
    return vec2(mr_pyramidTexel(relief, windows, ivec2(p.x, q.y), k) - mr_pyramidTexel(relief, windows, q, k),
                mr_pyramidTexel(relief, windows, ivec2(q.x, p.y), k) - mr_pyramidTexel(relief, windows, q, k)) / width;
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
    mr_SegmentWalk walk = mr_segmentWalk();
#ifdef MICRORELIEF_COARSE_TILE
    if (mr_coarseFirstLength > 0.0 && span > mr_coarseFirstLength)
        walk.depth = min(int(log2(span / mr_coarseFirstLength)), MICRORELIEF_MAX_DEPTH - 8);
#endif
    // The outcome, reported after the loops (which keeps their bodies small): a hit at
    // tHit >= 0, solved exactly on a leaf's patch or else taken as is.
    mr_WalkEnd end = mr_walkEnd();
    float leafBound = 0.0;  // the bound of the leaf the inner loop stopped at
    int lodLevel = -1;      // the level whose window stood for the surface (level of detail)
    while (!end.finished) {
        // Down the walk to a leaf that may hold a hit, or to the walk's end.
        bool atLeaf = false;
        while (end.iterations < query.maxIterations) {
            end.iterations += 1;
            mr_BaseFootprint footprint = mr_walkFootprint(relief, walk, start, dir, span);
            // A segment down to the floor (h = 0, in the solid) may hit; one above its
            // parent's bound cannot, and needs no fetch; any other is bounded by the
            // pyramid (mr_walkBound). Only a segment that ends where the ray leaves
            // the plane's box through the floor reaches it; that is tested exactly, since
            // the height there rounds to either side of 0.
            bool mayHit = floorExit && walk.tb == span;
            int level = -1;
            float bound = walk.parentBound;
            if (!mayHit && footprint.lowest <= walk.parentBound) {
                bound = mr_walkBound(relief, windows, walk, footprint, level);
                hit.stopLevel = level;
                mayHit = footprint.lowest <= bound;
            }
            if (mayHit) {
                if (query.lodCone > 0.0 && level >= 0 && exp2(float(level + 1)) <= query.lodCone * (tStart + walk.ta)) {
                    // Accuracy-controlled level of detail (paper, section II: "under
                    // criterion of required accuracy"): the window read, 2^(level+1)
                    // texels wide, projects to less than the tolerated pixel error, so its
                    // max box stands for the surface here: the hit is where the ray comes
                    // down to it.
                    end.tHit = mr_baseDescendTo(relief, start, dir, walk.ta, walk.tb, bound);
                    lodLevel = level;
                    end.finished = true;
                    break;
                }
                if (mr_walkAtLeaf(walk, footprint)) {
                    atLeaf = true;
                    leafBound = bound;
                    break;
                }
                // Descend into the near half (eq. 8), or straight into the far half when
                // the near one lies wholly above this segment's bound (a falling ray that
                // reaches the bound only past the midpoint).
                mr_walkDescend(walk, bound, mr_baseLowest(relief, start, dir, walk.ta, 0.5 * (walk.ta + walk.tb)) > bound);
                continue;
            }
            // Discarded. After a far half the walk climbs when the segment cleared its
            // bound by more than twice its own drop in height, so that the parent likely
            // clears its bound too and crosses empty space in one step; close to the
            // surface it stays at this depth. (The paper's recursion would climb to the
            // coarsest segment starting there, and so near the surface come back down
            // through levels whose bounds seldom reject.)
            if (!mr_walkNext(walk, footprint.lowest - bound > 2.0 * footprint.drop)) {
                end.finished = true;
                break;
            }
        }
        if (!atLeaf) break;  // finished, or out of iterations
        // No hit before the ray comes down to the leaf's bound: solve from there.
        float tFrom = mr_baseDescendTo(relief, start, dir, walk.ta, walk.tb, leafBound);
        // Two locals, copied into end after the call (what out means in GLSL anyway): WGSL
        // refuses two pointer arguments into one variable (docs/webgpu.md).
        mr_ReliefPatch leafPatch;
        ivec2 leafCell;
        end.tHit = mr_baseIntersectLeaf(relief, heights, start, dir, tFrom, walk.tb, leafPatch, leafCell);
        end.cellPatch = leafPatch;
        end.cell = leafCell;
        if (end.tHit >= 0.0) {
            end.finished = end.solved = true;
        } else if (!mr_walkNext(walk, false)) {
            end.finished = true;
        }
    }
    if (lodLevel >= 0 && end.tHit >= 0.0 && !query.anyHit) {
        // A hit the level of detail stood in for: on the window's box, its normal from
        // that level (mr_lodSlope), no sample read.
        hit.iterations = end.iterations;
        hit.kind = MR_RELIEF_TOP;
        hit.t = end.tHit;
        hit.position = start + end.tHit * dir;
        hit.normal = mr_baseTopNormal(relief, hit.position, mr_lodSlope(relief, windows, mr_baseMapPoint(relief, hit.position).xy, lodLevel));
        return;
    }
    mr_finishWalk(hit, relief, query, heights, start, dir, span, floorExit, end);
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
