// relief.frag: one ray per pixel through the pixel centre, traced by the multilevel
// method (microrelief/multilevel_trace.glsl), shaded, with the world position of the
// hit and the traversal's statistics as extra outputs. Misses are discarded; hits
// write gl_FragDepth, so the relief depth-composites with other geometry.
#include "microrelief/map_space.glsl"
#include "microrelief/multilevel_trace.glsl"
#include "microrelief/debug_views.glsl"
#include "microrelief/shading.glsl"

uniform sampler2D maxPyramid;  // the multilevel elevation map, nearest mipmaps
uniform sampler2D heightSamples;

uniform vec2 reliefSize;
uniform ivec2 pyramidSize;
uniform int pyramidLevels;
uniform float reliefMaxHeight;
uniform float heightScale;
uniform int maxIterations;

uniform vec3 eye;
uniform vec3 cameraRight;    // scaled by tan(fovx / 2)
uniform vec3 cameraUp;       // scaled by tan(fovy / 2)
uniform vec3 cameraForward;  // unit
uniform vec2 viewportSize;
uniform mat4 viewProjection;

uniform vec3 lightDirection;  // towards the light, unit
uniform vec3 albedo;
uniform int debugView;        // DEBUG_VIEW_*; 0 is the shaded picture

layout(location = 0) out vec4 outColor;
layout(location = 1) out vec4 outPosition;  // world hit position, 1
layout(location = 2) out vec4 outStats;     // iterations, fetches, stop level, exhausted

void main() {
    ReliefMap map = ReliefMap(reliefSize, pyramidSize, pyramidLevels, reliefMaxHeight, heightScale, maxIterations);

    vec2 ndc = gl_FragCoord.xy / viewportSize * 2.0 - 1.0;
    vec3 dir = cameraForward + ndc.x * cameraRight + ndc.y * cameraUp;
    ReliefHit hit = traceMultilevel(map, maxPyramid, heightSamples, worldToMapPoint(map, eye),
                                    worldToMapVector(map, dir));
    outStats = vec4(float(hit.iterations), float(hit.fetches), float(hit.stopLevel), hit.exhausted ? 1.0 : 0.0);
    if (hit.exhausted) {
        // Never silent: a traversal cut short by the budget shows as magenta.
        outColor = vec4(1.0, 0.0, 1.0, 1.0);
        outPosition = vec4(0.0);
        gl_FragDepth = gl_FragCoord.z;
        return;
    }
    if (hit.kind == RELIEF_MISS) discard;

    vec3 world = eye + hit.t * dir;
    vec3 n = reliefWorldNormal(map, hit);
    vec3 color;
    if (debugView == DEBUG_VIEW_ITERATIONS) {
        // Scaled to the cost of a few levels' worth of segments; saturates red beyond.
        color = debugScalar(float(hit.iterations), 8.0 * float(pyramidLevels));
    } else if (debugView == DEBUG_VIEW_LEVEL) {
        color = debugScalar(float(hit.stopLevel), float(pyramidLevels - 1));
    } else if (debugView == DEBUG_VIEW_NORMAL) {
        color = debugNormal(n);
    } else if (debugView == DEBUG_VIEW_DEPTH) {
        float distance = length(world - eye), far = length(eye) + 1.5;
        color = vec3(1.0 - clamp(distance / far, 0.0, 1.0));
    } else if (debugView == DEBUG_VIEW_POSITION) {
        vec3 top = mapToWorldPoint(map, vec3(map.size, map.maxHeight));
        color = debugPosition(world, -top * vec3(1.0, 0.0, 1.0), top);
    } else {
        ReliefMaterial material = ReliefMaterial(albedo, 0.25, 48.0);
        color = encodeSrgb(shadeRelief(material, n, lightDirection, normalize(-dir), vec3(1.0)));
    }
    outColor = vec4(color, 1.0);
    outPosition = vec4(world, 1.0);
    vec4 clip = viewProjection * vec4(world, 1.0);
    gl_FragDepth = clamp(0.5 + 0.5 * clip.z / clip.w, 0.0, 1.0);
}
