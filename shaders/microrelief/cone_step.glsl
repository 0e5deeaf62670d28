// cone_step.glsl: cone step mapping, the peer "cone" (J. Dummer, "Cone Step
// Mapping: An Iterative Ray-Heightfield Intersection Algorithm", 2006), with cones that
// are conservative for the bilinear surface and an exact end: stepping from cone to cone
// until the ray gets down to a texel's plateau, then the exact first hit over that texel
// square (mr_baseIntersectLeaf, the multilevel method's leaf), and on to the next texel
// where there is none. The plane only (the host refuses the others).
//
// Inputs in map space (relief_map.glsl): X, Y in texels, h in map height units, the ray
// origin + t dir (t as in world space); `cones` the W x H cone map, RG16F, (B_T, r_T) per
// texel square T (peers/ConeMap.h: B_T bounds the surface over T, r_T in texels per map
// height unit; the height scale is in dir.z, so it needs no term here; on the biquadratic
// level the apex raised, mr_coneOfLastLevel), read with
// texelFetch; `heights` the samples (bilinear_patch.glsl). Output, as mr_traceMultilevel's:
// the exact first point t >= 0 of the ray in the solid (top surface, side wall, bottom
// face) and statistics (iterations = texels stepped from; stopLevel 0).
//
// Why a step is safe (ConeMap.h): the surface lies on or under B_T + dist(x, T) / r_T
// everywhere. A ray at a point of T at height z > B_T that moves on by dt covers
// run = |dir.xy| dt horizontally, so it is at most run from T, and it drops by drop dt
// (drop = -dir.z). It stays above the surface while z - drop dt > B_T + run dt / r_T, i.e.
// for dt < (z - B_T) / (run / r_T + drop).
#ifndef MICRORELIEF_CONE_STEP_GLSL
#define MICRORELIEF_CONE_STEP_GLSL

#include "fetch_count.glsl"
#include "leaf_walk.glsl"
#include "relief_hit.glsl"
#include "relief_map.glsl"
#include "relief_query.glsl"
#include "texture_reads.glsl"
#include "variants.glsl"

// A cone map texel (B_T, r_T) at integer texel `texel`.
#ifndef MICRORELIEF_READ_CONE
#define MICRORELIEF_READ_CONE(cones, texel) texelFetch(cones, texel, 0).rg
#endif

// The cone of a texel on the biquadratic last level: the bilinear surface's cone (B_T, r_T)
// with its apex raised by 1/2 texel over r_T. Why that holds: the uniform quadratic
// B-spline of the samples is their bilinear interpolant averaged over the unit square
// centred at the point (per axis, the quadratic B-spline is the hat convolved with the
// unit box; the repeated edge samples are the bilinear surface's clamped edges, and a
// point past the map's edge is no nearer T than its clamp into the map). So with
// h(y) <= B_T + dist(y, T) / r_T for the bilinear h (ConeMap.h), and dist 1-Lipschitz,
//     h_q(x) = mean over u in [-1/2, 1/2]^2 of h(x + u) <= B_T + (dist(x, T) + E|u|) / r_T,
// E|u| = 0.3826 texels: the same cone with the apex 0.3826 / r_T higher. 1/2 here, the rest
// slack for the division (2.5 ulp at most) and the sum, rounded up by 2^-20 relative on
// top (B_T >= 0). Over T itself the piece lies under its Bezier net, whose nine values are
// the bilinear surface's at T's corners, edge midpoints and centre: under B_T already.
// A ratio of 0 (T's column) leaves no cone: every texel is then a leaf.
vec2 mr_coneOfLastLevel(vec2 cone) {
#if MICRORELIEF_INTERPOLATION == MR_INTERPOLATION_BIQUADRATIC
    cone.x = cone.y > 0.0 ? (cone.x + 0.5 / cone.y) * (1.0 + exp2(-20.0)) : MR_NEVER;
#endif
    return cone;
}

// The texel square the ray is in at map point p: on a boundary, the one it moves into.
ivec2 mr_coneTexelAt(mr_Relief relief, vec2 p, vec2 dir) {
    vec2 f = floor(p);
    ivec2 texel = ivec2(f);
    if (p.x == f.x && dir.x < 0.0) texel.x -= 1;
    if (p.y == f.y && dir.y < 0.0) texel.y -= 1;
    return clamp(texel, ivec2(0), ivec2(relief.map.size) - 1);
}

