// debug_views.glsl: colourings that show how the method works, per pixel: how many
// segments the traversal visited (a heat map), the pyramid level where it stopped,
// normals, depth and world position. Inputs are plain numbers; outputs display RGB.
#ifndef MICRORELIEF_DEBUG_VIEWS_GLSL
#define MICRORELIEF_DEBUG_VIEWS_GLSL

#include "precision.glsl"

const int MR_DEBUG_VIEW_SHADED = 0;
const int MR_DEBUG_VIEW_ITERATIONS = 1;  // segments visited, heat map
const int MR_DEBUG_VIEW_LEVEL = 2;       // pyramid level of the last segment
const int MR_DEBUG_VIEW_NORMAL = 3;      // world normal, n * 0.5 + 0.5
const int MR_DEBUG_VIEW_DEPTH = 4;       // distance from the eye, near bright
const int MR_DEBUG_VIEW_POSITION = 5;    // world position over the relief's box

// A perceptually ordered map from 0 (dark blue) through green and yellow to 1 (red):
// a cubic fit of the "turbo" colormap (A. Mikhailov, 2019), good enough for a heat map.
vec3 mr_heatColor(float x) {
    x = clamp(x, 0.0, 1.0);
    vec4 v4 = vec4(1.0, x, x * x, x * x * x);
    vec2 v2 = v4.zw * v4.z;
    vec3 color = vec3(dot(v4, vec4(0.13572138, 4.61539260, -42.66032258, 132.13108234)) +
                          dot(v2, vec2(-152.94239396, 59.28637943)),
                      dot(v4, vec4(0.09140261, 2.19418839, 4.84296658, -14.18503333)) +
                          dot(v2, vec2(4.27729857, 2.82956604)),
                      dot(v4, vec4(0.10667330, 12.64194608, -60.58204836, 110.36276771)) +
                          dot(v2, vec2(-89.90310912, 27.34824973)));
    return clamp(color, 0.0, 1.0);
}

// `value` in [0, scale] as a heat colour, scale > 0.
vec3 mr_debugScalar(float value, float scale) { return mr_heatColor(value / max(scale, 1e-6)); }

vec3 mr_debugNormal(vec3 n) { return n * 0.5 + 0.5; }

// Position inside the box [boxMin, boxMax] as RGB.
vec3 mr_debugPosition(vec3 p, vec3 boxMin, vec3 boxMax) { return clamp((p - boxMin) / max(boxMax - boxMin, vec3(1e-6)), 0.0, 1.0); }

#endif
