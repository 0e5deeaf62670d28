// base_surface.glsl: the base-surface seam of the library, everything the tracers need
// to know about the surface the height map is laid over (paper, section II: "planes,
// ellipsoids, or cylinders"; scene-and-cli.md, "Base surfaces"), for the base the host
// chooses with MICRORELIEF_BASE (relief_map.glsl): 0 the plane (base_plane.glsl), 1 a
// cylinder (base_cylinder.glsl), 2 an ellipsoid (base_ellipsoid.glsl). The C++ mirror is
// include/microrelief/base/BaseSurface.h; a new base is one file in each, and a branch here.
//
// The tracers work in the base's frame, where the ray is a straight line o + t d with the
// world's t (mr_baseFramePoint, mr_baseFrameVector). For a segment [ta, tb] of it the seam gives
// its footprint on the map and its lowest height above the base (mr_baseFootprint), both
// bounds, never samples: on a curved base the path in (X, Y, h) is a curve, but the angle
// about the axis is monotone along a line, the distance from the axis or the centre is
// convex along it, and the latitude has at most one interior extremum, so each extreme
// over the segment is at an end or at one interior point found in closed form. It gives
// the ray's interval in the bounding shell and the face it enters through
// (mr_baseClipToShell), the exact first hit over a leaf (mr_baseIntersectLeaf), and the hit's
// map point and normal (mr_baseMapPoint, mr_baseTopNormal, mr_baseWorldNormal).
//
// The exact hit on a curved base (mr_intersectLeafCells): along the ray the surface is no
// longer a polynomial in t. The leaf walks the cells its path crosses, in order, each
// cell's stretch ending where the path crosses a boundary (a half-plane of constant u, a
// plane or a cone of constant v), found in closed form; in each cell it subdivides the
// stretch as the traversal subdivides the ray, near half first, discarding each piece
// whose lowest height lies above the patch's max over its footprint (both exact: X and Y
// are monotone there, and a bilinear patch peaks at a corner of a rectangle), down to
// 2^-MICRORELIEF_CELL_DEPTH of the stretch; over such a piece the gap between the patch
// and the ray is smooth to third order, and a sign change of it at the piece's ends or
// middle gives the root by interpolation, while without one a concave parabola through the
// three values that reaches 0 is a ray touching the surface (a hit in the closed solid).
#ifndef MICRORELIEF_BASE_SURFACE_GLSL
#define MICRORELIEF_BASE_SURFACE_GLSL

#include "base_curved.glsl"
#include "base_cylinder.glsl"
#include "base_ellipsoid.glsl"
#include "base_plane.glsl"
#include "bilinear_patch.glsl"
#include "final_piece.glsl"
#include "map_space.glsl"
#include "relief_map.glsl"
#include "relief_patch.glsl"
#include "texture_reads.glsl"

// The curved leaf's subdivision of one cell's stretch of the ray: down to pieces
// MR_CURVED_FINAL_LENGTH long in the frame, or 2^-10 of the stretch at most. Over a piece of
// length w the gap g(t) between patch and ray departs from the parabola through its ends
// and middle by at most |g'''| w^3 / 125 (interpolation at three points w / 2 apart).
// g''' is dominated by the radial distance's, |r'''| <= 3 |d|^3 / r^2 along a line, over
// s, and by the path's turning about the axis, of the same order: with w |d| = 2^-7 and
// r >= 1 (the core below is solid), that is 1.1e-7 / s map units, float precision for
// s >= 0.1 and 1.1e-6 at s = 0.01. The patch is bilinear, its part of g a quadratic in t
// where the path is straight, which the parabola holds exactly.
#ifndef MICRORELIEF_CELL_DEPTH
#define MICRORELIEF_CELL_DEPTH 10
#endif
const float MR_CURVED_FINAL_LENGTH = 1.0 / 128.0;
// The biquadratic surface along a piece of the path D texels wide departs from the parabola
// through its ends and middle by about its third derivative times (D / 2)^3 / 9 sqrt(3): a
// bicubic's is bounded by the map's range, and with D = 2^-6 that is 2.6e-7 of it.
const float MR_BIQUADRATIC_FINAL_FOOTPRINT = 1.0 / 64.0;
// The patch's bound, padded by its own float rounding (a few ulp of the net's entries).
const float MR_PATCH_TOP_MARGIN = 1.0 / 1048576.0;

