// base_ellipsoid.glsl: an ellipsoid as the base surface (base_surface.glsl; the C++ copy
// is src/core/base/EllipsoidSurface.cpp). In the canonical frame q = (x / A, y / B, z / C) it
// is the unit sphere; v = theta / pi is the polar angle from +y (v = 0 at the top pole);
// the height sets the distance from the centre, |q| = 1 + s h: a star-shaped body.
#ifndef MICRORELIEF_BASE_ELLIPSOID_GLSL
#define MICRORELIEF_BASE_ELLIPSOID_GLSL

#include "base_curved.glsl"
#include "relief_map.glsl"

// Its traits (base_surface.glsl): u wraps round the axis across the seam, v clamps (at the poles),
// and the ray's path over the map is a curve (leaf_walk.glsl subdivides a leaf's stretches).
#define MICRORELIEF_BASE_WRAPS_U 1
#define MICRORELIEF_BASE_WRAPS_V 0
#define MICRORELIEF_BASE_STRAIGHT_PATH 0

float mr_ellipsoidRadial(vec3 q) { return length(q); }

// The polar angle as atan(|q.xz|, q.y): well conditioned at the poles, where acos(q.y / r)
// would lose half the digits. At the centre (undefined) the equator.
float mr_ellipsoidMapY(mr_Relief relief, vec3 q) {
    float rho = length(q.xz);
    bool atCentre = rho == 0.0 && q.y == 0.0;
    return relief.map.size.y * atan(rho, atCentre ? 0.0 : q.y) / MR_CURVED_PI;
}

// The smallest distance from the centre over [ta, tb] (convex along a line: the nearest
// point, clamped); the margin covers rounding.
float mr_ellipsoidLowestRadial(vec3 origin, vec3 dir, float ta, float tb) {
    float t = clamp(-dot(origin, dir) / dot(dir, dir), ta, tb);
    return length(origin + t * dir) - MR_CURVED_RADIUS_MARGIN;
}

// Where the latitude turns: q.y / |q| along o + t d has the derivative N(t) / |p|^3 with N
// linear in t, N(t) = dy |o|^2 - oy (o.d) + t (dy (o.d) - oy |d|^2); its one root is the
// latitude's only interior extremum (MR_NEVER if none).
float mr_ellipsoidTurnY(vec3 origin, vec3 dir) {
    float od = dot(origin, dir);
    float slope = dir.y * od - origin.y * dot(dir, dir);
    return slope == 0.0 ? MR_NEVER : -(dir.y * dot(origin, origin) - origin.y * od) / slope;
}

// The Y range over [ta, tb] whose ends have Y = ya and yb: theirs, and the turn's if it
// lies inside.
vec2 mr_ellipsoidRangeY(mr_Relief relief, vec3 origin, vec3 dir, float ta, float tb, float ya, float yb) {
    vec2 range = vec2(min(ya, yb), max(ya, yb));
    float turn = mr_ellipsoidTurnY(origin, dir);
    if (turn > ta && turn < tb) {
        float y = mr_ellipsoidMapY(relief, origin + turn * dir);
        range = vec2(min(range.x, y), max(range.y, y));
    }
    return range;
}

// The t in [from, to] (where Y is monotone, so there is one at most) at which the line
// crosses the cone of constant Y = boundary, cos^2 |p_xz|^2 = sin^2 p_y^2 on the nappe
// where p_y has the sign of cos; MR_NEVER if none. The equator's cone is the plane
// y = 0 (the quadratic's double root there would lose half the digits).
float mr_ellipsoidCrossY(mr_Relief relief, vec3 origin, vec3 dir, float boundary, float from, float to) {
    float theta = MR_CURVED_PI * boundary / relief.map.size.y;
    float c = cos(theta), s = sin(theta);
    if (abs(c) < 1e-6) {
        float t = dir.y == 0.0 ? MR_NEVER : -origin.y / dir.y;
        return t >= from && t <= to ? t : MR_NEVER;
    }
    float c2 = c * c, s2 = s * s;
    float a = c2 * dot(dir.xz, dir.xz) - s2 * dir.y * dir.y;
    float b = c2 * dot(origin.xz, dir.xz) - s2 * origin.y * dir.y;
    float k = c2 * dot(origin.xz, origin.xz) - s2 * origin.y * origin.y;
    vec2 roots = vec2(MR_NEVER);
    if (a == 0.0) {
        if (b != 0.0) roots.x = -k / (2.0 * b);
    } else {
        float disc = b * b - a * k;
        if (disc < 0.0) return MR_NEVER;
        float q = -(b + (b >= 0.0 ? 1.0 : -1.0) * sqrt(disc));
        roots = vec2(q / a, q != 0.0 ? k / q : MR_NEVER);
    }
    float first = MR_NEVER;
    for (int r = 0; r < 2; ++r) {
        float t = roots[r];
        bool nappe = (origin.y + t * dir.y) * c >= 0.0;
        if (t >= from && t <= to && nappe) first = min(first, t);
    }
    return first;
}

