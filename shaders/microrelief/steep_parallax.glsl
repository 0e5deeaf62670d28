// steep_parallax.glsl: steep parallax mapping, the peer "steep" of issue 5 (M. McGuire
// and M. McGuire, "Steep Parallax Mapping", I3D 2005 poster).
//
// Inputs in map space (relief_map.glsl): X, Y in texels, h in map height units, the ray
// origin + t dir (t as in world space); `heights` the W x H samples (bilinear_patch.glsl);
// `layers`, the quality knob: the depth below the proxy (the top face h = maxHeight of the
// relief box) is cut into that many equal layers, and the ray is sampled where it crosses
// each (layer_march.glsl). The first sample on or under the surface is the hit, as is,
// with the normal read there.
//
// Wrong by design: no refinement, so the hit lies up to one layer deep inside the
// relief, and thin features between two samples are stepped over (stair-stepping and
// missed peaks at grazing angles, where a layer spans many texels). No side walls or
// bottom face: a ray that leaves through a wall first is a miss (the silhouette).
#ifndef MICRORELIEF_STEEP_PARALLAX_GLSL
#define MICRORELIEF_STEEP_PARALLAX_GLSL

#include "layer_march.glsl"
#include "relief_hit.glsl"
#include "relief_map.glsl"
#include "texture_reads.glsl"

mr_ReliefHit mr_traceSteepParallax(mr_Relief relief, MICRORELIEF_SAMPLER heights, vec3 origin, vec3 dir, int layers) {
    mr_ReliefHit hit = mr_reliefMissHit();
    mr_LayerSample above, below;
    if (mr_marchLayers(relief, heights, origin, dir, layers, hit, above, below)) {
        mr_setMapTopHitAt(hit, relief, heights, below.t, origin + below.t * dir);
    }
    return hit;
}

#endif
