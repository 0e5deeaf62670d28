// relief.frag: one ray per pixel through the pixel centre, traced by the multilevel
// method (microrelief/multilevel_trace.glsl), shaded, with the world position of the
// hit and the traversal's statistics as extra outputs. Misses are discarded; hits
// write gl_FragDepth, so the relief depth-composites with other geometry.
#include "microrelief/map_space.glsl"
#include "microrelief/multilevel_trace.glsl"
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
    ReliefMaterial material = ReliefMaterial(albedo, 0.25, 48.0);
    vec3 color = shadeRelief(material, n, lightDirection, normalize(-dir), vec3(1.0));
    outColor = vec4(encodeSrgb(color), 1.0);
    outPosition = vec4(world, 1.0);
    vec4 clip = viewProjection * vec4(world, 1.0);
    gl_FragDepth = clamp(0.5 + 0.5 * clip.z / clip.w, 0.0, 1.0);
}