// The bounding shell: the ball of radius 1 + s maxHeight. It is entered through the
// shell itself, never a face.
vec2 mr_ellipsoidClipToShell(mr_Relief relief, vec3 origin, vec3 dir) {
    return mr_curvedInsideRadius(origin, dir, 1.0 + relief.placement.heightScale * relief.map.maxHeight);
}

// A segment's ends as (X, Y, distance from the centre), what its footprint is made of.
vec3 mr_ellipsoidEnd(mr_Relief relief, vec3 q) { return vec3(mr_curvedMapX(relief, q), mr_ellipsoidMapY(relief, q), mr_ellipsoidRadial(q)); }

// The footprint of [ta, tb] from its ends `ea`, `eb` (mr_ellipsoidEnd).
mr_BaseFootprint mr_ellipsoidFootprint(mr_Relief relief, vec3 origin, vec3 dir, float ta, float tb, vec3 ea, vec3 eb) {
    vec2 x = mr_curvedRangeX(relief, ea.x, eb.x);
    vec2 y = mr_ellipsoidRangeY(relief, origin, dir, ta, tb, ea.y, eb.y) + vec2(-1.0, 1.0) * mr_curvedMarginY(relief);
    float lowest = (mr_ellipsoidLowestRadial(origin, dir, ta, tb) - 1.0) / relief.placement.heightScale;
    return mr_BaseFootprint(vec2(x.x, y.x), vec2(x.y, y.y), lowest, abs(eb.z - ea.z) / relief.placement.heightScale);
}

// Frame point q moved `by` map units of height away from the centre (s by in the frame).
vec3 mr_ellipsoidRaise(mr_Relief relief, vec3 q, float by) {
    float r = mr_ellipsoidRadial(q);
    return r > 0.0 ? q * (1.0 + relief.placement.heightScale * by / r) : q;
}

// q = r w(theta, phi) with r = 1 + s h: the outward normal is r w - r_theta e_theta -
// r_phi / sin(theta) e_phi, with r_theta = s H / pi dh/dY and r_phi = s W / 2 pi dh/dX.
vec3 mr_ellipsoidTopNormal(mr_Relief relief, vec3 q, vec2 gradient) {
    float r = length(q);
    if (r == 0.0) return vec3(0.0, 1.0, 0.0);
    vec3 w = q / r;
    float sinTheta = length(w.xz), cosTheta = w.y;
    vec2 phi = sinTheta > 0.0 ? w.xz / sinTheta : vec2(0.0, 1.0);  // (sin, cos) of phi
    vec3 eTheta = vec3(cosTheta * phi.x, -sinTheta, cosTheta * phi.y);
    vec3 ePhi = vec3(phi.y, 0.0, -phi.x);
    float rTheta = relief.placement.heightScale * relief.map.size.y / MR_CURVED_PI * gradient.y;
    float rPhi = relief.placement.heightScale * relief.map.size.x / (2.0 * MR_CURVED_PI) * gradient.x;
    return r * w - rTheta * eTheta - rPhi / max(sinTheta, 1e-6) * ePhi;
}

// base_surface.glsl's set of mr_base* functions, for the ellipsoid.
vec3 mr_baseObjectToFrame(mr_Relief relief, vec3 object) { return mr_curvedFramePoint(relief, object); }
vec3 mr_baseObjectToFrameVector(mr_Relief relief, vec3 object) { return mr_curvedFrameVector(relief, object); }
vec3 mr_baseFrameToObject(mr_Relief relief, vec3 q) { return mr_curvedObjectPoint(relief, q); }
vec3 mr_baseObjectNormal(mr_Relief relief, vec3 n) { return mr_curvedObjectNormal(relief, n); }

float mr_baseMapY(mr_Relief relief, vec3 q) { return mr_ellipsoidMapY(relief, q); }
vec3 mr_baseMapPoint(mr_Relief relief, vec3 q) {
    return vec3(mr_curvedMapX(relief, q), mr_ellipsoidMapY(relief, q), (mr_ellipsoidRadial(q) - 1.0) / relief.placement.heightScale);
}
vec2 mr_baseMapMargin(mr_Relief relief) { return vec2(mr_curvedMarginX(relief), mr_curvedMarginY(relief)); }
vec3 mr_baseRaise(mr_Relief relief, vec3 q, float by) { return mr_ellipsoidRaise(relief, q, by); }

