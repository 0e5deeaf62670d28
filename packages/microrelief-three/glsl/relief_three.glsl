// relief_three.glsl: microrelief-three's glue between three.js and the library (the GLSL of
// shaders/microrelief/, spliced before this file by scripts/build.mjs). One ray per pixel
// through the pixel's own centre, traced by the multilevel method, for any three.js camera.
//
// use:   mrPixel p; if (mrFaceRejected() || !mrTracePixel(p)) discard;
//        gl_FragDepth = mrWindowDepth(p.world, clip);
// needs: the uniforms below (src/relief.js fills them, per relief and per draw).
//
// The camera's rays are affine in the pixel's NDC (x, y): origin o0 + x ox + y oy and
// direction d0 + x dx + y dy, in the world. A perspective camera has ox = oy = 0 and o0 its
// eye; an orthographic one (a directional light's shadow camera) has one direction and
// origins on its near plane. JavaScript computes the six vectors in double from the
// camera's projectionMatrixInverse and matrixWorld; with d0's component along the view
// axis 1, t is the view depth and [near, far] the t range three would keep (mrRange).
// The NDC is the pixel centre's, from gl_FragCoord and the viewport (mrViewport), never
// an interpolated box position: rounding the interpolation moves a ray off its pixel
// centre, and at silhouettes that flips whole pixels. Shadow passes, whose viewport three
// sets behind the renderer's back, take it from the interpolated clip position (mrClip):
// a shadow map samples far more coarsely than that rounding.
#ifndef MICRORELIEF_THREE_GLSL
#define MICRORELIEF_THREE_GLSL

// ---- The pixel in parameters only: the part both entries run. The WebGL entry calls it
// through the uniforms below (mrTracePixel); the WebGPU entry's glsl/webgpu_shading.glsl calls
// it too, translated with the library by naga (scripts/wgsl.mjs, generated/wgsl.js), where
// MICRORELIEF_THREE_PARAMETERS_ONLY leaves out the uniforms (WGSL has none of GLSL's). ----

struct mrPixel {
    vec3 origin;       // world (about mrWorldOrigin)
    vec3 dir;          // world, not unit
    mr_ReliefHit hit;  // the library's answer, in the base's frame
    bool exhausted;    // the traversal ran out of its budget (never silent: shown magenta)
    vec3 world;        // the hit, world (about mrWorldOrigin): origin + t dir
    vec3 normal;       // world, unit
    vec2 uv;           // three's convention: (u, 1 - v), the image's row 0 at uv.y = 1
};

// A draw's camera rays (the uniforms mrRayOrigin ... mrRange below say what each is).
struct mrCameraRays {
    vec3 origin, originDx, originDy;
    vec3 dir, dirDx, dirDy;
    vec2 range;
};

// The centre of the pixel at `fragCoord` in NDC: (fragCoord - viewport.xy) / viewport.zw
// * 2 - 1, with viewport (x, y, width, height) in the target's pixels. `yDown`: the window's
// y runs down from the top (WebGPU's fragment position and viewport), NDC's y still up.
vec2 mrNdcOf(vec2 fragCoord, vec4 viewport, bool yDown) {
    vec2 ndc = (fragCoord - viewport.xy) / viewport.zw * 2.0 - 1.0;
    if (yDown) ndc.y = -ndc.y;
    return ndc;
}

