// relief.frag: one ray per pixel through the pixel centre, traced by the multilevel
// method (microrelief/multilevel_trace.glsl) or, for comparison, one of its peers,
// shaded, with the world position of the hit and the traversal's statistics as extra
// outputs. Misses are discarded; hits write gl_FragDepth for the caller's projection and
// depth convention, so the relief depth-composites with other geometry. The colour is
// linear: an sRGB framebuffer encodes it (OffscreenTarget's is one).
//
// Host defines, their values named in microrelief/variants.glsl (MR_METHOD_MAXMIP ...):
// MICRORELIEF_TILING (the map repeated: relief_map.glsl); MICRORELIEF_METHOD (multilevel,
// normal, offset, steep, pom, relief, maxmip, cone, rcsm); MICRORELIEF_BASE (plane,
// cylinder, ellipsoid: base_surface.glsl); MICRORELIEF_COUNT_FETCHES for the
// instrumented variant, which writes texel reads to the statistics and keeps misses (so
// they are counted too);
// MICRORELIEF_SHADOWS (off, hard, soft: shadow.glsl; the exact methods only);
// MICRORELIEF_ALBEDO_MAP (1: the surface's colour from the albedo texture);
// MICRORELIEF_DEPTH_LAYOUT, what the depth written promises against the rasterised
// proxy's (any: nothing; greater or equal; less or equal), which keeps early depth tests
// where the GL has conservative depth (GL 4.2, ARB_conservative_depth);
// MICRORELIEF_PAGED (1: a map larger than one texture, read through pages:
// paged_map.glsl, GLSL 4.30; the multilevel method only).
// MICRORELIEF_COARSE_TILE (T: each pixel's walk starts where the coarse pass found its
// T x T tile's rays may first meet the solid, coarse_start.frag; the multilevel method on
// the plane only; undefined: the single pass).
// variants.glsl is defines only on desktop GL (its precision statements are GLSL ES's, which
// never takes the #extension below), so the #extension may follow it.
#include "microrelief/variants.glsl"
#ifndef MICRORELIEF_DEPTH_LAYOUT
#define MICRORELIEF_DEPTH_LAYOUT MR_DEPTH_LAYOUT_ANY
#endif
#if MICRORELIEF_DEPTH_LAYOUT != MR_DEPTH_LAYOUT_ANY && __VERSION__ < 420 && defined(GL_ARB_conservative_depth)
#extension GL_ARB_conservative_depth : enable
#endif
#if MICRORELIEF_DEPTH_LAYOUT != MR_DEPTH_LAYOUT_ANY && (__VERSION__ >= 420 || defined(GL_ARB_conservative_depth))
#if MICRORELIEF_DEPTH_LAYOUT == MR_DEPTH_LAYOUT_GREATER
layout(depth_greater) out float gl_FragDepth;
#else
layout(depth_less) out float gl_FragDepth;
#endif
#endif

// First: a paged map sets the library's read hooks (texture_reads.glsl).
#include "paged_map.glsl"
#include "microrelief/map_space.glsl"
#include "microrelief/multilevel_trace.glsl"

