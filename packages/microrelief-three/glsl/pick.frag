// pick.frag: rays traced by the library for three's Raycaster and for batches of rays
// (src/relief.js: raycast, traceRays), the answers written as the bits of floats into an
// RGBA8 target, one float a pixel, so that they read back exactly on any WebGL 2 (no float
// render target needed). The rays are the texels of two RGBA32F textures of W x H: origin
// and tMin, direction and tMax (world about the first ray's origin, src/relief.js
// traceRays; t in units of the direction's length). The target is
// W x 12 H: rows [k H, (k + 1) H) hold field k of every ray: 0 t, 1 kind (MR_RELIEF_*),
// 2 exhausted, 3-5 the world hit (origin + t dir, as relief.frag computes it), 6-8 the world
// unit normal, 9-10 uv (three's convention), 11 iterations.
uniform sampler2D mrRayOrigins;
uniform sampler2D mrRayDirections;
uniform int mrRayRows;  // H

layout(location = 0) out vec4 packedFloat;

vec4 mrPackFloat(float value) {
    uint bits = floatBitsToUint(value);
    return vec4(float(bits & 255u), float((bits >> 8u) & 255u), float((bits >> 16u) & 255u), float(bits >> 24u)) / 255.0;
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    int field = pixel.y / mrRayRows;
    ivec2 ray = ivec2(pixel.x, pixel.y - field * mrRayRows);
    vec4 origin = texelFetch(mrRayOrigins, ray, 0), dir = texelFetch(mrRayDirections, ray, 0);
    mr_Relief relief = mrRelief();
    mr_RayQuery query = mr_RayQuery(origin.w, dir.w, false, mr_traversalBudget(relief.map), 0.0);
    mr_ReliefHit hit = mr_traceMultilevel(relief, query, mrWindows, mrHeights, mr_baseFramePoint(relief, origin.xyz),
                                          mr_baseFrameVector(relief, dir.xyz));
    vec3 world = origin.xyz + hit.t * dir.xyz;
    bool found = hit.kind != MR_RELIEF_MISS && !hit.exhausted;
    vec3 normal = found ? mr_reliefWorldNormal(relief, hit) : vec3(0.0);
    vec3 m = mr_baseMapPoint(relief, hit.position);
    float values[12] = float[12](hit.t, float(hit.kind), hit.exhausted ? 1.0 : 0.0, world.x, world.y, world.z,
                                 normal.x, normal.y, normal.z, m.x / mrMapSize.x, 1.0 - m.y / mrMapSize.y,
                                 float(hit.iterations));
    packedFloat = mrPackFloat(values[clamp(field, 0, 11)]);
}
