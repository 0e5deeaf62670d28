// albedo.glsl: the surface's colour at a traced hit from an albedo texture over the map,
// filtered over the pixel's footprint (relief.frag's picture; any host's too).
//
// use:   vec3 c = mr_surfaceAlbedo(albedo, relief, hit, dir, n, dDx, dDy, false);
// with:  albedo  the colours over (u, v) of one tile of the map (row 0 at v = 0), sRGB
//                decoded by the sampler, mipmapped, repeating;
//        hit     the tracer's answer for the ray origin + t dir (world, dir not unit);
//        n       the world normal at the hit (mr_reliefWorldNormal);
//        dDx, dDy one pixel's step of the ray direction across and up the picture
//                (world; a perspective camera's right and up vectors times 2 / viewport
//                size when dir = forward + ndc.x right + ndc.y up);
//        finest  true: the finest level, unfiltered (what one ray sees; for tests).
// Everything the functions read is an argument: no uniforms.
// options (define before the first include, as texture_reads.glsl's hooks):
//  * MICRORELIEF_ALBEDO_TEXTURE: the type the functions take the albedo as (default
//    sampler2D; a WebGPU host's texture2D, whose sampler the next hook pairs it with);
//  * MICRORELIEF_ALBEDO_SAMPLED(albedo): what textureSize, texelFetch and textureGrad are
//    called on (default the argument itself; sampler2D(albedo, itsSampler) for a
//    texture2D). docs/webgpu.md says why: WGSL has no combined texture-samplers.
#ifndef MICRORELIEF_ALBEDO_GLSL
#define MICRORELIEF_ALBEDO_GLSL

#include "base_surface.glsl"
#include "precision.glsl"
#include "relief_hit.glsl"
#include "relief_map.glsl"

#ifndef MICRORELIEF_ALBEDO_TEXTURE
#define MICRORELIEF_ALBEDO_TEXTURE sampler2D
#endif

#ifndef MICRORELIEF_ALBEDO_SAMPLED
#define MICRORELIEF_ALBEDO_SAMPLED(albedo) albedo
#endif

// A world displacement `delta` at frame point q as a displacement of the map point (X, Y):
// linear on the plane; on a curved base the difference of the two ends' map points (delta
// is a pixel's footprint, small), X taken the short way round the seam.
vec2 mr_mapDelta(mr_Relief relief, vec3 q, vec3 delta) {
    vec3 dq = mr_baseFrameVector(relief, delta);
    // The frame is map space: the displacement is the map point's.
#if MICRORELIEF_BASE_STRAIGHT_PATH
    return dq.xy;
#else
    vec2 d = mr_baseMapPoint(relief, q + dq).xy - mr_baseMapPoint(relief, q).xy;
    d.x -= relief.map.size.x * floor(d.x / relief.map.size.x + 0.5);
    return d;
#endif
}

// The albedo's finest level, interpolated bilinearly between texel centres and repeating:
// what one ray sees with no filtering over a pixel (the supersampled pictures tests
// compare with). By texelFetch, since an anisotropic sampler may not keep to an explicit
// level (llvmpipe's does not).
vec3 mr_finestAlbedo(MICRORELIEF_ALBEDO_TEXTURE albedo, vec2 uv) {
    ivec2 size = textureSize(MICRORELIEF_ALBEDO_SAMPLED(albedo), 0);
    vec2 p = uv * vec2(size) - 0.5;
    ivec2 i0 = ivec2(floor(p));
    vec2 f = p - vec2(i0);
    ivec2 a = (i0 % size + size) % size, b = (a + 1) % size;
    vec3 c00 = texelFetch(MICRORELIEF_ALBEDO_SAMPLED(albedo), a, 0).rgb;
    vec3 c10 = texelFetch(MICRORELIEF_ALBEDO_SAMPLED(albedo), ivec2(b.x, a.y), 0).rgb;
    vec3 c01 = texelFetch(MICRORELIEF_ALBEDO_SAMPLED(albedo), ivec2(a.x, b.y), 0).rgb;
    vec3 c11 = texelFetch(MICRORELIEF_ALBEDO_SAMPLED(albedo), b, 0).rgb;
    return mix(mix(c00, c10, f.x), mix(c01, c11, f.x), f.y);
}

