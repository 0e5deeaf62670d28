// parallax_occlusion.glsl: parallax occlusion mapping, the peer "pom" of issue 5
// (N. Tatarchuk, "Dynamic Parallax Occlusion Mapping with Approximate Soft Shadows", I3D
// 2006; Brawley & Tatarchuk, ShaderX3 2004), in the form Unity HDRP and Unreal ship.
//
// Inputs in map space (relief_map.glsl): X, Y in texels, h in map height units, the ray
// origin + t dir (t as in world space); `heights` the W x H samples (bilinear_patch.glsl);
// `minSamples`, `maxSamples`: the layer count is mix(maxSamples, minSamples, |V.N|) with V
// the unit tangent-space view vector and N the base normal, so grazing views take more.
// A linear search over the layers (layer_march.glsl) finds the first sample under the
// surface; the hit is where the two linear height profiles of that last segment cross,
// the ray's and the one between the two surface samples (Tatarchuk 2006, sec. 3).
//
// Wrong by design: the surface between two samples is taken as a straight line, so the
// hit is approximate (good on smooth relief) and features thinner than a layer are still
// missed at grazing angles. No side walls or bottom face: a ray that leaves through a
// wall first is a miss (the silhouette).
#ifndef MICRORELIEF_PARALLAX_OCCLUSION_GLSL
#define MICRORELIEF_PARALLAX_OCCLUSION_GLSL

#include "layer_march.glsl"
#include "relief_hit.glsl"
#include "relief_map.glsl"
#include "texture_reads.glsl"

mr_ReliefHit mr_traceParallaxOcclusion(mr_Relief relief, MICRORELIEF_SAMPLER heights, vec3 origin, vec3 dir,
                                 int minSamples, int maxSamples) {
    mr_ReliefHit hit = mr_reliefMissHit();
    float cosView = abs(mr_tangentSpaceDirection(relief, dir).z);
    int layers = int(mix(float(maxSamples), float(minSamples), cosView));
    mr_LayerSample above, below;
    if (!mr_marchLayers(relief, heights, origin, dir, layers, hit, above, below)) return hit;
    // g = surface - ray is linear in t along the segment in this approximation: its root.
    float t = below.t;
    if (below.g > above.g) t = mix(below.t, above.t, below.g / (below.g - above.g));
    mr_setMapTopHitAt(hit, relief, heights, t, origin + t * dir);
    return hit;
}

#endif
