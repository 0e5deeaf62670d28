// base_cylinder.glsl: a cylinder as the base surface (base_surface.glsl; the C++ copy is
// src/core/base/CylinderSurface.cpp). In the canonical frame q = (x / R, 2 y / L, z / R) the
// column has radius 1 about the y axis and flat caps at y = +-1; v = (1 - q.y) / 2 runs
// down the axis; the height sets the distance from the axis, |q.xz| = 1 + s h.
#ifndef MICRORELIEF_BASE_CYLINDER_GLSL
#define MICRORELIEF_BASE_CYLINDER_GLSL

#include "base_curved.glsl"
#include "relief_map.glsl"

// Its traits (base_surface.glsl): u wraps round the axis across the seam, v clamps (at the caps),
// and the ray's path over the map is a curve (leaf_walk.glsl subdivides a leaf's stretches).
#define MICRORELIEF_BASE_WRAPS_U 1
#define MICRORELIEF_BASE_WRAPS_V 0
#define MICRORELIEF_BASE_STRAIGHT_PATH 0

float mr_cylinderRadial(vec3 q) { return length(q.xz); }
float mr_cylinderMapY(mr_Relief relief, vec3 q) { return relief.map.size.y * 0.5 * (1.0 - q.y); }

// The smallest distance from the axis over [ta, tb]: |p_xz(t)| is convex along a line,
// so its minimum is at the nearest point, clamped to the segment. Exact; the margin
// covers rounding.
float mr_cylinderLowestRadial(vec3 origin, vec3 dir, float ta, float tb) {
    float dd = dot(dir.xz, dir.xz);
    float t = dd > 0.0 ? clamp(-dot(origin.xz, dir.xz) / dd, ta, tb) : ta;
    return length(origin.xz + t * dir.xz) - MR_CURVED_RADIUS_MARGIN;
}


// The t at which the line crosses the plane of constant Y = boundary (once at most, so
// any t, as for mr_curvedCrossX), MR_NEVER where it is parallel.
float mr_cylinderCrossY(mr_Relief relief, vec3 origin, vec3 dir, float boundary) {
    if (dir.y == 0.0) return MR_NEVER;
    return (1.0 - 2.0 * boundary / relief.map.size.y - origin.y) / dir.y;
}

// The bounding shell: the slab |y| <= 1 and the cylinder of radius 1 + s maxHeight, a
// convex region met in one interval; the later of the two entries names the face (a cap
// or the shell, MR_RELIEF_MISS, where the traversal starts).
vec2 mr_cylinderClipToShell(mr_Relief relief, vec3 origin, vec3 dir, out int entryFace) {
    entryFace = MR_RELIEF_MISS;
    vec2 side = mr_curvedInsideRadius(vec3(origin.x, 0.0, origin.z), vec3(dir.x, 0.0, dir.z),
                                   1.0 + relief.placement.heightScale * relief.map.maxHeight);
    if (dir.y == 0.0) return abs(origin.y) > 1.0 ? vec2(1.0, 0.0) : side;
    float t0 = (-1.0 - origin.y) / dir.y, t1 = (1.0 - origin.y) / dir.y;
    vec2 slab = vec2(min(t0, t1), max(t0, t1));
    if (slab.x > side.x) entryFace = MR_RELIEF_CAP;
    return vec2(max(side.x, slab.x), min(side.y, slab.y));
}

// A segment's ends as (X, Y, distance from the axis), what its footprint is made of.
vec3 mr_cylinderEnd(mr_Relief relief, vec3 q) { return vec3(mr_curvedMapX(relief, q), mr_cylinderMapY(relief, q), mr_cylinderRadial(q)); }

// The footprint of [ta, tb] from its ends `ea`, `eb` (mr_cylinderEnd): Y is linear in t, so
// its range is that of the ends.
mr_BaseFootprint mr_cylinderFootprint(mr_Relief relief, vec3 origin, vec3 dir, float ta, float tb, vec3 ea, vec3 eb) {
    vec2 x = mr_curvedRangeX(relief, ea.x, eb.x);
    vec2 y = vec2(min(ea.y, eb.y), max(ea.y, eb.y)) + vec2(-1.0, 1.0) * mr_curvedMarginY(relief);
    float lowest = (mr_cylinderLowestRadial(origin, dir, ta, tb) - 1.0) / relief.placement.heightScale;
    return mr_BaseFootprint(vec2(x.x, y.x), vec2(x.y, y.y), lowest, abs(eb.z - ea.z) / relief.placement.heightScale);
}

// q = rho e_rho(phi) + y e_y with rho = 1 + s h: the outward normal is rho e_rho - rho_phi
// e_phi - rho rho_y e_y, with rho_phi = s W / 2 pi dh/dX and rho_y = -s H / 2 dh/dY.
vec3 mr_cylinderTopNormal(mr_Relief relief, vec3 q, vec2 gradient) {
    float rho = mr_cylinderRadial(q);
    if (rho == 0.0) return vec3(0.0, 1.0, 0.0);
    vec3 eRho = vec3(q.x, 0.0, q.z) / rho, ePhi = vec3(q.z, 0.0, -q.x) / rho;
    float rhoPhi = relief.placement.heightScale * relief.map.size.x / (2.0 * MR_CURVED_PI) * gradient.x;
    float rhoY = -relief.placement.heightScale * relief.map.size.y * 0.5 * gradient.y;
    return rho * eRho - rhoPhi * ePhi - vec3(0.0, rho * rhoY, 0.0);
}

