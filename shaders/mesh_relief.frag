// mesh_relief.frag: the relief on a triangle mesh (docs/bases.md, "The mesh"; issue 50), one
// fragment of a prism's hull (mesh_relief.vert) at a time: the ray from the eye through the
// fragment's point on the hull, traced in that one prism (microrelief/base_mesh.glsl, the
// GLSL of core/trace/MeshTracer); the hit's depth is written and the depth test keeps the
// least over prisms, which is the first hit on the union. A ray that misses the prism is
// discarded. The eye may be inside a hull (the hulls that may hold it are drawn without face
// culling, the others with back faces culled: gl/MeshRelief.h): the trace starts at
// lambda = 0, the eye, wherever the fragment is.
//
// Host defines: MICRORELIEF_INTERPOLATION (relief_map.glsl: the last level, bilinear or
// biquadratic).
//
// Outputs as relief.frag's (gl/OffscreenTarget.h): the colour (linear: an sRGB target with
// sRGB writes on encodes it), the hit's position less the eye (w = 1), the statistics (zero
// here) and the light's share (1: no shadows yet); and at location 4 the normal AOV, the
// hit's outward unit surface normal (base_mesh.glsl's mr_meshNormal; zero where the eye is
// inside the solid) and w = 1, which a target with a fifth draw buffer receives (the GL drops
// it where there is none, as OffscreenTarget has). The colour is relief.frag's: the
// library's shading (microrelief/shading.glsl) of the albedo under one directional light, or
// the normal debug view (debug_views.glsl) where mr_debugView asks for it.
#define MICRORELIEF_PYRAMID_TEXEL_FETCH 1
#include "microrelief/variants.glsl"
#include "microrelief/base_mesh.glsl"
#include "microrelief/debug_views.glsl"
#include "microrelief/shading.glsl"

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
uniform vec3 mr_lightDirection;    // towards the directional light, unit
uniform vec3 mr_albedo;            // the surface's diffuse colour, linear
uniform int mr_debugView;          // MR_DEBUG_VIEW_SHADED or MR_DEBUG_VIEW_NORMAL

in vec3 mr_proxyPoint;
flat in uint mr_meshTriangleIndex;

layout(location = 0) out vec4 outColor;
layout(location = 1) out vec4 outPosition;
layout(location = 2) out vec4 outStats;
layout(location = 3) out vec4 outShadow;
layout(location = 4) out vec4 outNormal;

void main() {
    mr_Relief relief;
    relief.map = mr_ReliefMap(mr_mapSize, ivec2(mr_mapSize), mr_levelCount, mr_top, ivec2(1));
    relief.placement = mr_ReliefPlacement(mat4(1.0), mat4(1.0), mr_heightScale, vec3(1.0));
    mr_MeshTriangle tri = mr_meshTriangle(mr_meshTable, int(mr_meshTriangleIndex));
    // The ray through the fragment: its point on the hull lies on the pixel's ray (the
    // perspective-correct interpolation of the proxy's positions at the pixel's centre).
    vec3 dir = mr_proxyPoint - mr_eye;
    mr_MeshHit hit;
    float lambda = mr_meshTraceTriangle(relief, mr_meshWindows, mr_meshHeights, tri, mr_eye, dir,
                                        mr_heightScale, mr_top, MR_NEVER, mr_budget, hit);
    if (lambda < 0.0) discard;
    vec3 offset = lambda * dir;
    vec4 clip = mr_viewProjection * vec4(mr_eye + offset, 1.0);
    gl_FragDepth = clamp(0.5 * (clip.z / clip.w) + 0.5, 0.0, 1.0);
    vec3 n = mr_meshNormal(relief, mr_meshHeights, tri, mr_heightScale, hit, dir);
    // Shaded as relief.frag shades the analytic bases; at the eye inside the solid (no
    // surface there) as a surface facing it.
    vec3 view = normalize(-dir);
    vec3 shadingNormal = hit.surface == MR_MESH_INSIDE ? view : n;
    mr_ReliefMaterial material = mr_ReliefMaterial(mr_albedo, 0.25, 48.0);
    vec3 linear = mr_debugView == MR_DEBUG_VIEW_NORMAL
                      ? mr_decodeSrgb(mr_debugNormal(n))
                      : mr_shadeRelief(material, shadingNormal, mr_lightDirection, view, vec3(1.0));
    outColor = vec4(linear, 1.0);
    outPosition = vec4(offset, 1.0);
    outStats = vec4(0.0);
    outShadow = vec4(1.0);
    outNormal = vec4(n, 1.0);
}
