// shading.glsl: one directional light on a neutral material, Lambert diffuse plus a
// Blinn-Phong highlight and a sky/ground ambient, so that relief reads at a glance.
// Directions are world-space unit vectors: n the surface normal, l towards the light,
// v towards the viewer. Output is linear radiance: an sRGB framebuffer encodes it, or
// mr_encodeSrgb() where the target is not one.
#ifndef MICRORELIEF_SHADING_GLSL
#define MICRORELIEF_SHADING_GLSL

#include "precision.glsl"

struct mr_ReliefMaterial {
    vec3 albedo;      // diffuse reflectance, linear
    float specular;   // Blinn-Phong highlight strength
    float shininess;  // Blinn-Phong exponent
};

vec3 mr_shadeRelief(mr_ReliefMaterial material, vec3 n, vec3 l, vec3 v, vec3 lightColor) {
    float diffuse = max(dot(n, l), 0.0);
    vec3 h = normalize(l + v);
    float highlight = diffuse > 0.0 ? pow(max(dot(n, h), 0.0), material.shininess) : 0.0;
    // Hemispherical ambient: brighter facing up (y), so walls and bottom stay readable.
    vec3 ambient = mix(vec3(0.08, 0.08, 0.09), vec3(0.20, 0.21, 0.24), 0.5 + 0.5 * n.y);
    return material.albedo * (ambient + diffuse * lightColor) + material.specular * highlight * lightColor;
}

vec3 mr_encodeSrgb(vec3 linear) {
    vec3 c = clamp(linear, 0.0, 1.0);
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

// The inverse of mr_encodeSrgb: a display colour (a debug view's) as the linear value an
// sRGB framebuffer encodes back to it.
vec3 mr_decodeSrgb(vec3 encoded) {
    vec3 c = clamp(encoded, 0.0, 1.0);
    return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(vec3(0.04045), c));
}

#endif