#include "microrelief/cone_step.glsl"
#include "microrelief/maxmip_trace.glsl"
#include "microrelief/normal_mapping.glsl"
#include "microrelief/parallax_occlusion.glsl"
#include "microrelief/parallax_offset.glsl"
#include "microrelief/relaxed_cone_step.glsl"
#include "microrelief/relief_mapping.glsl"
#include "microrelief/steep_parallax.glsl"
// Every method is included (the host splices includes before the preprocessor runs);
// MICRORELIEF_METHOD picks the one that is called, and the compiler drops the rest.
#ifndef MICRORELIEF_METHOD
#define MICRORELIEF_METHOD MR_METHOD_MULTILEVEL
#endif
// The method's row (variants.glsl: MR_TRAITS_*), what the choices below read.
#if MICRORELIEF_METHOD == MR_METHOD_MULTILEVEL
#define MICRORELIEF_METHOD_TRAITS MR_TRAITS_MULTILEVEL
#elif MICRORELIEF_METHOD == MR_METHOD_NORMAL
#define MICRORELIEF_METHOD_TRAITS MR_TRAITS_NORMAL
#elif MICRORELIEF_METHOD == MR_METHOD_OFFSET
#define MICRORELIEF_METHOD_TRAITS MR_TRAITS_OFFSET
#elif MICRORELIEF_METHOD == MR_METHOD_STEEP
#define MICRORELIEF_METHOD_TRAITS MR_TRAITS_STEEP
#elif MICRORELIEF_METHOD == MR_METHOD_POM
#define MICRORELIEF_METHOD_TRAITS MR_TRAITS_POM
#elif MICRORELIEF_METHOD == MR_METHOD_RELIEF
#define MICRORELIEF_METHOD_TRAITS MR_TRAITS_RELIEF
#elif MICRORELIEF_METHOD == MR_METHOD_MAXMIP
#define MICRORELIEF_METHOD_TRAITS MR_TRAITS_MAXMIP
#elif MICRORELIEF_METHOD == MR_METHOD_CONE
#define MICRORELIEF_METHOD_TRAITS MR_TRAITS_CONE
#elif MICRORELIEF_METHOD == MR_METHOD_RCSM
#define MICRORELIEF_METHOD_TRAITS MR_TRAITS_RCSM
#else
// No apostrophe in the message: naga's preprocessor (the page's WebGPU path) reads the
// lines of a branch not taken too, and refuses a lone quote there.
#error MICRORELIEF_METHOD is none of the MR_METHOD_* values of microrelief/variants.glsl
#endif
// The choices test a trait as (MICRORELIEF_METHOD_TRAITS & MR_TRAIT_X) != 0, spelled out:
// naga's preprocessor (the WGSL translation, docs/webgpu.md) takes no function-like macro
// in an #if.
#ifndef MICRORELIEF_SHADOWS
#define MICRORELIEF_SHADOWS MR_SHADOWS_OFF
#endif
#include "microrelief/albedo.glsl"
#include "microrelief/debug_views.glsl"
#include "microrelief/shading.glsl"
#include "microrelief/shadow.glsl"
#include "relief_parameters.glsl"

// The multilevel elevation map (max_pyramid.glsl), nearest mipmaps: the aligned levels
// (maxmip's quadtree) and the overlapping ones (the multilevel method's windows), on
// texture units 0 and 2; the samples on unit 1 (ReliefShader binds them).
uniform sampler2D maxPyramid;
uniform sampler2D windowPyramid;
uniform sampler2D heightSamples;
uniform sampler2D albedoMap;  // unit 3: the surface's colour over (u, v), mipmapped
uniform sampler2D coneMap;    // unit 4: cone and rcsm's cone map (peers/ConeMap.h), linear
#ifdef MICRORELIEF_COARSE_TILE
uniform sampler2D coarseStart;  // unit 6: the coarse pass's starts, a texel per tile (coarse_start.frag)
#endif

#ifndef MICRORELIEF_ALBEDO_MAP
#define MICRORELIEF_ALBEDO_MAP 0
#endif

// The surface's colour at the hit (microrelief/albedo.glsl, filtered over the pixel's
// footprint from ray differentials), or the uniform albedo without a texture.
vec3 surfaceAlbedo(mr_Relief relief, mr_ReliefHit hit, vec3 dir, vec3 n) {
#if MICRORELIEF_ALBEDO_MAP
    vec2 pixel = 2.0 / viewportSize;
    return mr_surfaceAlbedo(albedoMap, relief, hit, dir, n, cameraRight * pixel.x, cameraUp * pixel.y,
                            albedoFinest != 0);
#else
    return albedo;
#endif
}

