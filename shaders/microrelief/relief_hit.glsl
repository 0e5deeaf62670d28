// relief_hit.glsl: filling a ReliefHit (multilevel_trace.glsl) for the peer methods of
// issue 5: the empty answer, and a top-surface hit at any map point.
//
// Inputs are in map space (relief_map.glsl): X, Y in texels, h in map height units; t is
// the ray parameter, the same in world and map space. The top normal follows setTopHit:
// the unnormalised (-dh/dX, -dh/dY, 1) of the bilinear surface (bilinear_patch.glsl).
#ifndef MICRORELIEF_RELIEF_HIT_GLSL
#define MICRORELIEF_RELIEF_HIT_GLSL

#include "bilinear_patch.glsl"
#include "multilevel_trace.glsl"
#include "relief_map.glsl"

// No hit yet, nothing read.
ReliefHit reliefMissHit() {
    ReliefHit hit;
    hit.kind = RELIEF_MISS;
    hit.t = -1.0;
    hit.position = vec3(0.0);
    hit.normal = vec3(0.0, 0.0, 1.0);
    hit.iterations = 0;
    hit.fetches = 0;
    hit.stopLevel = -1;
    hit.exhausted = false;
    return hit;
}

// A top-surface hit reported at `position` with ray parameter `t`, the normal taken from
// the bilinear gradient at position.xy (what a normal map would give there). The point
// need not lie on the ray: the offset methods report one that does not.
void setTopHitAt(inout ReliefHit hit, ReliefMap map, sampler2D heights, float t, vec3 position) {
    ivec2 cell = cellAt(position.xy);
    vec4 corners = cellCorners(map, heights, cell, hit.fetches);
    // setTopHit with a zero direction reports `position` itself, with its border rule.
    setTopHit(hit, map, position, vec3(0.0), 0.0, corners, cell);
    hit.t = t;
}

#endif