// The albedo averaged over a pixel's footprint with (u, v) derivatives gx, gy: anisotropic
// filtering by hand, up to 16 trilinear taps spread along the footprint's longer axis,
// each as wide as its shorter one (textureGrad with the tap's own derivatives). Done here,
// not by the sampler's anisotropy: a sampler may not keep to explicit derivatives when it
// filters anisotropically (llvmpipe's takes them from neighbouring fragments), and they
// are the point: the ray's own footprint, right at silhouettes and steep relief where
// neighbouring pixels see other surfaces.
vec3 mr_filteredAlbedo(MICRORELIEF_ALBEDO_TEXTURE albedo, vec2 uv, vec2 gx, vec2 gy) {
    vec2 texels = vec2(textureSize(MICRORELIEF_ALBEDO_SAMPLED(albedo), 0));
    float lx = length(gx * texels), ly = length(gy * texels);
    vec2 major = lx >= ly ? gx : gy, minor = lx >= ly ? gy : gx;
    float ratio = max(lx, ly) / max(min(lx, ly), 1e-6);
    int taps = int(clamp(ceil(ratio), 1.0, 16.0));
    vec2 step = major / float(taps);
    vec3 sum = vec3(0.0);
    for (int i = 0; i < taps; ++i)
        sum += textureGrad(MICRORELIEF_ALBEDO_SAMPLED(albedo), uv + step * (float(i) + 0.5 - 0.5 * float(taps)),
                           step, minor).rgb;
    return sum / float(taps);
}

// The surface's colour at the hit: the albedo texture at the hit's (u, v), filtered over
// the pixel's footprint there. The footprint comes from ray differentials (Igehy, "Tracing
// Ray Differentials", SIGGRAPH 1999): one pixel's step of the ray direction, dD, moves the
// hit on its tangent plane by t (dD - (n . dD) / (n . D) D); mapped to (u, v), the two
// steps are the footprint's axes (mr_filteredAlbedo).
vec3 mr_surfaceAlbedo(MICRORELIEF_ALBEDO_TEXTURE albedo, mr_Relief relief, mr_ReliefHit hit, vec3 dir,
                      vec3 n, vec3 dDx, vec3 dDy, bool finest) {
    // (u, v) of the tile the hit is in: the albedo repeats with the map's tiles.
    vec3 m = mr_baseMapPoint(relief, hit.position);
    vec2 tileSize = mr_tileSize(relief.map), tiles = relief.map.size / tileSize;
    vec2 uv = m.xy / tileSize;
    vec2 halfTexel = 0.5 / vec2(textureSize(MICRORELIEF_ALBEDO_SAMPLED(albedo), 0));
#if !MICRORELIEF_BASE_WRAPS_U
    uv = clamp(uv, halfTexel, tiles - halfTexel);  // the map's edges clamp (the texture repeats)
#else
    uv.y = clamp(uv.y, halfTexel.y, tiles.y - halfTexel.y);  // u wraps round the base
#endif
    if (finest) return mr_finestAlbedo(albedo, uv);
    float nd = dot(n, dir);
    nd = abs(nd) < 1e-8 ? (nd < 0.0 ? -1e-8 : 1e-8) : nd;
    vec3 dPx = hit.t * (dDx - dot(n, dDx) / nd * dir);
    vec3 dPy = hit.t * (dDy - dot(n, dDy) / nd * dir);
    vec2 gx = mr_mapDelta(relief, hit.position, dPx) / tileSize;
    vec2 gy = mr_mapDelta(relief, hit.position, dPy) / tileSize;
    return mr_filteredAlbedo(albedo, uv, gx, gy);
}

#endif
