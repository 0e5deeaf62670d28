// webgpu_shading.glsl: the WebGPU entry's pixels (microrelief-three/webgpu): mrShadePixel,
// ReliefShadingNodeMaterial's, the counterpart of microrelief_shading.frag's main (one pixel's
// ray traced, shaded and its depth), and mrTraceHit, ReliefStandardNodeMaterial's, the
// counterpart of three_material.glsl's mrBeginPixel (the hit for three's lighting), both by
// relief_three.glsl's shared functions (mrNdcOf, mrTraceRay, mrShadeHit), and mrSelfShadow,
// the counterpart of three_material.glsl's mrSelfShadowDirection and mrSelfShadowPoint
// (selfShadow: the hard shadow from mrTraceHit's hit towards one of three's lights). Not for
// WebGL: scripts/wgsl.mjs translates it with the library and relief_three.glsl (uniforms left
// out) into each variant of generated/wgsl.js, and src/webgpu.js calls the WGSL mrShadePixel
// from its node materials by wgslFn, each parameter one of three's nodes (the textures, the
// fragment's position, the viewport, the face, the relief's uniforms).
//
// mrShadePixel returns (colour, depth); depth -1 where the pixel shows nothing (a miss, or a face that
// does not run: faces 1 front, 2 back, 3 both). fragCoord and viewport (x, y, width, height in
// the target's pixels) run down from the top, as WebGPU's and three's WebGPU viewport's do.
// Depth: WebGPU's clip z / w is already in [0, 1] (three's WebGPU projection, reversed or not),
// the depth buffer's value for the viewport's default depth range [0, 1]. shadows: 1 the hard
// self-shadow, 0 none. The other parameters are relief_three.glsl's uniforms of their names.
#ifndef MICRORELIEF_WEBGPU_SHADING_GLSL
#define MICRORELIEF_WEBGPU_SHADING_GLSL

// The pixel at `fragCoord` traced: false where it shows nothing (a face that does not run,
// or a miss); `relief` and `p` as relief_three.glsl's mrTraceRay gives them. Both pixels below.
bool mrTraceFragment(MICRORELIEF_SAMPLER heights, MICRORELIEF_SAMPLER windows, vec2 fragCoord, vec4 viewport,
                     bool front, float faces, vec2 mapSize, vec2 pyramidSize, float levelCount, float maxHeight,
                     mat4 objectToWorld, mat4 worldToObject, float heightScale, vec3 frameScale,
                     float pixelError, vec3 rayOrigin, vec3 rayOriginDx, vec3 rayOriginDy,
                     vec3 rayDir, vec3 rayDirDx, vec3 rayDirDy, vec2 range, out mr_Relief relief, out mrPixel p) {
    relief = mr_Relief(mr_ReliefMap(mapSize, ivec2(pyramidSize), int(levelCount), maxHeight, ivec2(1)),
                       mr_ReliefPlacement(objectToWorld, worldToObject, heightScale, frameScale));
    bool runs = faces == 1.0 ? front : (faces == 2.0 ? !front : true);
    if (!runs) return false;
    mrCameraRays rays = mrCameraRays(rayOrigin, rayOriginDx, rayOriginDy, rayDir, rayDirDx, rayDirDy, range);
    return mrTraceRay(relief, windows, heights, rays, mrNdcOf(fragCoord, viewport, true), viewport, pixelError,
                      worldToObject, mapSize, p);
}

// The map's colours at hit `p` where `useAlbedoMap` is 1 (mr_surfaceAlbedo: filtered over the
// pixel's footprint, as relief.frag and the WebGL entry's materials draw them; the footprint's
// ray steps per pixel are the camera's per NDC unit times 2 / the viewport's size), else
// `albedo`. The WGSL takes the albedo's sampler as its first parameter (scripts/wgsl.mjs's
// samplerAsParameter).
vec3 mrPixelAlbedo(MICRORELIEF_ALBEDO_TEXTURE albedoMap, float useAlbedoMap, vec3 albedo, mr_Relief relief, mrPixel p,
                   vec4 viewport, vec3 rayDirDx, vec3 rayDirDy) {
    if (useAlbedoMap != 1.0) return albedo;
    vec2 pixel = 2.0 / viewport.zw;
    return mr_surfaceAlbedo(albedoMap, relief, p.hit, p.dir, p.normal, rayDirDx * pixel.x, rayDirDy * pixel.y, false);
}

