// pick.frag: one ray of three's Raycaster traced by the library (src/relief.js: raycast),
// its answer written as the bits of 16 floats into a 16 x 1 RGBA8 target, one float a
// pixel, so that it reads back exactly on any WebGL 2 (no float render target needed).
// Pixel k holds: 0 t, 1 kind (MR_RELIEF_*), 2 exhausted, 3-5 the world hit (origin + t dir,
// as relief.frag computes it), 6-8 the world unit normal, 9-10 uv (three's convention),
// 11 iterations.
uniform vec3 mrPickOrigin;  // world
uniform vec3 mrPickDir;     // world, unit: t is the distance
uniform vec2 mrPickRange;   // the Raycaster's near and far

layout(location = 0) out vec4 packedFloat;

vec4 mrPackFloat(float value) {
    uint bits = floatBitsToUint(value);
    return vec4(float(bits & 255u), float((bits >> 8u) & 255u), float((bits >> 16u) & 255u), float(bits >> 24u)) / 255.0;
}

void main() {
    mr_Relief relief = mrRelief();
    mr_RayQuery query = mr_RayQuery(mrPickRange.x, mrPickRange.y, false, mr_traversalBudget(relief.map), 0.0);
    mr_ReliefHit hit = mr_traceMultilevel(relief, query, mrWindows, mrHeights, mr_baseFramePoint(relief, mrPickOrigin),
                                          mr_baseFrameVector(relief, mrPickDir));
    vec3 world = mrPickOrigin + hit.t * mrPickDir;
    bool found = hit.kind != MR_RELIEF_MISS && !hit.exhausted;
    vec3 normal = found ? mr_reliefWorldNormal(relief, hit) : vec3(0.0);
    vec3 m = mr_baseMapPoint(relief, hit.position);
    float values[12] = float[12](hit.t, float(hit.kind), hit.exhausted ? 1.0 : 0.0, world.x, world.y, world.z,
                                 normal.x, normal.y, normal.z, m.x / mrMapSize.x, 1.0 - m.y / mrMapSize.y,
                                 float(hit.iterations));
    int k = int(gl_FragCoord.x);
    packedFloat = k < 12 ? mrPackFloat(values[k]) : vec4(0.0);
}