// The ball has no face: a ray comes in through the shell itself.
vec2 mr_baseClipToShell(mr_Relief relief, vec3 origin, vec3 dir, out int entryFace, out bool floorExit) {
    entryFace = MR_RELIEF_MISS;
    floorExit = false;
    return mr_ellipsoidClipToShell(relief, origin, dir);
}

vec3 mr_baseEnd(mr_Relief relief, vec3 q) { return mr_ellipsoidEnd(relief, q); }

mr_BaseFootprint mr_baseFootprintOf(mr_Relief relief, vec3 origin, vec3 dir, float ta, float tb, vec3 ea, vec3 eb) {
    return mr_ellipsoidFootprint(relief, origin, dir, ta, tb, ea, eb);
}

float mr_baseLowest(mr_Relief relief, vec3 origin, vec3 dir, float ta, float tb) {
    return (mr_ellipsoidLowestRadial(origin, dir, ta, tb) - 1.0) / relief.placement.heightScale;
}

// Where the line first comes within the centre distance of height h (padded by the radius
// margin: never later than the exact one).
float mr_baseDescendTo(mr_Relief relief, vec3 origin, vec3 dir, float ta, float tb, float h) {
    float radius = 1.0 + relief.placement.heightScale * h + MR_CURVED_RADIUS_MARGIN;
    vec2 inside = mr_curvedInsideRadius(origin, dir, radius);
    return inside.x > ta && inside.x <= tb ? inside.x : ta;
}

float mr_baseTurnY(vec3 origin, vec3 dir) { return mr_ellipsoidTurnY(origin, dir); }

vec3 mr_baseTopNormal(mr_Relief relief, vec3 q, vec2 gradient) { return mr_ellipsoidTopNormal(relief, q, gradient); }
// Never asked for (no face); the cylinder's cap normal, as a caller would read it.
vec3 mr_baseFaceNormal(mr_Relief relief, int face, vec3 q, vec3 dir) { return vec3(0.0, q.y > 0.0 ? 1.0 : -1.0, 0.0); }

// q = r (sin theta sin phi, cos theta, sin theta cos phi) with r = 1 + s h,
// theta = pi Y / H, phi = 2 pi (X / W - 0.5).
vec3 mr_baseSurfacePoint(mr_Relief relief, vec3 m) {
    float phi = 2.0 * MR_CURVED_PI * (m.x / relief.map.size.x - 0.5), r = 1.0 + relief.placement.heightScale * m.z;
    float theta = MR_CURVED_PI * m.y / relief.map.size.y;
    return r * vec3(sin(theta) * sin(phi), cos(theta), sin(theta) * cos(phi));
}

void mr_baseTangentFrame(mr_Relief relief, vec3 m, out vec3 alongX, out vec3 alongY, out vec3 alongH) {
    float phi = 2.0 * MR_CURVED_PI * (m.x / relief.map.size.x - 0.5), r = 1.0 + relief.placement.heightScale * m.z;
    vec3 ePhi = vec3(cos(phi), 0.0, -sin(phi));
    float theta = MR_CURVED_PI * m.y / relief.map.size.y;
    vec3 w = vec3(sin(theta) * sin(phi), cos(theta), sin(theta) * cos(phi));
    vec3 eTheta = vec3(cos(theta) * sin(phi), -sin(theta), cos(theta) * cos(phi));
    alongX = r * sin(theta) * (2.0 * MR_CURVED_PI / relief.map.size.x) * ePhi;
    alongY = r * (MR_CURVED_PI / relief.map.size.y) * eTheta;
    alongH = relief.placement.heightScale * w;
}

bool mr_baseXIncreases(vec3 origin, vec3 dir) { return mr_curvedXIncreases(origin, dir); }
float mr_baseCrossX(mr_Relief relief, vec3 origin, vec3 dir, float boundary, float after) {
    return mr_curvedCrossX(relief, origin, dir, boundary, after);
}
// A cone of constant Y may be crossed twice along a line: the crossing on the branch
// [from, to] where Y is monotone.
float mr_baseCrossY(mr_Relief relief, vec3 origin, vec3 dir, float boundary, float from, float to) {
    return mr_ellipsoidCrossY(relief, origin, dir, boundary, from, to);
}

const float MR_BASE_FINAL_LENGTH = MR_CURVED_FINAL_LENGTH;

#endif
