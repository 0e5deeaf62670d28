// relief_query.glsl: what one ray asks of the relief (mr_RayQuery), apart from the relief
// itself (mr_Relief, relief_map.glsl): the part of the ray that counts, whether the
// closest hit or any hit is wanted, the traversal's budget and its level of detail. A
// primary ray asks for the closest hit over [0, inf); a shadow ray for any hit between
// just off its surface and its light; an engine's own ray for whatever range it has.
//
// The exact tracers (mr_traceMultilevel, mr_traceMaxMip) take a query; the step-based
// peers take a step count instead and know no range.
#ifndef MICRORELIEF_RELIEF_QUERY_GLSL
#define MICRORELIEF_RELIEF_QUERY_GLSL

#include "relief_map.glsl"

struct mr_RayQuery {
    // The answer is the first point of the closed solid on the ray with t in [tMin, tMax]
    // (t in units of the ray direction's length): where the ray comes in through the
    // surface, a wall, the bottom or a cap, or the ray's start at tMin when that already
    // lies in the solid.
    float tMin;
    float tMax;
    // Any hit (a shadow ray's question: is anything in the way?): the tracer stops at the
    // first hit it confirms, which for these near-first traversals is the closest one,
    // and reports its t and position but no normal.
    bool anyHit;
    // The traversal's budget of segments (mr_traversalBudget); running out is reported
    // (mr_ReliefHit.exhausted), never silent.
    int maxIterations;
    // Accuracy-controlled level of detail (multilevel only): a level-k window at ray
    // parameter t may stand for the surface once 2^(k+1) <= lodCone * t; 0 is exact
    // (multilevel_trace.glsl).
    float lodCone;
};

// A t beyond every ray's end.
const float MR_T_INFINITY = 3.4e38;

// The budget a traversal of a W x H map gets (the C++ traversalBudget, the page's): a ray
// visits about two segments per finest texel it crosses plus their ancestors, so
// 8 (W + H) + 256 is several times what any ray needs; running out means a bug.
const int MR_BUDGET_PER_TEXEL = 8;
const int MR_BUDGET_BASE = 256;

int mr_traversalBudget(mr_ReliefMap map) {
    return MR_BUDGET_PER_TEXEL * (int(map.size.x) + int(map.size.y)) + MR_BUDGET_BASE;
}

// The closest hit over [0, inf), exact, within the map's budget: a primary ray.
mr_RayQuery mr_closestHitQuery(mr_ReliefMap map) {
    return mr_RayQuery(0.0, MR_T_INFINITY, false, mr_traversalBudget(map), 0.0);
}

// Any hit over [tMin, tMax], exact: a shadow ray.
mr_RayQuery mr_anyHitQuery(mr_ReliefMap map, float tMin, float tMax) {
    return mr_RayQuery(tMin, tMax, true, mr_traversalBudget(map), 0.0);
}

#endif