// The ray at `ndc` traced in `relief`; false where it misses. `viewport` gives the pixel's
// size for the level of detail (width 0: none, a shadow pass); `worldToObject` and `mapSize`
// are the relief's (relief.map's).
bool mrTraceRay(mr_Relief relief, MICRORELIEF_SAMPLER windows, MICRORELIEF_SAMPLER heights, mrCameraRays rays,
                vec2 ndc, vec4 viewport, float pixelError, mat4 worldToObject, vec2 mapSize, out mrPixel p) {
    p.origin = rays.origin + ndc.x * rays.originDx + ndc.y * rays.originDy;
    p.dir = rays.dir + ndc.x * rays.dirDx + ndc.y * rays.dirDy;
    // The level-of-detail cone of relief.frag: a window may stand for the surface once it
    // projects to less than pixelError pixels (the view's camera only).
    float lodCone = 0.0;
    if (pixelError > 0.0 && viewport.z > 0.0) {
        float pixelAngle = 2.0 * length(rays.dirDy) / viewport.w;
        float objectLength = length(mat3(worldToObject) * p.dir);
        lodCone = pixelError * pixelAngle * objectLength * max(mapSize.x, mapSize.y);
    }
    mr_RayQuery query = mr_RayQuery(rays.range.x, rays.range.y, false, mr_traversalBudget(relief.map), lodCone);
    p.hit = mr_traceMultilevel(relief, query, windows, heights, mr_baseFramePoint(relief, p.origin),
                               mr_baseFrameVector(relief, p.dir));
    p.exhausted = p.hit.exhausted;
    p.world = p.origin + max(p.hit.t, rays.range.x) * p.dir;
    p.normal = vec3(0.0, 1.0, 0.0);
    p.uv = vec2(0.0);
    if (p.exhausted) return true;
    if (p.hit.kind == MR_RELIEF_MISS) return false;
    p.world = p.origin + p.hit.t * p.dir;  // on the ray exactly, as relief.frag has it
    p.normal = mr_reliefWorldNormal(relief, p.hit);
    vec3 m = mr_baseMapPoint(relief, p.hit.position);
    p.uv = vec2(m.x / mapSize.x, 1.0 - m.y / mapSize.y);
    return true;
}

// The library's shading of hit `p` (relief.frag's shaded view): one directional light
// (`lightDirection`, world, towards the light), `albedo` (linear), the hard self-shadow where
// `hardShadow`; `exhausted` where that shadow's traversal ran out of its budget.
vec3 mrShadeHit(mr_Relief relief, MICRORELIEF_SAMPLER windows, MICRORELIEF_SAMPLER heights, mrPixel p,
                vec3 lightDirection, vec3 albedo, bool hardShadow, out bool exhausted) {
    exhausted = false;
    float visibility = 1.0;
    if (hardShadow)
        visibility = mr_hardShadow(relief, windows, heights, p.hit, mr_baseFrameVector(relief, lightDirection),
                                   MR_T_INFINITY, exhausted);
    mr_ReliefMaterial material = mr_ReliefMaterial(albedo, 0.25, 48.0);
    return mr_shadeRelief(material, p.normal, normalize(lightDirection), normalize(-p.dir), vec3(visibility));
}

// The world size of a shadow-map texel at `p` for a light whose matrix `m` takes the world to
// the map's [0, 1] (projective for a spot light): 1 over the steepest rate of its
// coordinates (three_material.glsl's and webgpu_shading.glsl's shadow lookups move the hit
// off the surface by a reach of these: docs/three.md, "Shadow acne").
float mrShadowTexel(mat4 m, vec3 p, vec2 mapSize) {
    vec4 c = m * vec4(p, 1.0);
    vec3 x = vec3(m[0][0], m[1][0], m[2][0]), y = vec3(m[0][1], m[1][1], m[2][1]), w = vec3(m[0][3], m[1][3], m[2][3]);
    vec2 perUnit = vec2(length(x - (c.x / c.w) * w), length(y - (c.y / c.w) * w)) * mapSize / abs(c.w);
    return 1.0 / min(perUnit.x, perUnit.y);
}

// The same on a point light's cube (`m` its shadow matrix, the light at the origin it takes
// p to): a face's texel at the depth of p's largest coordinate about the light.
float mrPointShadowTexel(mat4 m, vec3 p, vec2 mapSize) {
    vec3 a = abs((m * vec4(p, 1.0)).xyz);
    return 2.0 * max(a.x, max(a.y, a.z)) / mapSize.x;
}

#ifndef MICRORELIEF_THREE_PARAMETERS_ONLY

uniform sampler2D mrHeights;   // the samples, R32F, W x H (nearest; u repeats on a curved base)
uniform sampler2D mrWindows;   // the windows pyramid, R16F, GL's mip sizes of W x H
uniform vec2 mrMapSize;        // W, H
uniform ivec2 mrPyramidSize;   // W, H
uniform int mrLevelCount;      // floor(log2 max(W, H)) + 1
uniform float mrMaxHeight;     // the pyramid's top texel, map units
uniform mat4 mrObjectToWorld;  // the relief's matrixWorld
uniform mat4 mrWorldToObject;  // its inverse (in double, then float)
uniform float mrHeightScale;   // s
uniform vec3 mrFrameScale;     // curved bases: (R, L / 2, R) or the ellipsoid's radii
uniform float mrPixelError;    // level of detail in pixels (0: exact)