// Between the world and the base's frame, in two steps: the model transform
// (mr_ReliefPlacement: the world to the relief's object space, an affine map, so t is
// kept), then the base's own (map space on the plane, the canonical frame on a curved
// base). With the identity for a model both steps are exact in float (a product with
// ones and zeros), so the model costs nothing in accuracy where it is not used.
vec3 mr_baseObjectPoint(mr_Relief relief, vec3 world) {
    return (relief.placement.worldToObject * vec4(world, 1.0)).xyz;
}

vec3 mr_baseFramePoint(mr_Relief relief, vec3 world) {
    vec3 object = mr_baseObjectPoint(relief, world);
#if MICRORELIEF_BASE == 0
    return mr_objectToMapPoint(relief, object);
#else
    return mr_curvedFramePoint(relief, object);
#endif
}

vec3 mr_baseFrameVector(mr_Relief relief, vec3 world) {
    vec3 object = mat3(relief.placement.worldToObject) * world;
#if MICRORELIEF_BASE == 0
    return mr_objectToMapVector(relief, object);
#else
    return mr_curvedFrameVector(relief, object);
#endif
}

vec3 mr_baseWorldPoint(mr_Relief relief, vec3 q) {
#if MICRORELIEF_BASE == 0
    vec3 object = mr_mapToObjectPoint(relief, q);
#else
    vec3 object = mr_curvedObjectPoint(relief, q);
#endif
    return (relief.placement.objectToWorld * vec4(object, 1.0)).xyz;
}

// Y of a frame point (curved bases), and the map point (X, Y, h): X in [0, W) on a
// curved base.
float mr_baseMapY(mr_Relief relief, vec3 q) {
#if MICRORELIEF_BASE == 1
    return mr_cylinderMapY(relief, q);
#elif MICRORELIEF_BASE == 2
    return mr_ellipsoidMapY(relief, q);
#else
    return q.y;
#endif
}

vec3 mr_baseMapPoint(mr_Relief relief, vec3 q) {
#if MICRORELIEF_BASE == 1
    return vec3(mr_curvedMapX(relief, q), mr_cylinderMapY(relief, q), (mr_cylinderRadial(q) - 1.0) / relief.placement.heightScale);
#elif MICRORELIEF_BASE == 2
    return vec3(mr_curvedMapX(relief, q), mr_ellipsoidMapY(relief, q), (mr_ellipsoidRadial(q) - 1.0) / relief.placement.heightScale);
#else
    return q;
#endif
}

// Frame point q moved `by` map units up the base's height axis: the same (X, Y) in exact
// arithmetic, the height h + by (float rounding may move X and Y by an ulp on a curved base).
vec3 mr_baseRaise(mr_Relief relief, vec3 q, float by) {
#if MICRORELIEF_BASE == 1
    return mr_cylinderRaise(relief, q, by);
#elif MICRORELIEF_BASE == 2
    return mr_ellipsoidRaise(relief, q, by);
#else
    return mr_planeRaise(q, by);
#endif
}

// The ray's interval in the bounding shell (empty when x > y); the face it enters through
// (MR_RELIEF_WALL_X, _WALL_Y, _BOTTOM, _CAP, or MR_RELIEF_MISS: the top face or the curved
// shell); whether it leaves through the plane's floor going down.
vec2 mr_baseClipToShell(mr_Relief relief, vec3 origin, vec3 dir, out int entryFace, out bool floorExit) {
    entryFace = MR_RELIEF_MISS;
    floorExit = false;
#if MICRORELIEF_BASE == 1
    return mr_cylinderClipToShell(relief, origin, dir, entryFace);
#elif MICRORELIEF_BASE == 2
    return mr_ellipsoidClipToShell(relief, origin, dir);
#else
    return mr_planeClipToShell(relief, origin, dir, entryFace, floorExit);
#endif
}

