// leaf_walk.glsl: the exact first hit of a ray over a leaf of the traversal, a stretch of a
// few texels: the patches (relief_patch.glsl) its path crosses, in order, each solved
// exactly (mr_baseIntersectLeaf). The multilevel and maxmip traversals and the shadow
// rays end here; the C++ twin is src/core/trace/MultilevelTracer.cpp (walkLeafCells).
//
// Along a straight path (the plane: MICRORELIEF_BASE_STRAIGHT_PATH) the bilinear surface is
// a quadratic in t on each cell, solved in closed form cell after cell (a 2D DDA,
// mr_intersectStraightLeaf), and the biquadratic one a quartic on each texel square
// (biquadratic_patch.glsl). On a curved base the surface along the ray is no longer a
// polynomial in t. The leaf walks the cells its path crosses, in order, each cell's stretch
// ending where the path crosses a boundary (a half-plane of constant u, a plane or a cone
// of constant v), found in closed form (mr_baseCrossX, mr_baseCrossY); in each cell it
// subdivides the stretch as the traversal subdivides the ray, near half first, discarding
// each piece whose lowest height lies above the patch's max over its footprint (both
// exact: X and Y are monotone there, and a bilinear patch peaks at a corner of a
// rectangle), down to 2^-MICRORELIEF_CELL_DEPTH of the stretch; over such a piece the gap
// between the patch and the ray is smooth to third order, and a sign change of it at the
// piece's ends or middle gives the root by interpolation, while without one a concave
// parabola through the three values that reaches 0 is a ray touching the surface (a hit in
// the closed solid).
#ifndef MICRORELIEF_LEAF_WALK_GLSL
#define MICRORELIEF_LEAF_WALK_GLSL

#include "base_surface.glsl"
#include "bilinear_patch.glsl"
#include "fetch_count.glsl"
#include "final_piece.glsl"
#include "relief_map.glsl"
#include "relief_patch.glsl"
#include "texture_reads.glsl"
#include "variants.glsl"

// The depth of the subdivision of one cell's stretch (the curved bases').
#ifndef MICRORELIEF_CELL_DEPTH
#define MICRORELIEF_CELL_DEPTH 10
#endif
// The biquadratic surface along a piece of the path D texels wide departs from the parabola
// through its ends and middle by about its third derivative times (D / 2)^3 / 9 sqrt(3): a
// bicubic's is bounded by the map's range, and with D = 2^-6 that is 2.6e-7 of it.
const float MR_BIQUADRATIC_FINAL_FOOTPRINT = 1.0 / 64.0;

// When a piece of a cell's stretch is final: once it is MR_BASE_FINAL_LENGTH long in the
// frame (the base's curvature then below float precision; never on a straight path), and
// for the biquadratic surface once its footprint is MR_BIQUADRATIC_FINAL_FOOTPRINT texels
// wide; the bilinear surface along a straight path is a quadratic the parabola holds exactly.
const float MR_FINAL_LENGTH = MR_BASE_FINAL_LENGTH;
#if MICRORELIEF_INTERPOLATION == MR_INTERPOLATION_BIQUADRATIC
const float MR_FINAL_FOOTPRINT = MR_BIQUADRATIC_FINAL_FOOTPRINT;
#else
const float MR_FINAL_FOOTPRINT = 1e30;
#endif

