// layer_march.glsl: the tangent-space ray march shared by the step-based peers (steep
// parallax, parallax occlusion, relief mapping): the ray sampled where it crosses fixed
// depth layers below the proxy, the top face h = maxHeight of the relief box.
//
// Inputs in map space (relief_map.glsl): X, Y in texels, h in map height units, the ray
// origin + t dir. Depth below the proxy is d = maxHeight - h; `layers` planes split
// d in [0, maxHeight] evenly (McGuire & McGuire 2005; Tatarchuk 2006; Policarpo et al.
// 2005 all march this way). Samples read the bilinear surface (bilinear_patch.glsl).
//
// These methods know only the top surface: no side walls, no bottom face. A ray that
// starts under the surface (entering through a wall or the bottom) stops at its first
// sample; one that does not descend never crosses a layer; one that leaves the box
// through a wall before going under is a miss (the silhouette).
#ifndef MICRORELIEF_LAYER_MARCH_GLSL
#define MICRORELIEF_LAYER_MARCH_GLSL

#include "relief_patch.glsl"
#include "relief_hit.glsl"
#include "relief_map.glsl"
#include "texture_reads.glsl"

// Upper bound on any sample count a caller asks for: every loop stays bounded.
#ifndef MICRORELIEF_MAX_LAYERS
#define MICRORELIEF_MAX_LAYERS 2048
#endif

// One sample of the march: ray parameter t and g = surface height - ray height
// (g >= 0: on or under the surface, inside the solid).
struct mr_LayerSample {
    float t;
    float g;
};

mr_LayerSample mr_layerSampleAt(mr_Relief relief, MICRORELIEF_SAMPLER heights, vec3 origin, vec3 dir, float t,
                          inout mr_ReliefHit hit) {
    vec3 p = origin + t * dir;
    hit.iterations += 1;
    return mr_LayerSample(t, mr_reliefHeight(relief, heights, p.xy) - p.z);
}

// The ray direction in the tangent frame of the published methods: map (X, Y, h) axes in
// world units (map_space.glsl), unit length. Its z is the cosine to the base normal.
vec3 mr_tangentSpaceDirection(mr_Relief relief, vec3 dir) {
    vec3 w = vec3(dir.xy / max(relief.map.size.x, relief.map.size.y), dir.z * relief.placement.heightScale);
    return w / max(length(w), 1e-30);
}

// Marches the layers from where the ray enters the box. True when a sample lies under
// the surface: `below` is the first such sample and `above` the one before it (equal
// to `below` when the very first sample is under). False for a miss.
bool mr_marchLayers(mr_Relief relief, MICRORELIEF_SAMPLER heights, vec3 origin, vec3 dir, int layers,
                 inout mr_ReliefHit hit, out mr_LayerSample above, out mr_LayerSample below) {
    int entryAxis, exitAxis;
    vec2 range = mr_clipToReliefBox(relief, origin, dir, MICRORELIEF_BASE_WRAPS_U == 1, entryAxis, exitAxis);
    float tNear = max(range.x, 0.0), tFar = range.y;
    above = mr_LayerSample(tNear, -1.0);
    below = above;
    if (tNear > tFar) return false;
    hit.stopLevel = 0;
    below = mr_layerSampleAt(relief, heights, origin, dir, tNear, hit);
    above = below;
    if (below.g >= 0.0) return true;
    // Layers lie below the entry: a ray that does not descend (or a flat box) never
    // reaches one, and the layer step (thickness / -dir.z) needs dir.z < 0.
    int count = clamp(layers, 1, MICRORELIEF_MAX_LAYERS);
    float thickness = relief.map.maxHeight / float(count);
    if (!(dir.z < 0.0) || !(thickness > 0.0)) return false;
    // The first layer plane strictly below the entry (layer 0 is the proxy itself).
    float entryDepth = relief.map.maxHeight - (origin.z + tNear * dir.z);
    int first = clamp(int(floor(entryDepth / thickness)) + 1, 1, count);
    bool floorExit = exitAxis == 2;  // h = 0 inside the footprint: the last layer
    for (int layer = first; layer <= count; ++layer) {
        bool floorLayer = floorExit && layer == count;  // h = 0: in the solid, always
        float layerHeight = relief.map.maxHeight - float(layer) * thickness;
        float t = floorLayer ? tFar : max((layerHeight - origin.z) / dir.z, tNear);
        if (t > tFar) {
            if (!floorExit) return false;  // left through a side wall: the silhouette
            t = tFar;                       // rounded past the floor
        }
        above = below;
        below = mr_layerSampleAt(relief, heights, origin, dir, t, hit);
        if (floorLayer) below.g = max(below.g, 0.0);  // rounding of h at tFar
        if (below.g >= 0.0) return true;
    }
    return false;  // out of layers
}

#endif