mr_ReliefHit traceInFrame(mr_Relief relief, mr_RayQuery query, vec3 origin, vec3 dir) {
#if MICRORELIEF_METHOD == MR_METHOD_NORMAL
    return mr_traceNormalMapping(relief, heightSamples, origin, dir);
#elif MICRORELIEF_METHOD == MR_METHOD_OFFSET
    return mr_traceParallaxOffset(relief, heightSamples, origin, dir);
#elif MICRORELIEF_METHOD == MR_METHOD_STEEP
    return mr_traceSteepParallax(relief, heightSamples, origin, dir, methodSteps);
#elif MICRORELIEF_METHOD == MR_METHOD_POM
    return mr_traceParallaxOcclusion(relief, heightSamples, origin, dir, methodMinSteps, methodSteps);
#elif MICRORELIEF_METHOD == MR_METHOD_RELIEF
    return mr_traceReliefMapping(relief, heightSamples, origin, dir, methodSteps, methodRefineSteps);
#elif MICRORELIEF_METHOD == MR_METHOD_MAXMIP
    return mr_traceMaxMip(relief, query, maxPyramid, heightSamples, origin, dir);
#elif MICRORELIEF_METHOD == MR_METHOD_CONE
    return mr_traceConeStep(relief, query, coneMap, heightSamples, origin, dir);
#elif MICRORELIEF_METHOD == MR_METHOD_RCSM
    return mr_traceRelaxedCones(relief, coneMap, heightSamples, origin, dir, methodSteps, methodRefineSteps);
#else  // MR_METHOD_MULTILEVEL: the row's ladder above refuses any other value
    return mr_traceMultilevel(relief, query, windowPyramid, heightSamples, origin, dir);
#endif
}

// The step-based peers on a curved base, as engines run them there (pom, relief): in the
// base's tangent frame where the ray enters the shell, map space taken as flat from there
// on; their answer, a map point, is then placed on the base (off the ray, like offset's).
#define MICRORELIEF_TANGENT_PEER (!MICRORELIEF_BASE_STRAIGHT_PATH && (MICRORELIEF_METHOD_TRAITS & MR_TRAIT_TANGENT_FRAME) != 0)

mr_ReliefHit traceRay(mr_Relief relief, mr_RayQuery query, vec3 origin, vec3 dir) {
#if MICRORELIEF_TANGENT_PEER
    vec3 localOrigin, localDir;
    float tEntry;
    if (!mr_baseTangentRay(relief, origin, dir, localOrigin, localDir, tEntry)) return mr_reliefMissHit();
    mr_ReliefHit hit = traceInFrame(relief, query, localOrigin, localDir);
    if (hit.kind == MR_RELIEF_TOP) {
        vec3 q = mr_baseSurfacePoint(relief, hit.position);
        hit.normal = mr_baseTopNormal(relief, q, -hit.normal.xy);
        hit.position = q;
        hit.t += tEntry;
    }
    return hit;
#else
    return traceInFrame(relief, query, origin, dir);
#endif
}

// The window depth of world point p as the fixed-function path makes it for the caller's
// projection (viewProjection), clip-space convention (depthZeroToOne) and glDepthRange,
// which reversed-Z needs nothing more for. Held to the promise of the depth layout: the
// proxy face the fragment comes from lies on the ray before the hit (front faces, layout
// greater with a standard depth test) or after it (back faces, from inside the box), so
// the bound only ever moves a hit on that face by rounding.
float windowDepth(vec3 p) {
    vec4 clip = viewProjection * vec4(p, 1.0);
    float ndc = clip.z / clip.w;
    float unit = depthZeroToOne != 0 ? ndc : 0.5 + 0.5 * ndc;
    float depth = clamp(gl_DepthRange.near + gl_DepthRange.diff * unit, 0.0, 1.0);
#if MICRORELIEF_DEPTH_LAYOUT == MR_DEPTH_LAYOUT_GREATER
    depth = max(depth, gl_FragCoord.z);
#elif MICRORELIEF_DEPTH_LAYOUT == MR_DEPTH_LAYOUT_LESS
    depth = min(depth, gl_FragCoord.z);
#endif
    return depth;
}