// This draw's camera (the view's or a light's shadow camera). "World" below is three's world
// moved by minus mrWorldOrigin, the camera's position (src/relief.js composes the matrices
// in double), so that a relief far from three's origin is traced as exactly as one at it.
uniform vec3 mrWorldOrigin;     // three's world position of this shader's world origin
uniform vec3 mrRayOrigin, mrRayOriginDx, mrRayOriginDy;
uniform vec3 mrRayDir, mrRayDirDx, mrRayDirDy;
uniform vec4 mrViewport;        // x, y, width, height in window pixels; width 0: NDC from mrClip
uniform vec2 mrRange;           // the t range: the camera's near and far
uniform int mrFaces;            // which faces of the box run: 1 front, 2 back, 3 both
uniform mat4 mrViewProjection;  // world to this camera's clip space
uniform mat4 mrCameraToWorld;   // the camera's matrixWorld
uniform mat4 mrWorldToCamera;   // its inverse: the view matrix of this draw
uniform int mrPerspective;      // 1: a perspective projection (logarithmic depth applies)

varying vec4 mrClip;  // the box's clip position, interpolated

mr_Relief mrRelief() {
    return mr_Relief(mr_ReliefMap(mrMapSize, mrPyramidSize, mrLevelCount, mrMaxHeight, ivec2(1)),
                     mr_ReliefPlacement(mrObjectToWorld, mrWorldToObject, mrHeightScale, mrFrameScale));
}

// The box runs its front faces from outside, its back faces when the camera is inside or
// the near plane cuts it, both where near and far both cut it (src/relief.js decides).
bool mrFaceRejected() {
    return mrFaces == 1 ? !gl_FrontFacing : (mrFaces == 2 ? gl_FrontFacing : false);
}

// The pixel centre in NDC, as relief.frag computes it: (gl_FragCoord + 0) / size * 2 - 1.
vec2 mrPixelNdc() {
    if (mrViewport.z > 0.0) return mrNdcOf(gl_FragCoord.xy, mrViewport, false);
    return mrClip.xy / mrClip.w;
}

// The pixel's ray traced; false where it misses the relief.
bool mrTracePixel(out mrPixel p) {
    return mrTraceRay(mrRelief(), mrWindows, mrHeights,
                      mrCameraRays(mrRayOrigin, mrRayOriginDx, mrRayOriginDy, mrRayDir, mrRayDirDx, mrRayDirDy, mrRange),
                      mrPixelNdc(), mrViewport, mrPixelError, mrWorldToObject, mrMapSize, p);
}

// The window depth of world point `world` for this draw's camera, as the fixed function
// makes it from a vertex there: clip z / w to [0, 1] (three's reversed depth buffer sets
// the clip control to [0, 1] already), then the depth range. `clip` is the clip position.
float mrWindowDepth(vec3 world, out vec4 clip) {
    clip = mrViewProjection * vec4(world, 1.0);
    float ndc = clip.z / clip.w;
#ifdef USE_REVERSED_DEPTH_BUFFER
    float unit = ndc;
#else
    float unit = 0.5 + 0.5 * ndc;
#endif
    return clamp(gl_DepthRange.near + gl_DepthRange.diff * unit, 0.0, 1.0);
}

// The depth three's logarithmic depth buffer writes for clip position `clip`
// (logdepthbuf_fragment: log2(1 + w) * logDepthBufFC / 2 for a perspective camera).
#ifdef USE_LOGARITHMIC_DEPTH_BUFFER
float mrLogarithmicDepth(vec4 clip, float depth) {
    return mrPerspective != 0 ? log2(1.0 + clip.w) * logDepthBufFC * 0.5 : depth;
}
#endif

#endif  // MICRORELIEF_THREE_PARAMETERS_ONLY

#endif
