// base_curved.glsl: what the cylinder and the ellipsoid share as base surfaces
// (base_surface.glsl; the C++ copy is src/core/base/CurvedSurface.cpp): the canonical frame
// q = world / frameScale, the angle about the y axis that sets u, where the line crosses a
// half-plane of constant u, and the X part of a segment's footprint.
//
// u = fract(0.5 + atan(q.x, q.z) / 2 pi): u = 0.5 faces +z, the seam u = 0 is at -z.
//
// Float margins. Every bound the traversal compares is widened by a margin that covers
// the rounding of the float arithmetic that computes it, so that it is never on the wrong
// side of the exact value: X and Y by 2^-10 texel plus 2^-19 of the map's size (u and v
// carry float's 2^-24 relative error and atan's few ulp, far less than 2^-19), radial
// distances by 2^-19 in the frame (a point o + t d and its length, |o|, |t d| < 4: a few
// ulp of 4, 2^-21 each). None loosens a bound measurably.
#ifndef MICRORELIEF_BASE_CURVED_GLSL
#define MICRORELIEF_BASE_CURVED_GLSL

#include "relief_map.glsl"

const float MR_CURVED_PI = 3.14159265358979;
const float MR_CURVED_RADIUS_MARGIN = 1.0 / 524288.0;  // 2^-19

float mr_curvedMarginX(mr_Relief relief) { return 1.0 / 1024.0 + relief.map.size.x * (1.0 / 524288.0); }
float mr_curvedMarginY(mr_Relief relief) { return 1.0 / 1024.0 + relief.map.size.y * (1.0 / 524288.0); }

// The curved leaf's subdivision of one cell's stretch of the ray: down to pieces
// MR_CURVED_FINAL_LENGTH long in the frame, or 2^-10 of the stretch at most. Over a piece of
// length w the gap g(t) between patch and ray departs from the parabola through its ends
// and middle by at most |g'''| w^3 / 125 (interpolation at three points w / 2 apart).
// g''' is dominated by the radial distance's, |r'''| <= 3 |d|^3 / r^2 along a line, over
// s, and by the path's turning about the axis, of the same order: with w |d| = 2^-7 and
// r >= 1 (the core below is solid), that is 1.1e-7 / s map units, float precision for
// s >= 0.1 and 1.1e-6 at s = 0.01. The patch is bilinear, its part of g a quadratic in t
// where the path is straight, which the parabola holds exactly.
const float MR_CURVED_FINAL_LENGTH = 1.0 / 128.0;

vec3 mr_curvedFramePoint(mr_Relief relief, vec3 object) { return object / relief.placement.frameScale; }
vec3 mr_curvedFrameVector(mr_Relief relief, vec3 object) { return object / relief.placement.frameScale; }
vec3 mr_curvedObjectPoint(mr_Relief relief, vec3 q) { return q * relief.placement.frameScale; }
// The inverse transpose of diag(frameScale); not unit.
vec3 mr_curvedObjectNormal(mr_Relief relief, vec3 n) { return n / relief.placement.frameScale; }

// X of frame point q, in [0, W). On the axis (where atan(0, 0) is undefined) u = 0.5.
float mr_curvedMapX(mr_Relief relief, vec3 q) {
    bool onAxis = q.x == 0.0 && q.z == 0.0;
    return relief.map.size.x * fract(0.5 + atan(q.x, onAxis ? 1.0 : q.z) * (0.5 / MR_CURVED_PI));
}

// Whether X grows along the line: d(atan(x, z))/dt = (z dx - x dz) / (x^2 + z^2), whose
// sign is constant along a line.
bool mr_curvedXIncreases(vec3 origin, vec3 dir) { return origin.z * dir.x - origin.x * dir.z > 0.0; }

// The t at which the line crosses the half-plane of constant X = boundary through the
// axis (points lambda (sin phi, y, cos phi), lambda >= 0), MR_NEVER where it does not.
// The line meets the half-plane's plane once at most, so any t is that crossing: a walk at
// t = `after` (its X monotone, its cell the one that holds it) that finds the boundary
// ahead of it behind `after` has rounded past it already, and steps on. But a line through
// the axis (an eye on it: every ray from it) meets every half-plane's plane there, and
// rounding both picks the side X moves to (mr_curvedXIncreases' sign of 0) and puts that
// meeting on either side: such a crossing, far behind on the axis, is no crossing; X is
// constant along the line past it. A crossing behind `after` is taken for the rounding of
// one at `after` only where it lies as far from the axis as the path at `after` does,
// within a factor 2 (the rounding of t moves the point by a few ulp, far less); one nearer
// the axis is that meeting (a line that misses the axis by more than rounding never
// crosses the boundary ahead behind `after`).
float mr_curvedCrossX(mr_Relief relief, vec3 origin, vec3 dir, float boundary, float after) {
    float phi = 2.0 * MR_CURVED_PI * (boundary / relief.map.size.x - 0.5);
    float s = sin(phi), c = cos(phi);
    float rate = s * dir.z - c * dir.x;
    if (rate == 0.0) return MR_NEVER;
    float t = (c * origin.x - s * origin.z) / rate;
    vec3 p = origin + t * dir;
    if (!(s * p.x + c * p.z > 0.0)) return MR_NEVER;
    if (t < after) {
        vec3 q = origin + after * dir;
        if (dot(p.xz, p.xz) < 0.25 * dot(q.xz, q.xz)) return MR_NEVER;
    }
    return t;
}

// The X range of the path between frame points of X = xa and xb. The angle about the axis is
// monotone along a line, and a segment that does not meet the axis turns by less than half
// a turn, so the path covers exactly the shorter arc between its ends. Near half a turn
// the segment passes next to the axis (where rounding could pick the wrong arc, and one
// through it jumps by half a turn): all of u then. lo in [0, W), hi up to lo + W.
vec2 mr_curvedRangeX(mr_Relief relief, float xa, float xb) {
    float w = relief.map.size.x, margin = mr_curvedMarginX(relief);
    float arc = xb - xa;
    if (arc > 0.5 * w) arc -= w;
    if (arc < -0.5 * w) arc += w;
    if (abs(arc) >= 0.5 * w - 2.0 * margin) return vec2(0.0, w);
    vec2 range = vec2(min(xa, xa + arc) - margin, max(xa, xa + arc) + margin);
    return range.x < 0.0 ? range + w : range;
}

// The interval of t where |p(t)| <= radius for the line p = o + t d (in the xz plane for
// the cylinder, in space for the ellipsoid), from the point nearest the centre, which keeps
// far origins accurate. Empty (x > y) when the line passes outside.
vec2 mr_curvedInsideRadius(vec3 origin, vec3 dir, float radius) {
    float dd = dot(dir, dir);
    if (dd == 0.0) return dot(origin, origin) <= radius * radius ? vec2(-1e30, 1e30) : vec2(1.0, -1.0);
    float tc = -dot(origin, dir) / dd;
    vec3 pc = origin + tc * dir;
    float h2 = (radius * radius - dot(pc, pc)) / dd;
    if (h2 < 0.0) return vec2(1.0, -1.0);
    float halfChord = sqrt(h2);
    return vec2(tc - halfChord, tc + halfChord);
}

#endif
