// mesh_relief.frag: the relief on a triangle mesh (docs/bases.md, "The mesh"; issue 50), one
// fragment of a prism's hull (mesh_relief.vert) at a time: the ray from the eye through the
// fragment's point on the hull, traced in that one prism (microrelief/base_mesh.glsl, the
// GLSL of core/trace/MeshTracer); the hit's depth is written and the depth test keeps the
// least over prisms, which is the first hit on the union. A ray that misses the prism is
// discarded. The eye may be inside a hull (drawn without face culling, gl/MeshRelief.h): the
// trace starts at lambda = 0, the eye, wherever the fragment is.
//
// Outputs as relief.frag's (gl/OffscreenTarget.h): the colour, the hit's position less the
// eye (w = 1), the statistics (zero here) and the light's share (1: no shadows yet).
#define MICRORELIEF_PYRAMID_TEXEL_FETCH 1
#include "microrelief/base_mesh.glsl"

uniform sampler2D mr_meshTable;    // base_mesh.glsl's triangle table
uniform sampler2D mr_meshHeights;  // the map's samples, R32F, texel (i, j) the sample at X = i + 1/2
uniform sampler2D mr_meshWindows;  // the windows of the map's pyramid tiled 3 x 3 (R32F, bound / 2^S)
uniform mat4 mr_viewProjection;
uniform vec3 mr_eye;               // mesh units
uniform float mr_heightScale;      // s, mesh units per map unit
uniform float mr_top;              // H: the pyramid's top, map units
uniform vec2 mr_mapSize;           // W, H texels
uniform int mr_levelCount;         // the windows' levels
uniform int mr_budget;             // segments a piece may visit

in vec3 mr_proxyPoint;
flat in uint mr_meshTriangleIndex;

layout(location = 0) out vec4 outColor;
layout(location = 1) out vec4 outPosition;
layout(location = 2) out vec4 outStats;
layout(location = 3) out vec4 outShadow;

void main() {
    mr_Relief relief;
    relief.map = mr_ReliefMap(mr_mapSize, ivec2(mr_mapSize), mr_levelCount, mr_top, ivec2(1));
    relief.placement = mr_ReliefPlacement(mat4(1.0), mat4(1.0), mr_heightScale, vec3(1.0));
    mr_MeshTriangle tri = mr_meshTriangle(mr_meshTable, int(mr_meshTriangleIndex));
    // The ray through the fragment: its point on the hull lies on the pixel's ray (the
    // perspective-correct interpolation of the proxy's positions at the pixel's centre).
    vec3 dir = mr_proxyPoint - mr_eye;
    float hitT;
    vec2 hitUv;
    float lambda = mr_meshTraceTriangle(relief, mr_meshWindows, mr_meshHeights, tri, mr_eye, dir,
                                        mr_heightScale, mr_top, MR_NEVER, mr_budget, hitT, hitUv);
    if (lambda < 0.0) discard;
    vec3 offset = lambda * dir;
    vec4 clip = mr_viewProjection * vec4(mr_eye + offset, 1.0);
    gl_FragDepth = clamp(0.5 * (clip.z / clip.w) + 0.5, 0.0, 1.0);
    float shade = 0.25 + 0.75 * clamp(hitT / max(mr_top, 1e-30), 0.0, 1.0);
    outColor = vec4(vec3(shade), 1.0);
    outPosition = vec4(offset, 1.0);
    outStats = vec4(0.0);
    outShadow = vec4(1.0);
}