// Frame point q moved `by` map units of height away from the axis (s by in the frame).
vec3 mr_cylinderRaise(mr_Relief relief, vec3 q, float by) {
    float rho = mr_cylinderRadial(q);
    if (rho == 0.0) return q;
    vec2 xz = q.xz * (1.0 + relief.placement.heightScale * by / rho);
    return vec3(xz.x, q.y, xz.y);
}

vec3 mr_cylinderFaceNormal(vec3 q) { return vec3(0.0, q.y > 0.0 ? 1.0 : -1.0, 0.0); }

// base_surface.glsl's set of mr_base* functions, for the cylinder.
vec3 mr_baseObjectToFrame(mr_Relief relief, vec3 object) { return mr_curvedFramePoint(relief, object); }
vec3 mr_baseObjectToFrameVector(mr_Relief relief, vec3 object) { return mr_curvedFrameVector(relief, object); }
vec3 mr_baseFrameToObject(mr_Relief relief, vec3 q) { return mr_curvedObjectPoint(relief, q); }
vec3 mr_baseObjectNormal(mr_Relief relief, vec3 n) { return mr_curvedObjectNormal(relief, n); }

float mr_baseMapY(mr_Relief relief, vec3 q) { return mr_cylinderMapY(relief, q); }
vec3 mr_baseMapPoint(mr_Relief relief, vec3 q) {
    return vec3(mr_curvedMapX(relief, q), mr_cylinderMapY(relief, q), (mr_cylinderRadial(q) - 1.0) / relief.placement.heightScale);
}
vec2 mr_baseMapMargin(mr_Relief relief) { return vec2(mr_curvedMarginX(relief), mr_curvedMarginY(relief)); }
vec3 mr_baseRaise(mr_Relief relief, vec3 q, float by) { return mr_cylinderRaise(relief, q, by); }

vec2 mr_baseClipToShell(mr_Relief relief, vec3 origin, vec3 dir, out int entryFace, out bool floorExit) {
    floorExit = false;
    return mr_cylinderClipToShell(relief, origin, dir, entryFace);
}

vec3 mr_baseEnd(mr_Relief relief, vec3 q) { return mr_cylinderEnd(relief, q); }

mr_BaseFootprint mr_baseFootprintOf(mr_Relief relief, vec3 origin, vec3 dir, float ta, float tb, vec3 ea, vec3 eb) {
    return mr_cylinderFootprint(relief, origin, dir, ta, tb, ea, eb);
}

float mr_baseLowest(mr_Relief relief, vec3 origin, vec3 dir, float ta, float tb) {
    return (mr_cylinderLowestRadial(origin, dir, ta, tb) - 1.0) / relief.placement.heightScale;
}

// Where the line first comes within the axis distance of height h (padded by the radius
// margin: never later than the exact one).
float mr_baseDescendTo(mr_Relief relief, vec3 origin, vec3 dir, float ta, float tb, float h) {
    float radius = 1.0 + relief.placement.heightScale * h + MR_CURVED_RADIUS_MARGIN;
    vec2 inside = mr_curvedInsideRadius(vec3(origin.x, 0.0, origin.z), vec3(dir.x, 0.0, dir.z), radius);
    return inside.x > ta && inside.x <= tb ? inside.x : ta;
}

// Y runs along the axis, linear along a line: it never turns.
float mr_baseTurnY(vec3 origin, vec3 dir) { return MR_NEVER; }

vec3 mr_baseTopNormal(mr_Relief relief, vec3 q, vec2 gradient) { return mr_cylinderTopNormal(relief, q, gradient); }
vec3 mr_baseFaceNormal(mr_Relief relief, int face, vec3 q, vec3 dir) { return mr_cylinderFaceNormal(q); }

// q = (r sin phi, 1 - 2 Y / H, r cos phi) with r = 1 + s h, phi = 2 pi (X / W - 0.5).
vec3 mr_baseSurfacePoint(mr_Relief relief, vec3 m) {
    float phi = 2.0 * MR_CURVED_PI * (m.x / relief.map.size.x - 0.5), r = 1.0 + relief.placement.heightScale * m.z;
    return vec3(r * sin(phi), 1.0 - 2.0 * m.y / relief.map.size.y, r * cos(phi));
}

void mr_baseTangentFrame(mr_Relief relief, vec3 m, out vec3 alongX, out vec3 alongY, out vec3 alongH) {
    float phi = 2.0 * MR_CURVED_PI * (m.x / relief.map.size.x - 0.5), r = 1.0 + relief.placement.heightScale * m.z;
    vec3 ePhi = vec3(cos(phi), 0.0, -sin(phi));
    alongX = r * (2.0 * MR_CURVED_PI / relief.map.size.x) * ePhi;
    alongY = vec3(0.0, -2.0 / relief.map.size.y, 0.0);
    alongH = relief.placement.heightScale * vec3(sin(phi), 0.0, cos(phi));
}

bool mr_baseXIncreases(vec3 origin, vec3 dir) { return mr_curvedXIncreases(origin, dir); }
float mr_baseCrossX(mr_Relief relief, vec3 origin, vec3 dir, float boundary, float after) {
    return mr_curvedCrossX(relief, origin, dir, boundary, after);
}
// Each plane of constant Y is crossed once along a line (any t).
float mr_baseCrossY(mr_Relief relief, vec3 origin, vec3 dir, float boundary, float from, float to) {
    return mr_cylinderCrossY(relief, origin, dir, boundary);
}

const float MR_BASE_FINAL_LENGTH = MR_CURVED_FINAL_LENGTH;

#endif
