// normal_mapping.glsl: normal mapping, the peer "normal" of issue 5: the relief is not
// displaced at all; the flat proxy (the top face h = maxHeight of the relief box) is
// shaded with the height map's normal at the point the ray meets it (bump mapping,
// Blinn 1978; normal maps, Cohen, Olano & Manocha 1998 and Peercy, Airey & Cabral 1997).
//
// Inputs in map space (relief_map.glsl): X, Y in texels, h in map height units, the ray
// origin + t dir (t as in world space); `heights` the W x H samples (bilinear_patch.glsl).
// Output: a MR_RELIEF_TOP hit on the plane h = maxHeight inside the footprint, seen from
// above, with the bilinear surface's normal there; a miss otherwise.
//
// Wrong by design: no parallax, no occlusion, no silhouette, no side walls or bottom
// face; the position is always on the top plane (up to maxHeight above the surface).
#ifndef MICRORELIEF_NORMAL_MAPPING_GLSL
#define MICRORELIEF_NORMAL_MAPPING_GLSL

#include "relief_hit.glsl"
#include "relief_map.glsl"
#include "texture_reads.glsl"

mr_ReliefHit mr_traceNormalMapping(mr_Relief relief, MICRORELIEF_SAMPLER heights, vec3 origin, vec3 dir) {
    mr_ReliefHit hit = mr_reliefMissHit();
    // The proxy is one-sided: only a ray going down meets its front face.
    if (!(dir.z < 0.0)) return hit;
    float t = (relief.map.maxHeight - origin.z) / dir.z;
    vec3 p = origin + t * dir;
    bool inFootprint = all(greaterThanEqual(p.xy, vec2(0.0))) && all(lessThanEqual(p.xy, relief.map.size));
    if (t < 0.0 || !inFootprint) return hit;
    hit.iterations = 1;
    hit.stopLevel = 0;
    mr_setMapTopHitAt(hit, relief, heights, t, vec3(p.xy, relief.map.maxHeight));
    return hit;
}

#endif
