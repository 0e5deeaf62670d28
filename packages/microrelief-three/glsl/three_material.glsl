// three_material.glsl: the traced hit as three.js's own fragment shaders expect their
// inputs (src/materials.js splices it before main() of MeshStandardMaterial,
// MeshPhysicalMaterial, MeshDepthMaterial and MeshDistanceMaterial, and calls
// mrBeginPixel() first thing in main()).
//
// three computes per vertex what its fragment shader reads: the view position, the normal,
// the uvs, the fog depth, the shadow maps' coordinates, the logarithmic depth. On the proxy
// box those would be the box's. src/materials.js turns each of those varyings into a plain
// global and defines MR_HAS_<name> beside it (inside three's own #if, so the macro exists
// exactly where the variable does); mrBeginPixel() then gives each one the value three's
// vertex shader would have computed at the hit, from the hit's world position and normal.
//
// options: MR_SHADOW_PASS (a depth or distance material: exhausted rays cast nothing);
//          MR_SELF_SHADOW (the library's exact hard shadow, mr_hardShadow, for each of
//          three's punctual lights, on top of three's shadow maps); MR_ALBEDO_MAP (the
//          map's colours by mr_surfaceAlbedo (microrelief/albedo.glsl), filtered over the pixel's
//          footprint from ray differentials, multiplying diffuseColor).
#ifndef MICRORELIEF_THREE_MATERIAL_GLSL
#define MICRORELIEF_THREE_MATERIAL_GLSL

mrPixel mrHitPixel;
bool mrExhausted = false;

#ifdef MR_ALBEDO_MAP
uniform sampler2D mrAlbedoMap;  // the map's colours, row 0 at v = 0 (flipY false), sRGB, mipmapped

// The map's colours at the hit, filtered over the pixel's footprint (microrelief/albedo.glsl,
// as relief.frag draws them).
vec3 mrSurfaceAlbedo() {
    vec2 pixel = 2.0 / mrViewport.zw;
    return mr_surfaceAlbedo(mrAlbedoMap, mrRelief(), mrHitPixel.hit, mrHitPixel.dir, mrHitPixel.normal,
                            mrRayDirDx * pixel.x, mrRayDirDy * pixel.y, false);
}
#endif

#ifdef USE_SHADOWMAP
// The shadow bias that follows the shadow map's texel (docs/three.md, "Shadow acne"). A
// shadow-map texel holds the traced depth of the one light ray through its centre; a
// receiver's traced hit P compares its own depth with texels whose centres lie up to a
// reach d (world units, across the light's rays) from its own ray: half a texel's diagonal
// for the nearest texel (BASIC), the PCF taps' radius plus a diagonal for three's filtered
// lookups (each tap a bilinear compare of the four texels about it). Where the surface is
// locally a plane at an angle theta between its normal and the light, the depth of a ray d
// away differs from P's by at most d tan(theta) world units along the light, unbounded at
// grazing light. Moved along its normal by b before the lookup, P stands b / cos(theta)
// nearer the light than the plane below it along the ray, so no texel within d shadows it
// where b / cos(theta) > d tan(theta), i.e. b > d sin(theta): b = d holds at every angle.
// d is reach texels of the map's world size at P: the frustum's width / mapSize for a
// directional light, the same at P's depth for a spot light (its projective matrix's
// derivative), 2 |P - light|_max / mapSize on a point light's cube face. Concave bends
// within d and the depth buffer's own steps are not covered (the user's normalBias and bias
// add to it).
float mrShadowReach(float radius) {
#ifdef SHADOWMAP_TYPE_BASIC
    return 0.70710678;
#else
    return radius + 1.41421356;
#endif
}

// The normal offset the texel asks for, world units (mrShadowReach texels).
float mrShadowTexelBias(mat4 m, vec3 p, vec2 mapSize, float radius) {
    return mrShadowReach(radius) * mrShadowTexel(m, p, mapSize);
}

float mrPointShadowTexelBias(mat4 m, vec3 p, vec2 mapSize, float radius) {
    return mrShadowReach(radius) * mrPointShadowTexel(m, p, mapSize);
}
#endif

