// microrelief_shading.frag: ReliefShadingMaterial's fragment shader, the picture
// microrelief-render draws (relief.frag's shaded view: mr_shadeRelief of one directional
// light, the map's albedo by mr_surfaceAlbedo, the hard self-shadow as an option) for a
// relief in a three.js scene, written through three's output conversion (colour space; no
// tone mapping by default). Spliced after the library and relief_three.glsl by
// src/materials.js.
//
// options: MICRORELIEF_ALBEDO_MAP (1: the albedo texture, else `albedo`), MICRORELIEF_SHADOWS
//          (MR_SHADOWS_OFF or MR_SHADOWS_HARD: the library's variants.glsl).
uniform vec3 mrLightDirection;  // towards the light, world, unit
uniform vec3 albedo;            // linear, without an albedo texture
uniform sampler2D albedoMap;    // the map's colours, row 0 at v = 0 (flipY false), sRGB, mipmapped

// relief.frag's surfaceAlbedo: the texture filtered over the pixel's footprint, or `albedo`.
vec3 surfaceAlbedo(mr_Relief relief, mrPixel p) {
#if MICRORELIEF_ALBEDO_MAP
    vec2 pixel = 2.0 / mrViewport.zw;
    return mr_surfaceAlbedo(albedoMap, relief, p.hit, p.dir, p.normal, mrRayDirDx * pixel.x, mrRayDirDy * pixel.y, false);
#else
    return albedo;
#endif
}

void main() {
    mrPixel p;
    if (mrFaceRejected() || !mrTracePixel(p)) discard;
    if (p.exhausted) {
        // Never silent: a traversal cut short by its budget shows magenta (relief.frag).
        gl_FragColor = vec4(1.0, 0.0, 1.0, 1.0);
        gl_FragDepth = gl_FragCoord.z;
        return;
    }
    // The shading both entries run (relief_three.glsl's mrShadeHit).
    mr_Relief relief = mrRelief();
    bool exhausted = false;
    vec3 colour = mrShadeHit(relief, mrWindows, mrHeights, p, mrLightDirection, surfaceAlbedo(relief, p),
                             MICRORELIEF_SHADOWS == MR_SHADOWS_HARD, exhausted);
    if (exhausted) {
        gl_FragColor = vec4(1.0, 0.0, 1.0, 1.0);
        gl_FragDepth = gl_FragCoord.z;
        return;
    }
    gl_FragColor = vec4(colour, 1.0);
    vec4 clip;
    float depth = mrWindowDepth(p.world, clip);
#ifdef USE_LOGARITHMIC_DEPTH_BUFFER
    depth = mrLogarithmicDepth(clip, depth);
#endif
    gl_FragDepth = depth;
#include <tonemapping_fragment>
#include <colorspace_fragment>
}
