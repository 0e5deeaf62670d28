// parallax_offset.glsl: parallax mapping with offset limiting, the peer "offset" of
// issue 5 (Kaneko et al., "Detailed Shape Representation with Parallax Mapping", ICAT
// 2001; T. Welsh, "Parallax Mapping with Offset Limiting: A Per-Pixel Approximation of
// Uneven Surfaces", Infiscape 2004).
//
// Inputs in map space (relief_map.glsl): X, Y in texels, h in map height units, the ray
// origin + t dir (t as in world space); `heights` the W x H samples (bilinear_patch.glsl).
// One height h0 is read where the ray enters the relief box (normally the proxy, the top
// face h = maxHeight). Parallax mapping moves (X, Y) along the view direction by the
// depth d = h_entry - h0 times V.xy / V.z, V the unit tangent-space view vector; Welsh's
// offset limiting drops the division by V.z, so the shift never exceeds d (measured in
// world units) and grazing views do not swim. The hit is reported at the shifted (X, Y)
// and the sampled height h0, with the normal read there; t is the ray's parameter at
// height h0 (where an unlimited offset would have put the point, useful for depth).
//
// Wrong by design: one sample, so no occlusion and no self-shadowing; the position is
// off the ray (offset limiting) and ignores the height at the shifted point; steep
// relief shifts too little; no side walls or bottom face. A shifted point outside the
// footprint is a miss (the silhouette); a ray that does not go down is a miss unless it
// enters under the surface (then the hit is that entry point).
#ifndef MICRORELIEF_PARALLAX_OFFSET_GLSL
#define MICRORELIEF_PARALLAX_OFFSET_GLSL

#include "relief_patch.glsl"
#include "layer_march.glsl"
#include "relief_hit.glsl"
#include "relief_map.glsl"
#include "texture_reads.glsl"

mr_ReliefHit mr_traceParallaxOffset(mr_Relief relief, MICRORELIEF_SAMPLER heights, vec3 origin, vec3 dir) {
    mr_ReliefHit hit = mr_reliefMissHit();
    int entryAxis, exitAxis;
    vec2 range = mr_clipToReliefBox(relief, origin, dir, MICRORELIEF_BASE_WRAPS_U == 1, entryAxis, exitAxis);
    float tNear = max(range.x, 0.0);
    if (tNear > range.y) return hit;
    vec3 entry = origin + tNear * dir;
    hit.iterations = 1;
    hit.stopLevel = 0;
    float h0 = mr_reliefHeight(relief, heights, entry.xy);
    if (entry.z <= h0) {
        mr_setMapTopHitAt(hit, relief, heights, tNear, entry);  // entered under the surface
        return hit;
    }
    if (!(dir.z < 0.0)) return hit;
    // Welsh 2004: shift = d V.xy, not d V.xy / V.z, with d and V in world units; here V
    // points along the ray (into the relief), so the shift is away from the eye.
    vec3 view = mr_tangentSpaceDirection(relief, dir);
    float depthInTexels = (entry.z - h0) * relief.placement.heightScale * max(relief.map.size.x, relief.map.size.y);
    vec2 shifted = entry.xy + depthInTexels * view.xy;
    bool inFootprint =
        all(greaterThanEqual(shifted, vec2(0.0))) && all(lessThanEqual(shifted, relief.map.size));
    if (!inFootprint) return hit;
    mr_setMapTopHitAt(hit, relief, heights, (h0 - origin.z) / dir.z, vec3(shifted, h0));
    return hit;
}

#endif
