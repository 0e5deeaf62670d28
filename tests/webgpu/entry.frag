// entry.frag: the test entry of glsl_wgsl_equal.py. One ray per pixel through the pixel's
// centre, traced by the multilevel method, its hard and soft self-shadows, its albedo and its
// shading, every answer written out as floats (four RGBA32F targets). The same GLSL for
// WebGL 2 (assembled as ES 3.00, the library's default reads) and, with VULKAN defined, for
// naga's GLSL front end and so WGSL: WGSL has no combined texture-samplers, so the library's
// read hooks (texture_reads.glsl, albedo's) take textures without samplers there, and the
// albedo a separate sampler.
#ifdef VULKAN
// The reads as microrelief-three's WGSL makes them (scripts/wgsl.mjs: kWebGpuHooks): the
// heights and the pyramid by texelFetch without a sampler (WGSL's textureLoad), four reads a
// cell; the albedo through a sampler. mrNearest stays bound (binding 4), unused.
#extension GL_EXT_samplerless_texture_functions : require
layout(set = 0, binding = 4) uniform sampler mrNearest;
layout(set = 0, binding = 5) uniform sampler mrAlbedoSampler;
#define MICRORELIEF_SAMPLER texture2D
#define MICRORELIEF_TEXTURE_GATHER 0
#define MICRORELIEF_READ_SAMPLE(heights, texel) texelFetch(heights, texel, 0).r
#define MICRORELIEF_READ_PYRAMID(pyramid, texel, level, levelSize) texelFetch(pyramid, texel, level).r
#define MICRORELIEF_ALBEDO_TEXTURE texture2D
#define MICRORELIEF_ALBEDO_SAMPLED(t) sampler2D(t, mrAlbedoSampler)
#define MR_TEXTURE(n) layout(set = 0, binding = n) uniform texture2D
#define MR_BLOCK layout(set = 0, binding = 3, std140) uniform
#else
#define MR_TEXTURE(n) uniform sampler2D
#define MR_BLOCK layout(std140) uniform
#endif
#include "microrelief/multilevel_trace.glsl"
#include "microrelief/shading.glsl"
#include "microrelief/shadow.glsl"
#include "microrelief/albedo.glsl"

MR_TEXTURE(0) mrHeights;
MR_TEXTURE(1) mrWindows;
MR_TEXTURE(2) mrAlbedo;
MR_BLOCK Params {
    mat4 objectToWorld;
    mat4 worldToObject;
    vec4 frame;      // xyz: frameScale, w: heightScale
    vec4 map;        // xy: map size, z: maxHeight
    ivec4 pyramid;   // xy: pyramid size, z: level count
    vec4 range;      // x, y: t range; z: the light's tan radius; w: heightToObject
    vec4 light;      // xyz: towards the light, world
    vec4 rayOrigin, rayOriginDx, rayOriginDy, rayDir, rayDirDx, rayDirDy;
    vec4 viewport;   // xy: size in pixels
} P;

layout(location = 0) out vec4 outHit;     // t, kind, exhausted (1 primary, 2 shadow), hard shadow
layout(location = 1) out vec4 outNormal;  // world normal, soft shadow
layout(location = 2) out vec4 outColor;   // shaded colour, albedo's red
layout(location = 3) out vec4 outStats;   // iterations, stop level, frame position x, y

void main() {
    vec2 ndc = gl_FragCoord.xy / P.viewport.xy * 2.0 - 1.0;
    vec3 origin = P.rayOrigin.xyz + ndc.x * P.rayOriginDx.xyz + ndc.y * P.rayOriginDy.xyz;
    vec3 dir = P.rayDir.xyz + ndc.x * P.rayDirDx.xyz + ndc.y * P.rayDirDy.xyz;
    mr_Relief relief = mr_Relief(mr_ReliefMap(P.map.xy, P.pyramid.xy, P.pyramid.z, P.map.z, ivec2(1)),
                                 mr_ReliefPlacement(P.objectToWorld, P.worldToObject, P.frame.w, P.frame.xyz));
    mr_RayQuery query = mr_RayQuery(P.range.x, P.range.y, false, mr_traversalBudget(relief.map), 0.0);
    mr_ReliefHit hit = mr_traceMultilevel(relief, query, mrWindows, mrHeights, mr_baseFramePoint(relief, origin),
                                          mr_baseFrameVector(relief, dir));
    outHit = vec4(hit.t, float(hit.kind), hit.exhausted ? 1.0 : 0.0, 0.0);
    outNormal = vec4(0.0);
    outColor = vec4(0.0);
    outStats = vec4(float(hit.iterations), float(hit.stopLevel), hit.position.xy);
    if (hit.kind == MR_RELIEF_MISS) return;
    vec3 n = mr_reliefWorldNormal(relief, hit);
    bool exhausted = false;
    vec3 toLight = mr_baseFrameVector(relief, P.light.xyz);
    float hard = mr_hardShadow(relief, mrWindows, mrHeights, hit, toLight, MR_T_INFINITY, exhausted);
    float soft = mr_softShadow(relief, mrWindows, mrHeights, hit, toLight, MR_T_INFINITY, P.range.z, P.range.w,
                               length(mat3(P.worldToObject) * P.light.xyz), exhausted);
    vec2 pixel = 2.0 / P.viewport.xy;
    vec3 albedo = mr_surfaceAlbedo(mrAlbedo, relief, hit, dir, n, P.rayDirDx.xyz * pixel.x, P.rayDirDy.xyz * pixel.y, false);
    vec3 c = mr_shadeRelief(mr_ReliefMaterial(albedo, 0.25, 48.0), n, normalize(P.light.xyz), normalize(-dir), vec3(hard));
    outHit.z += exhausted ? 2.0 : 0.0;
    outHit.w = hard;
    outNormal = vec4(n, soft);
    outColor = vec4(c, albedo.r);
}