// Where the ray leaves texel square `texel`, per axis (MR_NEVER along an axis it does not
// move in).
vec2 mr_coneTexelExits(ivec2 texel, vec3 origin, vec3 dir) {
    vec2 exits = vec2(MR_NEVER);
    for (int axis = 0; axis < 2; ++axis) {
        if (dir[axis] == 0.0) continue;
        float side = float(texel[axis]) + (dir[axis] > 0.0 ? 1.0 : 0.0);
        exits[axis] = (side - origin[axis]) / dir[axis];
    }
    return exits;
}

// The walk over origin + t dir, t in [0, tFar], of a ray that leaves the box through its
// floor when `floorExit`; fills `hit` with local t.
void mr_walkCones(mr_Relief relief, mr_RayQuery query, MICRORELIEF_SAMPLER cones, MICRORELIEF_SAMPLER heights,
                  vec3 origin, vec3 dir, float tFar, bool floorExit, inout mr_ReliefHit hit) {
    float run = length(dir.xy), drop = -dir.z;
    ivec2 stepDir = ivec2(sign(dir.xy));
    float t = 0.0;
    ivec2 texel = mr_coneTexelAt(relief, origin.xy, dir.xy);
    mr_WalkEnd end = mr_walkEnd();
    hit.stopLevel = 0;
    while (end.iterations < query.maxIterations) {
        end.iterations += 1;
        vec2 cone = mr_coneOfLastLevel(MICRORELIEF_READ_CONE(cones, texel));
        MICRORELIEF_FETCHED_BOUNDS(1);
        vec2 exits = mr_coneTexelExits(texel, origin, dir);
        float tExit = min(max(min(exits.x, exits.y), t), tFar);
        float z = origin.z + t * dir.z;
        bool leaf = true;
        if (z > cone.x) {
            // Above the plateau: the cone's step (the header), infinite where the ray never
            // comes down to the cone. A cone of ratio 0 is T's column: a ray moving across
            // gets no step (run / 0 is +inf), a vertical one falls to the plateau.
            float slope = (run > 0.0 ? run / cone.y : 0.0) + drop;
            float tCone = slope > 0.0 ? t + (z - cone.x) / slope : MR_NEVER;
            if (tCone >= tFar) {
                end.finished = true;  // above the surface to the walk's end
                break;
            }
            if (tCone > tExit) {
                t = tCone;  // out of this texel, anywhere: the texel it lands in
                texel = mr_coneTexelAt(relief, (origin + t * dir).xy, dir.xy);
                continue;
            }
            // The cone ends inside this texel; above the plateau all through it, no leaf.
            leaf = origin.z + tExit * dir.z <= cone.x;
        }
        if (leaf) {
            // At or under the plateau in this texel: the exact first hit over the rest of it.
            // Two locals, copied into end after the call (what out means in GLSL anyway): WGSL
            // refuses two pointer arguments into one variable (docs/webgpu.md).
            mr_ReliefPatch leafPatch;
            ivec2 leafCell;
            end.tHit = mr_baseIntersectLeaf(relief, heights, origin, dir, t, tExit, leafPatch, leafCell);
            end.cellPatch = leafPatch;
            end.cell = leafCell;
            if (end.tHit >= 0.0) {
                end.finished = end.solved = true;
                break;
            }
        }
        if (tExit >= tFar) {
            end.finished = true;
            break;
        }
        // Into the neighbour across the side(s) it leaves by (a 2D DDA step: rounding in
        // the texel found from a point cannot hold the walk at a boundary).
        texel += ivec2(exits.x <= tExit ? stepDir.x : 0, exits.y <= tExit ? stepDir.y : 0);
        if (any(lessThan(texel, ivec2(0))) || any(greaterThanEqual(texel, ivec2(relief.map.size)))) {
            end.finished = true;  // off the map: nothing more to meet (rounding kept tFar ahead)
            break;
        }
        t = tExit;
    }
    // tHit >= 0 only where a leaf solved it.
    mr_finishWalk(hit, relief, query, heights, origin, dir, tFar, floorExit, end);
}

// As mr_traceMultilevel, with the cone map for the pyramid.
mr_ReliefHit mr_traceConeStep(mr_Relief relief, mr_RayQuery query, MICRORELIEF_SAMPLER cones,
                              MICRORELIEF_SAMPLER heights, vec3 origin, vec3 dir) {
    mr_ReliefHit hit = mr_reliefMissHit();
    vec3 start;
    float tStart, span;
    bool floorExit;
    if (mr_enterReliefShell(relief, query, heights, origin, dir, hit, start, tStart, span, floorExit)) {
        mr_walkCones(relief, query, cones, heights, start, dir, span, floorExit, hit);
        mr_measureFromEye(hit, tStart);
    }
    return hit;
}

#endif