// A segment's end as the footprint needs it, computed once per end (a walk's neighbouring
// segments share theirs): the map point on the plane; (X, Y, radial distance) on a curved
// base.
vec3 mr_baseEnd(mr_Relief relief, vec3 q) {
#if MICRORELIEF_BASE == 1
    return mr_cylinderEnd(relief, q);
#elif MICRORELIEF_BASE == 2
    return mr_ellipsoidEnd(relief, q);
#else
    return q;
#endif
}

// The footprint of [ta, tb], whose ends are `ea`, `eb` (mr_baseEnd).
mr_BaseFootprint mr_baseFootprintOf(mr_Relief relief, vec3 origin, vec3 dir, float ta, float tb, vec3 ea, vec3 eb) {
#if MICRORELIEF_BASE == 1
    return mr_cylinderFootprint(relief, origin, dir, ta, tb, ea, eb);
#elif MICRORELIEF_BASE == 2
    return mr_ellipsoidFootprint(relief, origin, dir, ta, tb, ea, eb);
#else
    return mr_planeFootprint(ea, eb);
#endif
}

mr_BaseFootprint mr_baseFootprint(mr_Relief relief, vec3 origin, vec3 dir, float ta, float tb) {
    return mr_baseFootprintOf(relief, origin, dir, ta, tb, mr_baseEnd(relief, origin + ta * dir), mr_baseEnd(relief, origin + tb * dir));
}

// mr_baseFootprint(...).lowest alone: the lowest height over [ta, tb], never above it.
float mr_baseLowest(mr_Relief relief, vec3 origin, vec3 dir, float ta, float tb) {
#if MICRORELIEF_BASE == 1
    return (mr_cylinderLowestRadial(origin, dir, ta, tb) - 1.0) / relief.placement.heightScale;
#elif MICRORELIEF_BASE == 2
    return (mr_ellipsoidLowestRadial(origin, dir, ta, tb) - 1.0) / relief.placement.heightScale;
#else
    return mr_planeLowest(origin, dir, ta, tb);
#endif
}

// The first t in [ta, tb] at which the ray is at or below height h (map units), never
// later than the exact one; ta where it starts there or does not get that low.
float mr_baseDescendTo(mr_Relief relief, vec3 origin, vec3 dir, float ta, float tb, float h) {
#if MICRORELIEF_BASE == 0
    return mr_planeDescendTo(origin, dir, ta, tb, h);
#else
    float radius = 1.0 + relief.placement.heightScale * h + MR_CURVED_RADIUS_MARGIN;
#if MICRORELIEF_BASE == 1
    vec2 inside = mr_curvedInsideRadius(vec3(origin.x, 0.0, origin.z), vec3(dir.x, 0.0, dir.z), radius);
#else
    vec2 inside = mr_curvedInsideRadius(origin, dir, radius);
#endif
    return inside.x > ta && inside.x <= tb ? inside.x : ta;
#endif
}

// Where the latitude turns (MR_CURVED_NEVER on the plane and the cylinder).
float mr_baseTurnY(vec3 origin, vec3 dir) {
#if MICRORELIEF_BASE == 2
    return mr_ellipsoidTurnY(origin, dir);
#else
    return MR_CURVED_NEVER;
#endif
}

// The outward normal (not unit) in the frame at frame point q of the top surface, whose
// map gradient there is (dh/dX, dh/dY); of the face a ray entered through.
vec3 mr_baseTopNormal(mr_Relief relief, vec3 q, vec2 gradient) {
#if MICRORELIEF_BASE == 1
    return mr_cylinderTopNormal(relief, q, gradient);
#elif MICRORELIEF_BASE == 2
    return mr_ellipsoidTopNormal(relief, q, gradient);
#else
    return mr_planeTopNormal(gradient);
#endif
}

