// relaxed_cone_step.glsl: relaxed cone stepping, the peer "rcsm" (F. Policarpo,
// M. M. Oliveira, "Relaxed Cone Stepping for Relief Mapping", GPU Gems 3, ch. 18, 2007,
// listing 18-3): `coneSteps` relaxed cone steps from where the ray enters the relief box,
// then `binarySteps` halvings of the last step, as published (15 and 8 there: 23 fetches
// a pixel). The plane only (the host refuses the others).
//
// Inputs in map space (relief_map.glsl): X, Y in texels, h in map height units, the ray
// origin + t dir; `cones` the W x H relaxed cone map, RG16F, (h, r) per sample (peers/
// ConeMap.h: the sample and the relaxed ratio in texels per map height unit), read with
// bilinear filtering at the ray's (X, Y) as the published shader reads its RGBA8 map.
//
// A step from height z over a surface at hs (read from the map) moves the ray by
// dt = r (z - hs) / (run + r drop) (run = |dir.xy|, drop = -dir.z): the published
// d = r height / (ray_ratio + r) in depth, divided by drop. Under the surface the step is
// 0. The hit is where the binary search ends.
//
// Wrong by design: a relaxed cone may hold surface (a ray crosses it at most once inside
// the cone, by construction, but a ray entering it elsewhere may cross more), the binary
// search refines the crossing within the last step only, and 15 steps may not reach the
// surface at grazing angles (the hit then lies above it). No side walls or bottom face: a
// ray whose answer lies past where it leaves the box through a wall is a miss.
#ifndef MICRORELIEF_RELAXED_CONE_STEP_GLSL
#define MICRORELIEF_RELAXED_CONE_STEP_GLSL

#include "fetch_count.glsl"
#include "map_space.glsl"
#include "relief_hit.glsl"
#include "relief_map.glsl"
#include "texture_reads.glsl"

// The relaxed cone map, (h, r), interpolated at map point p (texels).
#ifndef MICRORELIEF_READ_RELAXED_CONE
#define MICRORELIEF_READ_RELAXED_CONE(cones, p, size) textureLod(cones, (p) / (size), 0.0).rg
#endif

// Upper bound on any step count a caller asks for: every loop stays bounded.
#ifndef MICRORELIEF_MAX_CONE_STEPS
#define MICRORELIEF_MAX_CONE_STEPS 2048
#endif

mr_ReliefHit mr_traceRelaxedCones(mr_Relief relief, MICRORELIEF_SAMPLER cones, MICRORELIEF_SAMPLER heights, vec3 origin,
                                  vec3 dir, int coneSteps, int binarySteps) {
    mr_ReliefHit hit = mr_reliefMissHit();
    int entryAxis, exitAxis;
    vec2 range = mr_clipToReliefBox(relief, origin, dir, MICRORELIEF_BASE_WRAPS_U == 1, entryAxis, exitAxis);
    float tNear = max(range.x, 0.0), tFar = range.y;
    if (tNear > tFar || !(dir.z < 0.0)) return hit;  // a ray that does not descend: no surface ahead
    hit.stopLevel = 0;
    float run = length(dir.xy), drop = -dir.z;
    float t = tNear, dt = 0.0;  // dt: the last step that moved
    int steps = clamp(coneSteps, 1, MICRORELIEF_MAX_CONE_STEPS);
    for (int i = 0; i < steps; ++i) {
        vec3 p = origin + t * dir;
        vec2 cone = MICRORELIEF_READ_RELAXED_CONE(cones, p.xy, relief.map.size);
        MICRORELIEF_FETCHED_BOUNDS(1);
        hit.iterations += 1;
        float above = max(p.z - cone.x, 0.0);
        float denominator = run + cone.y * drop;
        float step = denominator > 0.0 ? cone.y * above / denominator : 0.0;
        t += step;
        if (step > 0.0) dt = step;
    }
    // The binary search over the last step, from its middle (listing 18-3). The last step
    // that moved: once a relaxed step has taken the ray under the surface every later one
    // is 0, and the crossing lies in the step that went under (the published d, the last
    // step's, is that step when the ray goes under on the last one).
    float halfStep = 0.5 * dt;
    float tSearch = t - halfStep;
    int halvings = clamp(binarySteps, 0, 32);
    for (int i = 0; i < halvings; ++i) {
        vec3 p = origin + tSearch * dir;
        vec2 cone = MICRORELIEF_READ_RELAXED_CONE(cones, p.xy, relief.map.size);
        MICRORELIEF_FETCHED_BOUNDS(1);
        hit.iterations += 1;
        halfStep *= 0.5;
        tSearch += p.z > cone.x ? halfStep : -halfStep;  // above: forward; on or under: back
    }
    if (tSearch > tFar) {
        if (exitAxis != 2) return hit;  // past a side wall: the silhouette
        tSearch = tFar;                 // the floor
    }
    mr_setMapTopHitAt(hit, relief, heights, tSearch, origin + tSearch * dir);
    return hit;
}

#endif
