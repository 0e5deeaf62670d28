// relief.frag: one ray per pixel through the pixel centre, traced by the multilevel
// method (microrelief/multilevel_trace.glsl) or, for comparison, one of its peers,
// shaded, with the world position of the hit and the traversal's statistics as extra
// outputs. Misses are discarded; hits write gl_FragDepth, so the relief
// depth-composites with other geometry.
//
// Host defines: MICRORELIEF_METHOD (0 multilevel, 1 normal, 2 offset, 3 steep, 4 pom,
// 5 relief, 6 maxmip); MICRORELIEF_BASE (0 plane, 1 cylinder, 2 ellipsoid:
// base_surface.glsl); MICRORELIEF_COUNT_FETCHES for the instrumented variant, which
// writes texel reads to the statistics and keeps misses (so they are counted too).
#include "microrelief/map_space.glsl"
#include "microrelief/multilevel_trace.glsl"

#include "microrelief/maxmip_trace.glsl"
#include "microrelief/normal_mapping.glsl"
#include "microrelief/parallax_occlusion.glsl"
#include "microrelief/parallax_offset.glsl"
#include "microrelief/relief_mapping.glsl"
#include "microrelief/steep_parallax.glsl"
// Every method is included (the host splices includes before the preprocessor runs);
// MICRORELIEF_METHOD picks the one that is called, and the compiler drops the rest.
#ifndef MICRORELIEF_METHOD
#define MICRORELIEF_METHOD 0
#endif
#include "microrelief/debug_views.glsl"
#include "microrelief/shading.glsl"

// The multilevel elevation map (max_pyramid.glsl), nearest mipmaps: the aligned levels
// (maxmip's quadtree) and the overlapping ones (the multilevel method's windows).
uniform sampler2D maxPyramid;
uniform sampler2D windowPyramid;
uniform sampler2D heightSamples;

uniform vec2 reliefSize;
uniform ivec2 pyramidSize;
uniform int pyramidLevels;
uniform float reliefMaxHeight;
uniform float heightScale;
uniform int maxIterations;
uniform vec3 frameScale;     // curved bases: world size of the canonical frame's unit
uniform vec3 reliefBoxMin;   // the proxy box, world space (the position debug view)
uniform vec3 reliefBoxMax;

uniform vec3 eye;
uniform vec3 cameraRight;    // scaled by tan(fovx / 2)
uniform vec3 cameraUp;       // scaled by tan(fovy / 2)
uniform vec3 cameraForward;  // unit
uniform vec2 viewportSize;   // the whole picture's, in pixels
uniform vec2 tileOrigin;     // where the drawn tile sits in it (0, 0: the whole picture)
uniform mat4 viewProjection;

uniform vec3 lightDirection;  // towards the light, unit
uniform vec3 albedo;
uniform int debugView;        // DEBUG_VIEW_*; 0 is the shaded picture

uniform int methodSteps;         // peers' quality knob: layers, samples or linear steps
uniform int methodMinSteps;      // pom: samples when looking straight down
uniform int methodRefineSteps;   // relief: binary search steps
uniform float pixelErrorTolerance;  // multilevel: stop at windows narrower than this many pixels

mr_ReliefHit traceInFrame(mr_ReliefMap map, vec3 origin, vec3 dir) {
#if MICRORELIEF_METHOD == 1
    return mr_traceNormalMapping(map, heightSamples, origin, dir);
#elif MICRORELIEF_METHOD == 2
    return mr_traceParallaxOffset(map, heightSamples, origin, dir);
#elif MICRORELIEF_METHOD == 3
    return mr_traceSteepParallax(map, heightSamples, origin, dir, methodSteps);
#elif MICRORELIEF_METHOD == 4
    return mr_traceParallaxOcclusion(map, heightSamples, origin, dir, methodMinSteps, methodSteps);
#elif MICRORELIEF_METHOD == 5
    return mr_traceReliefMapping(map, heightSamples, origin, dir, methodSteps, methodRefineSteps);
#elif MICRORELIEF_METHOD == 6
    return mr_traceMaxMip(map, maxPyramid, heightSamples, origin, dir);
#else
    return mr_traceMultilevel(map, windowPyramid, heightSamples, origin, dir);
#endif
}

// The step-based peers on a curved base, as engines run them there (pom, relief): in the
// base's tangent frame where the ray enters the shell, map space taken as flat from there
// on; their answer, a map point, is then placed on the base (off the ray, like offset's).
#define MICRORELIEF_TANGENT_PEER (MICRORELIEF_BASE != 0 && (MICRORELIEF_METHOD == 4 || MICRORELIEF_METHOD == 5))