vec3 mr_baseFaceNormal(mr_Relief relief, int face, vec3 q, vec3 dir) {
#if MICRORELIEF_BASE == 0
    return mr_planeFaceNormal(face, dir);
#else
    return mr_cylinderFaceNormal(q);  // the cylinder's caps: the only faces a curved shell has
#endif
}

// A frame normal as a world-space unit vector: the frame's inverse transpose into object
// space, then the model's (the transpose of worldToObject's linear part).
vec3 mr_baseWorldNormal(mr_Relief relief, vec3 n) {
#if MICRORELIEF_BASE == 0
    vec3 object = mr_planeObjectNormal(relief, n);
#else
    vec3 object = mr_curvedObjectNormal(relief, n);
#endif
    return normalize(transpose(mat3(relief.placement.worldToObject)) * object);
}

// The frame point of map point (X, Y, h): the surface point of the base at (u, v),
// raised by h along the base's normal.
vec3 mr_baseSurfacePoint(mr_Relief relief, vec3 m) {
#if MICRORELIEF_BASE == 0
    return m;
#else
    float phi = 2.0 * MR_CURVED_PI * (m.x / relief.map.size.x - 0.5), r = 1.0 + relief.placement.heightScale * m.z;
#if MICRORELIEF_BASE == 1
    return vec3(r * sin(phi), 1.0 - 2.0 * m.y / relief.map.size.y, r * cos(phi));
#else
    float theta = MR_CURVED_PI * m.y / relief.map.size.y;
    return r * vec3(sin(theta) * sin(phi), cos(theta), sin(theta) * cos(phi));
#endif
#endif
}

// The base's tangent frame at map point m: the frame point's derivatives along X, Y and h
// (orthogonal on every base: map space's axes on the plane).
void mr_baseTangentFrame(mr_Relief relief, vec3 m, out vec3 alongX, out vec3 alongY, out vec3 alongH) {
#if MICRORELIEF_BASE == 0
    alongX = vec3(1.0, 0.0, 0.0);
    alongY = vec3(0.0, 1.0, 0.0);
    alongH = vec3(0.0, 0.0, 1.0);
#else
    float phi = 2.0 * MR_CURVED_PI * (m.x / relief.map.size.x - 0.5), r = 1.0 + relief.placement.heightScale * m.z;
    vec3 ePhi = vec3(cos(phi), 0.0, -sin(phi));
#if MICRORELIEF_BASE == 1
    alongX = r * (2.0 * MR_CURVED_PI / relief.map.size.x) * ePhi;
    alongY = vec3(0.0, -2.0 / relief.map.size.y, 0.0);
    alongH = relief.placement.heightScale * vec3(sin(phi), 0.0, cos(phi));
#else
    float theta = MR_CURVED_PI * m.y / relief.map.size.y;
    vec3 w = vec3(sin(theta) * sin(phi), cos(theta), sin(theta) * cos(phi));
    vec3 eTheta = vec3(cos(theta) * sin(phi), -sin(theta), cos(theta) * cos(phi));
    alongX = r * sin(theta) * (2.0 * MR_CURVED_PI / relief.map.size.x) * ePhi;
    alongY = r * (MR_CURVED_PI / relief.map.size.y) * eTheta;
    alongH = relief.placement.heightScale * w;
#endif
#endif
}