// Exact first hit on the bilinear surface along [ta, tb] of a straight path, or -1 (the
// plane's leaf for the bilinear surface; the biquadratic one walks texel squares below):
// the patches (cells between four samples) the segment crosses, in ray order, each solved
// as a quadratic,
// from one cell to its neighbour across the boundary the ray meets first (a 2D DDA, as
// in the reference tracer). Neighbouring patches share an edge (mr_neighbourCorners).
// `corners` and `cell` are the patch of the hit.
float mr_intersectStraightLeaf(mr_Relief relief, MICRORELIEF_SAMPLER heights, vec3 origin, vec3 dir, float ta, float tb,
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


// Map point m in the local coordinates of `cell`, with its height: (fx, fy, h).
vec3 mr_cellLocalPoint(mr_Relief relief, ivec2 cell, vec3 m) { return vec3(mr_patchLocal(relief, cell, m.xy), m.z); }

// Patch minus ray: >= 0 where the ray is on or under the surface.
float mr_cellGap(mr_ReliefPatch cellPatch, vec3 local) { return mr_patchValue(cellPatch, clamp(local.xy, 0.0, 1.0)) - local.z; }

// The first t in [c0, c1] where the ray meets the patch `cellPatch` of `cell`, or -1 (see the
// header). `startPoint` and `endPoint`: the map points at c0 and c1, which the walk has
// (mr_walkLeafCells: each cell's end is the next one's start). The walk carries the local coordinates of
// the current piece's ends, so that each step computes one new point: the middle it
// descends to, or the end of the piece it moves on to. Every margin pads a bound outwards.
float mr_cellStretchHit(mr_Relief relief, vec3 origin, vec3 dir, ivec2 cell, mr_ReliefPatch cellPatch, float c0, float c1,
                     vec3 startPoint, vec3 endPoint) {
#if MICRORELIEF_BASE_STRAIGHT_PATH && MICRORELIEF_INTERPOLATION == MR_INTERPOLATION_BIQUADRATIC
    // The plane's path is straight: the gap is one quartic (biquadratic_patch.glsl).
    vec3 pa = mr_cellLocalPoint(relief, cell, startPoint), pb = mr_cellLocalPoint(relief, cell, endPoint);
    mr_Quartic gap = mr_biquadraticPathGap(cellPatch, pa, pb);
    float footprint = max(abs(pb.x - pa.x), abs(pb.y - pa.y));
    float s = mr_quarticFirstHit(gap, MR_FINAL_FOOTPRINT / max(footprint, 1e-30), MR_PATCH_TOP_MARGIN * relief.map.maxHeight);
    return s < 0.0 ? -1.0 : c0 + s * (c1 - c0);
#else
    vec2 margin = mr_baseMapMargin(relief);
    float topMargin = MR_PATCH_TOP_MARGIN * relief.map.maxHeight;
    float finalLength = MR_FINAL_LENGTH / length(dir);
    // The whole stretch passed this test in the walk (mr_cellStretchMayHit, the same
    // computation): it is descended into, or solved at once where it is final already.
    vec3 fa = mr_cellLocalPoint(relief, cell, startPoint), fb = mr_cellLocalPoint(relief, cell, endPoint);
    bool finalPiece = MICRORELIEF_CELL_DEPTH == 0 ||
                 (c1 - c0 <= finalLength && max(abs(fb.x - fa.x), abs(fb.y - fa.y)) <= MR_FINAL_FOOTPRINT);
    int depth = finalPiece ? 0 : 1;
    uint index = 0u;
    float a = c0, b = finalPiece ? c1 : 0.5 * (c0 + c1);
    // Each pass reads one map point, at tq: the end b of a piece not yet tested, or the
    // middle of a final piece that may hold a hit (the three reads of a pass that tested,
    // descended or solved and stepped on would all run on a SIMD machine that runs both
    // sides of a branch). Where a piece is descended into, its near half's end is its
    // middle, 0.5 (a + b), as a piece's own middle is: the same points, in the same order.
    float tq = finalPiece ? 0.5 * (c0 + c1) : b;
    // A walk of the binary tree of pieces visits each at most once, each final one twice.
    for (int guard = 0; guard < (4 << MICRORELIEF_CELL_DEPTH); ++guard) {
        vec3 fq = mr_cellLocalPoint(relief, cell, mr_baseMapPoint(relief, origin + tq * dir));
        bool stepOn;
        if (finalPiece) {
            // The final piece's middle: a root of the parabola through its ends and middle.
            float s = mr_parabolaFirstRoot(mr_cellGap(cellPatch, fa), mr_cellGap(cellPatch, fq), mr_cellGap(cellPatch, fb));
            if (s >= 0.0) return a + s * (b - a);
            stepOn = true;
            finalPiece = false;
        } else {
            fb = fq;
            vec2 lo = min(fa.xy, fb.xy), hi = max(fa.xy, fb.xy);
            float top = mr_patchTop(cellPatch, lo - margin, hi + margin) + topMargin;
            bool may = mr_baseLowest(relief, origin, dir, a, b) <= top;
            finalPiece = may && (depth == MICRORELIEF_CELL_DEPTH ||
                            (b - a <= finalLength && max(hi.x - lo.x, hi.y - lo.y) <= MR_FINAL_FOOTPRINT));
            stepOn = !may;
            tq = 0.5 * (a + b);
            if (may && !finalPiece) {
                // Into the near half.
                depth += 1;
                index *= 2u;
                b = tq;
            }
        }
        if (stepOn) {
            // Past this piece: on to its successor in order, as high up as it is unvisited.
            index += 1u;
            while (depth > 0 && (index & 1u) == 0u) {
                index >>= 1;
                depth -= 1;
            }
            if (depth == 0) return -1.0;
            a = b;
            fa = fb;
            b = index + 1u == (1u << uint(depth)) ? c1 : c0 + float(index + 1u) * ((c1 - c0) * exp2(-float(depth)));
            tq = b;
        }
    }
    return -1.0;
#endif
}

// The walk of mr_walkLeafCells past the cell whose stretch ended at t1 (map point `next`),
// stepping in X, in Y or both as it left; false when the stretch ended at the walk's end.
bool mr_nextLeafCell(int width, bool xUp, bool yUp, bool stepX, bool stepY, float t1, vec3 next,
                     inout ivec2 cell, inout float t0, inout vec3 point) {
    if (!stepX && !stepY) return false;  // the stretch ended at `to`
#if !MICRORELIEF_BASE_WRAPS_U
    if (stepX) cell.x += xUp ? 1 : -1;
#else
    // Past the last column comes the first.
    if (stepX) cell.x = xUp ? (cell.x + 1 == width ? 0 : cell.x + 1) : (cell.x == 0 ? width - 1 : cell.x - 1);
#endif
    if (stepY) cell.y += yUp ? 1 : -1;
    t0 = t1;
    point = next;
    return true;
}

// Whether the ray may meet the patch over [c0, c1] at all: the first test of
// mr_cellStretchHit's, on the whole stretch (the straight path's quartic on the plane's
// biquadratic surface, else the patch's max over the stretch's footprint against its lowest
// point), with the same margins. False only where mr_cellStretchHit would return -1 at once.
bool mr_cellStretchMayHit(mr_Relief relief, vec3 origin, vec3 dir, ivec2 cell, mr_ReliefPatch cellPatch, float c0,
                          float c1, vec3 startPoint, vec3 endPoint) {
    vec3 fa = mr_cellLocalPoint(relief, cell, startPoint), fb = mr_cellLocalPoint(relief, cell, endPoint);
#if MICRORELIEF_BASE_STRAIGHT_PATH && MICRORELIEF_INTERPOLATION == MR_INTERPOLATION_BIQUADRATIC
    mr_Quartic gap = mr_biquadraticPathGap(cellPatch, fa, fb);
    return max(max(max(gap.c.x, gap.c.y), max(gap.c.z, gap.c.w)), gap.c4) >= -MR_PATCH_TOP_MARGIN * relief.map.maxHeight;
#else
    vec2 margin = mr_baseMapMargin(relief);
    float top = mr_patchTop(cellPatch, min(fa.xy, fb.xy) - margin, max(fa.xy, fb.xy) + margin) +
                MR_PATCH_TOP_MARGIN * relief.map.maxHeight;
    return mr_baseLowest(relief, origin, dir, c0, c1) <= top;
#endif
}

// The cells of the path over [from, to], where X and Y are both monotone, in order: each
// cell's stretch ends where the path crosses its boundary ahead in X or in Y. [branchFrom,
// branchTo] is the whole branch of the line that holds [from, to] on which Y is monotone,
// so that each boundary is crossed once on it: a crossing found there but behind the
// current t means rounding put the start just past it, and the walk steps on at once.
// `cellPatch` and `cell` are the patch of the hit.
//
// Two loops, as in the traversal (multilevel_trace.glsl): the inner one walks cells with
// the cheap test of mr_cellStretchMayHit until one may hold a hit, the outer one solves
// it, so that a block of pixels pays for the exact solve once per pass rather than at
// every cell where any of its pixels needs it.
float mr_walkLeafCells(mr_Relief relief, MICRORELIEF_SAMPLER heights, vec3 origin, vec3 dir, float from, float to,
                    float branchFrom, float branchTo, out mr_ReliefPatch cellPatch, out ivec2 cell) {
    int width = int(relief.map.size.x);
    // Cells in Y: -1..H - 1 between sample centres, 0..H - 1 over texel squares.
    int firstRow = MR_PATCH_OFFSET > 0.0 ? -1 : 0, lastRow = int(relief.map.size.y) - 1;
    vec3 start = mr_baseMapPoint(relief, origin + from * dir);
    cell = mr_patchCellAt(relief, start.xy);
    cell.y = clamp(cell.y, firstRow, lastRow);
#if !MICRORELIEF_BASE_WRAPS_U
    cell.x = clamp(cell.x, firstRow, width - 1);  // as Y; wrapped, it is in 0..W - 1 (mr_wrapCell)
#endif
    bool xUp = mr_baseXIncreases(origin, dir);
    float yTo = mr_baseMapY(relief, origin + to * dir);
    bool yMoves = yTo != start.y, yUp = yTo > start.y;
    float t0 = from, t1 = to;
    vec3 point = start, next = start;  // the map points at t0 and t1
    bool stepX = false, stepY = false;
    cellPatch = mr_ReliefPatch(0.0);
    int piece = 0, pieces = width + int(relief.map.size.y) + 4;
    bool walking = true;
    while (walking) {
        // Along the cells to one the ray may meet.
        bool may = false;
        for (; piece < pieces; ++piece) {
            t1 = to;
            stepX = false;
            stepY = false;
            // A wrapping map one sample wide has no boundary in X: its one cell goes all the way
            // round.
            float tx = MICRORELIEF_BASE_WRAPS_U == 0 || width > 1
                           ? mr_baseCrossX(relief, origin, dir, float(cell.x) + MR_PATCH_OFFSET + (xUp ? 1.0 : 0.0), t0)
                           : MR_NEVER;
            if (tx <= t1) {
                t1 = max(tx, t0);
                stepX = true;
            }
            float yBoundary = float(cell.y) + MR_PATCH_OFFSET + (yUp ? 1.0 : 0.0);
            if (yMoves && yBoundary > 0.0 && yBoundary < relief.map.size.y) {
                float ty = mr_baseCrossY(relief, origin, dir, yBoundary, branchFrom, branchTo);
                if (ty <= t1) {
                    float t = max(ty, t0);
                    stepX = stepX && t == t1;
                    t1 = t;
                    stepY = true;
                }
            }
            cellPatch = mr_patchAt(relief, heights, cell);
            next = mr_baseMapPoint(relief, origin + t1 * dir);
            may = mr_cellStretchMayHit(relief, origin, dir, cell, cellPatch, t0, t1, point, next);
            if (may) break;
            walking = mr_nextLeafCell(width, xUp, yUp, stepX, stepY, t1, next, cell, t0, point);
            if (!walking) break;
        }
        if (!may) break;
        // The exact solve of the cell found.
        float tHit = mr_cellStretchHit(relief, origin, dir, cell, cellPatch, t0, t1, point, next);
        if (tHit >= 0.0) return tHit;
        walking = mr_nextLeafCell(width, xUp, yUp, stepX, stepY, t1, next, cell, t0, point);
        piece += 1;
    }
    return -1.0;
}

// The exact first hit over [ta, tb] by the cells the path crosses: the latitude turns at
// most once along a line, so the leaf is walked in two pieces at most, X and Y monotone on
// each.
float mr_intersectLeafCells(mr_Relief relief, MICRORELIEF_SAMPLER heights, vec3 origin, vec3 dir, float ta, float tb,
                         out mr_ReliefPatch cellPatch, out ivec2 cell) {
    float turn = mr_baseTurnY(origin, dir);
    float from = ta, to = turn > ta && turn < tb ? turn : tb;
    float tHit = -1.0;
    for (int piece = 0; piece < 2; ++piece) {
        // The branch of the line, before or after the turn, that holds [from, to].
        bool beforeTurn = turn != MR_NEVER && turn >= to;
        float branchFrom = beforeTurn || turn == MR_NEVER ? -MR_NEVER : turn;
        float branchTo = beforeTurn ? turn : MR_NEVER;
        tHit = mr_walkLeafCells(relief, heights, origin, dir, from, to, branchFrom, branchTo, cellPatch, cell);
        if (tHit >= 0.0 || to >= tb) break;
        from = to;
        to = tb;
    }
    return tHit;
}

// The exact first hit on the surface over [ta, tb], or -1; `corners` and `cell` are the
// patch of the hit.
float mr_baseIntersectLeaf(mr_Relief relief, MICRORELIEF_SAMPLER heights, vec3 origin, vec3 dir, float ta, float tb,
                        out mr_ReliefPatch cellPatch, out ivec2 cell) {
#if MICRORELIEF_BASE_STRAIGHT_PATH && MICRORELIEF_INTERPOLATION == MR_INTERPOLATION_BILINEAR
    return mr_intersectStraightLeaf(relief, heights, origin, dir, ta, tb, cellPatch, cell);
#else
    return mr_intersectLeafCells(relief, heights, origin, dir, ta, tb, cellPatch, cell);
#endif
}

#endif