// How much of the light reaches `hit` (world direction or vector `toLight`): 1 without
// shadows; the hard shadow's 0 or 1, or the soft shadow's estimate (shadow.glsl), traced
// by the multilevel method whichever exact method traced the picture. A shadow ray that
// runs out of its budget marks the hit exhausted, as a primary ray would.
float lightVisibility(mr_Relief relief, inout mr_ReliefHit hit, vec3 toLight, bool pointLight) {
#if MICRORELIEF_SHADOWS != MR_SHADOWS_OFF && (MICRORELIEF_METHOD_TRAITS & MR_TRAIT_SOLID) != 0
    // The shadow ray in the frame: to a point light's frame position (t = 1 there), or
    // along a direction for ever.
    vec3 frameToLight = pointLight ? mr_baseFramePoint(relief, lightPosition.xyz) - hit.position
                                   : mr_baseFrameVector(relief, toLight);
    float tMaxLight = pointLight ? 1.0 : MR_T_INFINITY;
#if MICRORELIEF_SHADOWS == MR_SHADOWS_SOFT
    // Object-space angles: heights of the frame in object units, the ray's object length.
    float heightToObject = heightScale;
    // A curved base: heights are fractions of the frame's unit.
#if !MICRORELIEF_BASE_STRAIGHT_PATH
    heightToObject *= (frameScale.x + frameScale.y + frameScale.z) / 3.0;
#endif
    return mr_softShadow(relief, windowPyramid, heightSamples, hit, frameToLight, tMaxLight, lightTanRadius,
                         heightToObject, length(mat3(worldToObject) * toLight), hit.exhausted);
#else
    return mr_hardShadow(relief, windowPyramid, heightSamples, hit, frameToLight, tMaxLight, hit.exhausted);
#endif
#else
    return 1.0;
#endif
}

layout(location = 0) out vec4 outColor;
layout(location = 1) out vec4 outPosition;  // hit position in the shader's world (eye-relative), 1
layout(location = 2) out vec4 outStats;     // iterations, fetches, stop level (bound fetches when counting), exhausted
layout(location = 3) out vec4 outShadow;    // how much of the light reaches the hit (1 lit)

