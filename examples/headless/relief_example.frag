// The example's own fragment shader: every pixel of a full-screen triangle casts its ray,
// the library traces it (mr_traceMultilevel) and the hit is shaded as microrelief-render
// shades it. The colour is linear; the sRGB target encodes it.
#include "microrelief/multilevel_trace.glsl"
#include "microrelief/shading.glsl"

uniform sampler2D windows;  // ReliefTextures::windowPyramid(), the multilevel method's
uniform sampler2D heights;  // ReliefTextures::samples()
uniform vec2 mapSize;       // ReliefTextures::shape(), as mr_ReliefMap takes it
uniform ivec2 pyramidSize;
uniform int levelCount;
uniform float maxHeight;
uniform float heightScale;  // world height of map value 1
uniform vec3 eye, right, up, forward;  // CameraFrame: ray = eye + t (forward + x right + y up)
uniform vec2 viewport;
uniform vec3 lightDirection;  // towards the light, unit
uniform vec3 albedo;

layout(location = 0) out vec4 color;

void main() {
    vec2 ndc = gl_FragCoord.xy / viewport * 2.0 - 1.0;
    vec3 dir = forward + ndc.x * right + ndc.y * up;
    // The map where the scene convention puts it: no model transform, the plane y = 0.
    mr_Relief relief = mr_Relief(mr_ReliefMap(mapSize, pyramidSize, levelCount, maxHeight, ivec2(1)),
                                 mr_ReliefPlacement(mat4(1.0), mat4(1.0), heightScale, vec3(1.0)));
    mr_ReliefHit hit = mr_traceMultilevel(relief, mr_closestHitQuery(relief.map), windows, heights,
                                          mr_baseFramePoint(relief, eye), mr_baseFrameVector(relief, dir));
    if (hit.kind == MR_RELIEF_MISS || hit.exhausted) discard;  // the cleared background shows
    vec3 n = mr_reliefWorldNormal(relief, hit);
    mr_ReliefMaterial material = mr_ReliefMaterial(albedo, 0.25, 48.0);
    color = vec4(mr_shadeRelief(material, n, lightDirection, normalize(-dir), vec3(1.0)), 1.0);
}
