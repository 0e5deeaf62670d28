// relief_mapping.glsl: relief mapping, the peer "relief" of issue 5 (F. Policarpo, M. M.
// Oliveira, J. L. D. Comba, "Real-Time Relief Mapping on Arbitrary Polygonal Surfaces",
// I3D 2005, sec. 3: linear search, then binary search).
//
// Inputs in map space (relief_map.glsl): X, Y in texels, h in map height units, the ray
// origin + t dir (t as in world space); `heights` the W x H samples (bilinear_patch.glsl).
// `linearSteps` equal depth layers below the proxy (the top face h = maxHeight of the
// relief box) are searched for the first sample under the surface (layer_march.glsl);
// then `binarySteps` halvings of that last interval keep the half whose near end is above
// and far end under the surface. The hit is the last point found under the surface.
//
// Wrong by design: the linear search can step over features thinner than a layer at
// grazing angles (the binary search then refines the wrong crossing); the hit lies up to
// one layer / 2^binarySteps inside the relief. No side walls or bottom face: a ray that
// leaves through a wall first is a miss (the silhouette).
#ifndef MICRORELIEF_RELIEF_MAPPING_GLSL
#define MICRORELIEF_RELIEF_MAPPING_GLSL

#include "layer_march.glsl"
#include "relief_hit.glsl"
#include "relief_map.glsl"
#include "texture_reads.glsl"

// Beyond float precision of the interval: any larger count is clamped to it.
#ifndef MICRORELIEF_MAX_BINARY_STEPS
#define MICRORELIEF_MAX_BINARY_STEPS 32
#endif

mr_ReliefHit mr_traceReliefMapping(mr_Relief relief, MICRORELIEF_SAMPLER heights, vec3 origin, vec3 dir,
                             int linearSteps, int binarySteps) {
    mr_ReliefHit hit = mr_reliefMissHit();
    mr_LayerSample above, below;
    if (!mr_marchLayers(relief, heights, origin, dir, linearSteps, hit, above, below)) return hit;
    int steps = below.t > above.t ? clamp(binarySteps, 0, MICRORELIEF_MAX_BINARY_STEPS) : 0;
    for (int step = 0; step < steps; ++step) {
        float tMiddle = 0.5 * (above.t + below.t);
        mr_LayerSample middle = mr_layerSampleAt(relief, heights, origin, dir, tMiddle, hit);
        if (middle.g >= 0.0) {
            below = middle;
        } else {
            above = middle;
        }
    }
    mr_setMapTopHitAt(hit, relief, heights, below.t, origin + below.t * dir);
    return hit;
}

#endif
