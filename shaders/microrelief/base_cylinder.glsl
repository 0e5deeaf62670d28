// base_cylinder.glsl: a cylinder as the base surface (base_surface.glsl; the C++ copy is
// src/base/CylinderSurface.cpp). In the canonical frame q = (x / R, 2 y / L, z / R) the
// column has radius 1 about the y axis and flat caps at y = +-1; v = (1 - q.y) / 2 runs
// down the axis; the height sets the distance from the axis, |q.xz| = 1 + s h.
#ifndef MICRORELIEF_BASE_CYLINDER_GLSL
#define MICRORELIEF_BASE_CYLINDER_GLSL

#include "base_curved.glsl"
#include "relief_map.glsl"

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
// any t, as for mr_curvedCrossX), MR_CURVED_NEVER where it is parallel.
float mr_cylinderCrossY(mr_Relief relief, vec3 origin, vec3 dir, float boundary) {
    if (dir.y == 0.0) return MR_CURVED_NEVER;
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

#endif