mr_ReliefHit traceRay(mr_ReliefMap map, vec3 origin, vec3 dir) {
#if MICRORELIEF_TANGENT_PEER
    vec3 localOrigin, localDir;
    float tEntry;
    if (!mr_baseTangentRay(map, origin, dir, localOrigin, localDir, tEntry)) return mr_reliefMissHit();
    mr_ReliefHit hit = traceInFrame(map, localOrigin, localDir);
    if (hit.kind == MR_RELIEF_TOP) {
        vec3 q = mr_baseSurfacePoint(map, hit.position);
        hit.normal = mr_baseTopNormal(map, q, -hit.normal.xy);
        hit.position = q;
        hit.t += tEntry;
    }
    return hit;
#else
    return traceInFrame(map, origin, dir);
#endif
}

layout(location = 0) out vec4 outColor;
layout(location = 1) out vec4 outPosition;  // world hit position, 1
layout(location = 2) out vec4 outStats;     // iterations, fetches, stop level, exhausted

void main() {
    // Integer + 0.5 plus an integer: exact, so a tile's pixel casts the whole picture's ray.
    vec2 ndc = (gl_FragCoord.xy + tileOrigin) / viewportSize * 2.0 - 1.0;
    vec3 dir = cameraForward + ndc.x * cameraRight + ndc.y * cameraUp;
    // Level-of-detail cone: a span of w finest texels (a pyramid window) projects to less
    // than pixelErrorTolerance pixels once w <= lodCone * t (t along this unnormalised ray).
    float pixelAngle = 2.0 * length(cameraUp) / viewportSize.y;
    float lodCone = pixelErrorTolerance * pixelAngle * length(dir) * max(reliefSize.x, reliefSize.y);
    mr_ReliefMap map = mr_ReliefMap(reliefSize, pyramidSize, pyramidLevels, reliefMaxHeight, heightScale, maxIterations,
                              lodCone, frameScale);

    mr_ReliefHit hit = traceRay(map, mr_baseFramePoint(map, eye), mr_baseFrameVector(map, dir));
#ifdef MICRORELIEF_COUNT_FETCHES
    float fetches = float(hit.fetches);
#else
    float fetches = 0.0;  // the counting is dead code without the instrumented variant
#endif
    outStats = vec4(float(hit.iterations), fetches, float(hit.stopLevel), hit.exhausted ? 1.0 : 0.0);
    if (hit.exhausted) {
        // Never silent: a traversal cut short by the budget shows as magenta.
        outColor = vec4(1.0, 0.0, 1.0, 1.0);
        outPosition = vec4(0.0);
        gl_FragDepth = gl_FragCoord.z;
        return;
    }
    if (hit.kind == MR_RELIEF_MISS) {
#ifdef MICRORELIEF_COUNT_FETCHES
        // Keep the statistics of missed rays; the picture of this variant is not used.
        outColor = vec4(0.0);
        outPosition = vec4(0.0);
        gl_FragDepth = 1.0;
        return;
#else
        discard;
#endif
    }

#if MICRORELIEF_METHOD == 2 || MICRORELIEF_TANGENT_PEER
    // Parallax offset's answer is not on the ray (it shifts the texture lookup instead),
    // nor is a tangent-frame peer's on a curved base.
    vec3 world = mr_baseWorldPoint(map, hit.position);
#else
    vec3 world = eye + hit.t * dir;  // on the ray exactly, without a round trip through map space
#endif
    vec3 n = mr_reliefWorldNormal(map, hit);
    vec3 color;
    if (debugView == MR_DEBUG_VIEW_ITERATIONS) {
        // Scaled to the cost of a few levels' worth of segments; saturates red beyond.
        color = mr_debugScalar(float(hit.iterations), 8.0 * float(pyramidLevels));
    } else if (debugView == MR_DEBUG_VIEW_LEVEL) {
        color = mr_debugScalar(float(hit.stopLevel), float(pyramidLevels - 1));
    } else if (debugView == MR_DEBUG_VIEW_NORMAL) {
        color = mr_debugNormal(n);
    } else if (debugView == MR_DEBUG_VIEW_DEPTH) {
        float distance = length(world - eye), far = length(eye) + 1.5;
        color = vec3(1.0 - clamp(distance / far, 0.0, 1.0));
    } else if (debugView == MR_DEBUG_VIEW_POSITION) {
        color = mr_debugPosition(world, reliefBoxMin, reliefBoxMax);
    } else {
        mr_ReliefMaterial material = mr_ReliefMaterial(albedo, 0.25, 48.0);
        color = mr_encodeSrgb(mr_shadeRelief(material, n, lightDirection, normalize(-dir), vec3(1.0)));
    }
    outColor = vec4(color, 1.0);
    outPosition = vec4(world, 1.0);
    vec4 clip = viewProjection * vec4(world, 1.0);
    gl_FragDepth = clamp(0.5 + 0.5 * clip.z / clip.w, 0.0, 1.0);
}