// The depth of world point `world` (about the camera, as relief_three.glsl's) for WebGPU's
// depth buffer: clip z / w of `viewProjection`, in [0, 1].
float mrFragmentDepth(mat4 viewProjection, vec3 world) {
    vec4 clip = viewProjection * vec4(world, 1.0);
    return clamp(clip.z / clip.w, 0.0, 1.0);
}

vec4 mrShadePixel(MICRORELIEF_SAMPLER heights, MICRORELIEF_SAMPLER windows, vec2 fragCoord, vec4 viewport,
                  bool front, float faces, vec2 mapSize, vec2 pyramidSize, float levelCount, float maxHeight,
                  mat4 objectToWorld, mat4 worldToObject, float heightScale, vec3 frameScale,
                  float pixelError, vec3 rayOrigin, vec3 rayOriginDx, vec3 rayOriginDy,
                  vec3 rayDir, vec3 rayDirDx, vec3 rayDirDy, vec2 range,
                  mat4 viewProjection, vec3 lightDirection, vec3 albedo, float shadows,
                  MICRORELIEF_ALBEDO_TEXTURE albedoMap, float useAlbedoMap) {
    mr_Relief relief;
    mrPixel p;
    if (!mrTraceFragment(heights, windows, fragCoord, viewport, front, faces, mapSize, pyramidSize, levelCount, maxHeight,
                         objectToWorld, worldToObject, heightScale, frameScale, pixelError, rayOrigin, rayOriginDx,
                         rayOriginDy, rayDir, rayDirDx, rayDirDy, range, relief, p))
        return vec4(0.0, 0.0, 0.0, -1.0);
    vec3 colour = vec3(1.0, 0.0, 1.0);  // never silent: an exhausted traversal shows magenta
    if (!p.exhausted) {
        bool shadowExhausted = false;
        colour = mrShadeHit(relief, windows, heights, p, lightDirection,
                            mrPixelAlbedo(albedoMap, useAlbedoMap, albedo, relief, p, viewport, rayDirDx, rayDirDy),
                            shadows == 1.0, shadowExhausted);
        if (shadowExhausted) colour = vec3(1.0, 0.0, 1.0);
    }
    return vec4(colour, mrFragmentDepth(viewProjection, p.world));
}

// The pixel mrTraceHit traced last in this invocation, and its relief: what mrSelfShadow
// shoots its shadow rays from (private to the fragment, as three_material.glsl's mrHitPixel
// is in WebGL: naga writes them as `var<private>`).
mr_Relief mrTracedRelief;
mrPixel mrTracedPixel;