// The ray in the tangent frame where it enters the shell, as engines run parallax methods
// on a curved surface: map space (X, Y, h) taken as flat from that point on, the ray's
// direction expressed in the base's tangent frame there, blind to the curvature beyond.
// False when the ray misses the shell. `tEntry` is where it enters (or 0 inside it).
bool mr_baseTangentRay(mr_Relief relief, vec3 origin, vec3 dir, out vec3 localOrigin, out vec3 localDir,
                    out float tEntry) {
    int entryFace;
    bool floorExit;
    vec2 range = mr_baseClipToShell(relief, origin, dir, entryFace, floorExit);
    tEntry = max(range.x, 0.0);
    localOrigin = mr_baseMapPoint(relief, origin + tEntry * dir);
    localDir = vec3(0.0);
    if (tEntry > range.y) return false;
    vec3 alongX, alongY, alongH;
    mr_baseTangentFrame(relief, localOrigin, alongX, alongY, alongH);
    localDir = vec3(dot(dir, alongX) / dot(alongX, alongX), dot(dir, alongY) / dot(alongY, alongY),
                    dot(dir, alongH) / dot(alongH, alongH));
    return true;
}

// The leaf's walk over the cells its path crosses, for every base and both
// interpolations but the plane's bilinear surface (whose leaf is mr_planeIntersectLeaf):
// where the path crosses the cell boundaries X = i + MR_PATCH_OFFSET and Y = j + MR_PATCH_OFFSET
// (relief_patch.glsl), and which way it goes.
bool mr_baseXIncreases(vec3 origin, vec3 dir) {
#if MICRORELIEF_BASE == 0
    return dir.x > 0.0;
#else
    return mr_curvedXIncreases(origin, dir);
#endif
}

float mr_baseCrossX(mr_Relief relief, vec3 origin, vec3 dir, float boundary) {
#if MICRORELIEF_BASE == 0
    return mr_planeCrossX(origin, dir, boundary);
#else
    return mr_curvedCrossX(relief, origin, dir, boundary);
#endif
}

// On the plane and the cylinder each Y boundary is crossed once (any t); on the
// ellipsoid, the crossing on the branch [from, to] of the line where Y is monotone.
float mr_baseCrossY(mr_Relief relief, vec3 origin, vec3 dir, float boundary, float from, float to) {
#if MICRORELIEF_BASE == 2
    return mr_ellipsoidCrossY(relief, origin, dir, boundary, from, to);
#elif MICRORELIEF_BASE == 1
    return mr_cylinderCrossY(relief, origin, dir, boundary);
#else
    return mr_planeCrossY(origin, dir, boundary);
#endif
}

// When a piece of a cell's stretch is final (see the header): on a curved base once it is
// MR_CURVED_FINAL_LENGTH long in the frame, and for the biquadratic surface once its footprint
// is MR_BIQUADRATIC_FINAL_FOOTPRINT texels wide; the bilinear surface along a straight path is
// a quadratic the parabola holds exactly.
#if MICRORELIEF_BASE == 0
const float MR_FINAL_LENGTH = 1e30;
#else
const float MR_FINAL_LENGTH = MR_CURVED_FINAL_LENGTH;
#endif
#if MICRORELIEF_INTERPOLATION == 1
const float MR_FINAL_FOOTPRINT = MR_BIQUADRATIC_FINAL_FOOTPRINT;
#else
const float MR_FINAL_FOOTPRINT = 1e30;
#endif

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
#if MICRORELIEF_BASE == 0 && MICRORELIEF_INTERPOLATION == 1
    // The plane's path is straight: the gap is one quartic (biquadratic_patch.glsl).
    vec3 pa = mr_cellLocalPoint(relief, cell, startPoint), pb = mr_cellLocalPoint(relief, cell, endPoint);
    mr_Quartic gap = mr_biquadraticPathGap(cellPatch, pa, pb);
    float footprint = max(abs(pb.x - pa.x), abs(pb.y - pa.y));
    float s = mr_quarticFirstHit(gap, MR_FINAL_FOOTPRINT / max(footprint, 1e-30), MR_PATCH_TOP_MARGIN * relief.map.maxHeight);
    return s < 0.0 ? -1.0 : c0 + s * (c1 - c0);