void main() {
    // Integer + 0.5 plus an integer: exact, so a tile's pixel casts the whole picture's ray.
    vec2 ndc = (gl_FragCoord.xy + tileOrigin) / viewportSize * 2.0 - 1.0;
    vec3 dir = cameraForward + ndc.x * cameraRight + ndc.y * cameraUp;
    mr_Relief relief = mr_Relief(mr_ReliefMap(reliefSize, pyramidSize, pyramidLevels, reliefMaxHeight, reliefTiles),
                                 mr_ReliefPlacement(objectToWorld, worldToObject, heightScale, frameScale));
    // Level-of-detail cone: a span of w finest texels (a pyramid window) projects to less
    // than pixelErrorTolerance pixels once w <= lodCone * t (t along this unnormalised ray;
    // the pixel's width in object units, where the map's texels are counted, follows the
    // ray's direction there).
    float pixelAngle = 2.0 * length(cameraUp) / viewportSize.y;
    float objectLength = length(mat3(worldToObject) * dir);
    float lodCone = pixelErrorTolerance * pixelAngle * objectLength * max(reliefSize.x, reliefSize.y);
    mr_RayQuery query = mr_RayQuery(tMin, tMax, false, maxIterations, lodCone);
#ifdef MICRORELIEF_COARSE_TILE
    // The coarse pass's start for this pixel's tile (coarse_start.glsl: never after any of
    // the tile's first hits; MR_COARSE_KEEP leaves the range as it is).
    MICRORELIEF_FETCHED(1);
    vec4 coarse = texelFetch(coarseStart, ivec2(gl_FragCoord.xy) / MICRORELIEF_COARSE_TILE, 0);
    query.tMin = max(query.tMin, coarse.x);
    mr_coarseFirstLength = coarse.z;  // the primary ray's walk only: shadow rays start at the root
#endif

    mr_ReliefHit hit = traceRay(relief, query, mr_baseFramePoint(relief, eye), mr_baseFrameVector(relief, dir));
#ifdef MICRORELIEF_COARSE_TILE
    mr_coarseFirstLength = 0.0;
#endif
#ifdef MICRORELIEF_COUNT_FETCHES
    // The instrumented variant: the bounds' share of the reads where the stop level was
    // (fetch_count.glsl).
    outStats = vec4(float(hit.iterations), float(mr_fetchCount), float(mr_boundFetchCount),
                    hit.exhausted ? 1.0 : 0.0);
#else
    outStats = vec4(float(hit.iterations), 0.0, float(hit.stopLevel), hit.exhausted ? 1.0 : 0.0);
#endif
    if (hit.exhausted) {
        // Never silent: a traversal cut short by the budget shows as magenta.
        outColor = vec4(1.0, 0.0, 1.0, 1.0);
        outPosition = vec4(0.0);
        outShadow = vec4(0.0);
        gl_FragDepth = gl_FragCoord.z;
        return;
    }
    if (hit.kind == MR_RELIEF_MISS) {
#ifdef MICRORELIEF_COUNT_FETCHES
        // Keep the statistics of missed rays; the picture of this variant is not used.
        outColor = vec4(0.0);
        outPosition = vec4(0.0);
        outShadow = vec4(0.0);
        gl_FragDepth = gl_FragCoord.z;
        return;
#else
        discard;
#endif
    }

#if (MICRORELIEF_METHOD_TRAITS & MR_TRAIT_OFF_RAY) != 0 || MICRORELIEF_TANGENT_PEER
    // Parallax offset's answer is not on the ray (it shifts the texture lookup instead),
    // nor is a tangent-frame peer's on a curved base.
    vec3 world = mr_baseWorldPoint(relief, hit.position);
#else
    vec3 world = eye + hit.t * dir;  // on the ray exactly, without a round trip through map space
#endif
    vec3 n = mr_reliefWorldNormal(relief, hit);
    // Towards the light: a direction, or a point light's position from the hit (then the
    // shadow ray ends at the light, t = 1).
    bool pointLight = lightPosition.w > 0.5;
    vec3 toLight = pointLight ? lightPosition.xyz - world : lightDirection;
    float visibility = lightVisibility(relief, hit, toLight, pointLight);
    outShadow = vec4(visibility, 0.0, 0.0, 1.0);
#ifdef MICRORELIEF_COUNT_FETCHES
    outStats.yz = vec2(float(mr_fetchCount), float(mr_boundFetchCount));  // the shadow ray's reads too
#endif
    if (hit.exhausted) {  // the shadow ray's budget ran out
        outStats.w = 1.0;
        outColor = vec4(1.0, 0.0, 1.0, 1.0);
        outPosition = vec4(0.0);
        gl_FragDepth = gl_FragCoord.z;
        return;
    }
    vec3 color;  // display RGB for the debug views
    if (debugView == MR_DEBUG_VIEW_ITERATIONS) {
        // Scaled to the cost of a few levels' worth of segments; saturates red beyond.
        color = mr_debugScalar(float(hit.iterations), 8.0 * float(pyramidLevels));
    } else if (debugView == MR_DEBUG_VIEW_LEVEL) {
        color = mr_debugScalar(float(hit.stopLevel), float(pyramidLevels - 1));
    } else if (debugView == MR_DEBUG_VIEW_NORMAL) {
        color = mr_debugNormal(n);
    } else if (debugView == MR_DEBUG_VIEW_DEPTH) {
        // Scaled to the eye's distance from the relief's origin (from the world's origin
        // when the model is the identity), plus the relief's size.
        float distance = length(world - eye), far = length(objectToWorld[3].xyz - eye) + 1.5;
        color = vec3(1.0 - clamp(distance / far, 0.0, 1.0));
    } else {
        color = mr_debugPosition(mr_baseObjectPoint(relief, world), reliefBoxMin, reliefBoxMax);
    }
    // The output is linear: a debug view's display colour is decoded, so that the sRGB
    // target gives it back.
    mr_ReliefMaterial material = mr_ReliefMaterial(surfaceAlbedo(relief, hit, dir, n), 0.25, 48.0);
    vec3 linear = debugView == MR_DEBUG_VIEW_SHADED
                      ? mr_shadeRelief(material, n, normalize(toLight), normalize(-dir), vec3(visibility))
                      : mr_decodeSrgb(color);
    outColor = vec4(linear, 1.0);
    outPosition = vec4(world, 1.0);
    gl_FragDepth = windowDepth(world);
}