void mrBeginPixel() {
    if (mrFaceRejected() || !mrTracePixel(mrHitPixel)) discard;
    mrExhausted = mrHitPixel.exhausted;
#ifdef MR_SHADOW_PASS
    if (mrExhausted) discard;  // no shadow from a ray that did not finish
#endif
    // `world` about the camera (relief_three.glsl), for this draw's matrices; `threeWorld`
    // three's own, for its world-space uniforms (shadow and light matrices, fog of the
    // world, environment maps).
    vec3 world = mrHitPixel.world, normal = mrHitPixel.normal;
    vec3 threeWorld = world + mrWorldOrigin;
    vec4 clip;
    float depth = mrExhausted ? gl_FragCoord.z : mrWindowDepth(world, clip);
#ifdef USE_LOGARITHMIC_DEPTH_BUFFER
    if (!mrExhausted) depth = mrLogarithmicDepth(clip, depth);
#endif
    gl_FragDepth = depth;
    // In the camera's view space, where three lights: the view matrix of this draw.
    mat4 worldToView = mrWorldToCamera;
    vec3 viewHit = (worldToView * vec4(world, 1.0)).xyz;
#ifdef MR_HAS_vViewPosition
    vViewPosition = -viewHit;
#endif
#ifdef MR_HAS_vNormal
    vNormal = normalize(mat3(worldToView) * normal);
#endif
#ifdef MR_HAS_vFogDepth
    vFogDepth = -viewHit.z;
#endif
#ifdef MR_HAS_vClipPosition
    vClipPosition = -viewHit;
#endif
#ifdef MR_HAS_vWorldPosition
    vWorldPosition = threeWorld;
#endif
#ifdef MR_HAS_vHighPrecisionZW
    vHighPrecisionZW = clip.zw;
#endif
#ifdef MR_HAS_vFragDepth
    vFragDepth = 1.0 + clip.w;
#endif
#ifdef MR_HAS_vIsPerspective
    vIsPerspective = float(mrPerspective);
#endif
#ifdef MR_HAS_vDirectionalShadowCoord
    for (int i = 0; i < NUM_DIR_LIGHT_SHADOWS; ++i)
        vDirectionalShadowCoord[i] = directionalShadowMatrix[i] * vec4(threeWorld + normal * (directionalLightShadows[i].shadowNormalBias +
            mrShadowTexelBias(directionalShadowMatrix[i], threeWorld, directionalLightShadows[i].shadowMapSize, directionalLightShadows[i].shadowRadius)), 1.0);
#endif
#ifdef MR_HAS_vPointShadowCoord
    for (int i = 0; i < NUM_POINT_LIGHT_SHADOWS; ++i)
        vPointShadowCoord[i] = pointShadowMatrix[i] * vec4(threeWorld + normal * (pointLightShadows[i].shadowNormalBias +
            mrPointShadowTexelBias(pointShadowMatrix[i], threeWorld, pointLightShadows[i].shadowMapSize, pointLightShadows[i].shadowRadius)), 1.0);
#endif
#ifdef MR_HAS_vSpotLightCoord
    for (int i = 0; i < NUM_SPOT_LIGHT_COORDS; ++i) {
        vec3 p = threeWorld;
#if defined(USE_SHADOWMAP) && NUM_SPOT_LIGHT_SHADOWS > 0
        if (i < NUM_SPOT_LIGHT_SHADOWS) p += normal * (spotLightShadows[i].shadowNormalBias +
            mrShadowTexelBias(spotLightMatrix[i], threeWorld, spotLightShadows[i].shadowMapSize, spotLightShadows[i].shadowRadius));
#endif
        vSpotLightCoord[i] = spotLightMatrix[i] * vec4(p, 1.0);
    }
#endif
#ifdef MR_HAS_vSunShadowWorldPosition
    vSunShadowWorldPosition = vec4(threeWorld, -viewHit.z);
#endif
#ifdef MR_HAS_vSunShadowWorldNormal
    vSunShadowWorldNormal = normal;
#endif
    MR_UV_ASSIGNMENTS  // src/materials.js puts here each uv varying of this shader, through its map's transform (no comment: the build strips those)
}

// The tangent frame at the hit in view space (three's getTangentFrame, which takes it from
// screen-space derivatives that break at every silhouette): the map's u and v axes on the
// surface (mr_baseTangentFrame) through the model, v flipped to three's uv, orthonormalised
// against the shading normal.
mat3 mrTangentFrame(vec3 normal, vec2 unusedUv) {
    mr_Relief relief = mrRelief();
    vec3 q = mrHitPixel.hit.position, alongX, alongY, alongH;
    mr_baseTangentFrame(relief, mr_baseMapPoint(relief, q), alongX, alongY, alongH);
    mat3 toView = mat3(mrWorldToCamera) * mat3(mrObjectToWorld);
    vec3 origin = mr_baseFrameToObject(relief, q);
    vec3 t = toView * (mr_baseFrameToObject(relief, q + alongX) - origin);
    vec3 b = -(toView * (mr_baseFrameToObject(relief, q + alongY) - origin));
    t = normalize(t - dot(t, normal) * normal);
    vec3 c = cross(normal, t);
    return mat3(t, dot(c, b) < 0.0 ? -c : c, normal);
}

// The library's exact hard shadow from the hit towards a light (1 lit, 0 shadowed): the
// frame vector `frameToLight` up to tMax (relief.frag's lightVisibility).
float mrSelfShadow(vec3 frameToLight, float tMax) {
#ifdef MR_SELF_SHADOW
    if (mrExhausted) return 1.0;
    bool exhausted = false;
    return mr_hardShadow(mrRelief(), mrWindows, mrHeights, mrHitPixel.hit, frameToLight, tMax, exhausted);
#else
    return 1.0;
#endif
}

// three's lights are in view space: a direction towards a directional (or sun) light, the
// position of a point or spot light.
float mrSelfShadowDirection(vec3 viewDirection) {
    return mrSelfShadow(mr_baseFrameVector(mrRelief(), mat3(mrCameraToWorld) * viewDirection), MR_T_INFINITY);
}

float mrSelfShadowPoint(vec3 viewPosition) {
    mr_Relief relief = mrRelief();
    vec3 world = (mrCameraToWorld * vec4(viewPosition, 1.0)).xyz;
    return mrSelfShadow(mr_baseFramePoint(relief, world) - mrHitPixel.hit.position, 1.0);
}

#endif