// ReliefStandardNodeMaterial's pixel: the traced hit as three's lighting takes it, as
// three_material.glsl's mrBeginPixel gives it to three's WebGL shaders (the hit in the view
// space of `worldToCamera`, the view of this draw; the normal through its rotation). Returns
// the columns (the hit in view space, its depth: -1 where the pixel shows nothing), (the unit
// normal in view space, 1 where the traversal was exhausted, else 0), (the map's colours at
// the hit where useAlbedoMap is 1, else white: three's diffuse colour is multiplied by them,
// as three_material.glsl's MR_ALBEDO_MAP does), and zeros.
mat4 mrTraceHit(MICRORELIEF_SAMPLER heights, MICRORELIEF_SAMPLER windows, vec2 fragCoord, vec4 viewport,
                bool front, float faces, vec2 mapSize, vec2 pyramidSize, float levelCount, float maxHeight,
                mat4 objectToWorld, mat4 worldToObject, float heightScale, vec3 frameScale,
                float pixelError, vec3 rayOrigin, vec3 rayOriginDx, vec3 rayOriginDy,
                vec3 rayDir, vec3 rayDirDx, vec3 rayDirDy, vec2 range,
                mat4 viewProjection, mat4 worldToCamera, MICRORELIEF_ALBEDO_TEXTURE albedoMap, float useAlbedoMap) {
    mr_Relief relief;
    mrPixel p;
    if (!mrTraceFragment(heights, windows, fragCoord, viewport, front, faces, mapSize, pyramidSize, levelCount, maxHeight,
                         objectToWorld, worldToObject, heightScale, frameScale, pixelError, rayOrigin, rayOriginDx,
                         rayOriginDy, rayDir, rayDirDx, rayDirDy, range, relief, p))
        return mat4(vec4(0.0, 0.0, 0.0, -1.0), vec4(0.0), vec4(0.0), vec4(0.0));
    mrTracedRelief = relief;
    mrTracedPixel = p;
    vec3 viewHit = (worldToCamera * vec4(p.world, 1.0)).xyz;
    vec3 viewNormal = normalize(mat3(worldToCamera) * p.normal);
    vec3 colours = p.exhausted ? vec3(1.0) : mrPixelAlbedo(albedoMap, useAlbedoMap, vec3(1.0), relief, p, viewport, rayDirDx, rayDirDy);
    return mat4(vec4(viewHit, mrFragmentDepth(viewProjection, p.world)), vec4(viewNormal, p.exhausted ? 1.0 : 0.0),
                vec4(colours, 0.0), vec4(0.0));
}

// The library's exact hard self-shadow at the hit mrTraceHit traced in this invocation (1
// lit, 0 shadowed), towards one of three's lights as three_material.glsl's
// mrSelfShadowDirection and mrSelfShadowPoint shoot it in WebGL: `light` in the camera's view
// space (three lights there), w 0 the unit direction towards a directional light (the ray to
// MR_T_INFINITY), w 1 a point or spot light's position (the ray to the light, t 1 in the
// frame); `cameraToWorld` the camera's matrixWorld about the camera (relief_three.glsl's
// mrCameraToWorld). 1 where the pixel's traversal was exhausted (shown magenta: no shadow
// from a hit that is not one), as in WebGL.
float mrSelfShadow(MICRORELIEF_SAMPLER heights, MICRORELIEF_SAMPLER windows, mat4 cameraToWorld, vec4 light) {
    if (mrTracedPixel.exhausted) return 1.0;
    vec3 toLight;
    float tMax = MR_T_INFINITY;
    if (light.w == 0.0) {
        toLight = mr_baseFrameVector(mrTracedRelief, mat3(cameraToWorld) * light.xyz);
    } else {
        vec3 world = (cameraToWorld * vec4(light.xyz, 1.0)).xyz;
        toLight = mr_baseFramePoint(mrTracedRelief, world) - mrTracedPixel.hit.position;
        tMax = 1.0;
    }
    bool exhausted = false;
    return mr_hardShadow(mrTracedRelief, windows, heights, mrTracedPixel.hit, toLight, tMax, exhausted);
}

// The world size of a shadow-map texel at `p` (three's world), for ReliefStandardNodeMaterial's
// shadow lookups (docs/three.md, "Shadow acne": the hit is moved along its normal by the map's
// reach times this before three looks it up): `m` the light's shadow matrix, a spot or
// directional light's (relief_three.glsl's mrShadowTexel) or, where `point` is 1, a point
// light's (mrPointShadowTexel), the rule the WebGL entry's three_material.glsl applies.
float mrShadowTexelSize(mat4 m, vec3 p, vec2 mapSize, float point) {
    return point == 1.0 ? mrPointShadowTexel(m, p, mapSize) : mrShadowTexel(m, p, mapSize);
}

#endif