#else
    vec2 margin = vec2(mr_curvedMarginX(relief), mr_curvedMarginY(relief));
    float topMargin = MR_PATCH_TOP_MARGIN * relief.map.maxHeight;
    float finalLength = MR_FINAL_LENGTH / length(dir);
    int depth = 0;
    uint index = 0u;
    float a = c0, b = c1;
    vec3 fa = mr_cellLocalPoint(relief, cell, startPoint), fb = mr_cellLocalPoint(relief, cell, endPoint);
    // A walk of the binary tree of pieces visits each at most once.
    for (int guard = 0; guard < (2 << MICRORELIEF_CELL_DEPTH); ++guard) {
        vec2 lo = min(fa.xy, fb.xy), hi = max(fa.xy, fb.xy);
        float top = mr_patchTop(cellPatch, lo - margin, hi + margin) + topMargin;
        bool may = mr_baseLowest(relief, origin, dir, a, b) <= top;
        bool last = depth == MICRORELIEF_CELL_DEPTH ||
                    (b - a <= finalLength && max(hi.x - lo.x, hi.y - lo.y) <= MR_FINAL_FOOTPRINT);
        if (may && !last) {
            // Into the near half.
            depth += 1;
            index *= 2u;
            b = 0.5 * (a + b);
            fb = mr_cellLocalPoint(relief, cell, mr_baseMapPoint(relief, origin + b * dir));
            continue;
        }
        if (may) {
            float m = 0.5 * (a + b);
            float ga = mr_cellGap(cellPatch, fa), gb = mr_cellGap(cellPatch, fb);
            float gm = mr_cellGap(cellPatch, mr_cellLocalPoint(relief, cell, mr_baseMapPoint(relief, origin + m * dir)));
            float s = mr_parabolaFirstRoot(ga, gm, gb);
            if (s >= 0.0) return a + s * (b - a);
        }
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
        fb = mr_cellLocalPoint(relief, cell, mr_baseMapPoint(relief, origin + b * dir));
    }
    return -1.0;
#endif
}

// The walk of mr_walkLeafCells past the cell whose stretch ended at t1 (map point `next`),
// stepping in X, in Y or both as it left; false when the stretch ended at the walk's end.
bool mr_nextLeafCell(int width, bool xUp, bool yUp, bool stepX, bool stepY, float t1, vec3 next,
                     inout ivec2 cell, inout float t0, inout vec3 point) {
    if (!stepX && !stepY) return false;  // the stretch ended at `to`
#if MICRORELIEF_BASE == 0
    if (stepX) cell.x += xUp ? 1 : -1;
#else
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
#if MICRORELIEF_BASE == 0 && MICRORELIEF_INTERPOLATION == 1
    mr_Quartic gap = mr_biquadraticPathGap(cellPatch, fa, fb);
    return max(max(max(gap.c.x, gap.c.y), max(gap.c.z, gap.c.w)), gap.c4) >= -MR_PATCH_TOP_MARGIN * relief.map.maxHeight;
#else
    vec2 margin = vec2(mr_curvedMarginX(relief), mr_curvedMarginY(relief));
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
#if MICRORELIEF_BASE == 0
    cell.x = clamp(cell.x, firstRow, width - 1);
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
            // A curved map one sample wide has no boundary in X: its one cell goes all the way
            // round.
            float tx = MICRORELIEF_BASE == 0 || width > 1
                           ? mr_baseCrossX(relief, origin, dir, float(cell.x) + MR_PATCH_OFFSET + (xUp ? 1.0 : 0.0))
                           : MR_CURVED_NEVER;
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
        bool beforeTurn = turn != MR_CURVED_NEVER && turn >= to;
        float branchFrom = beforeTurn || turn == MR_CURVED_NEVER ? -MR_CURVED_NEVER : turn;
        float branchTo = beforeTurn ? turn : MR_CURVED_NEVER;
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
#if MICRORELIEF_BASE == 0 && MICRORELIEF_INTERPOLATION == 0
    return mr_planeIntersectLeaf(relief, heights, origin, dir, ta, tb, cellPatch, cell);
#else
    return mr_intersectLeafCells(relief, heights, origin, dir, ta, tb, cellPatch, cell);
#endif
}

#endif
