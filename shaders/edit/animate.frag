// animate.frag: a height field that changes with time (render/AnimatedHeights.h), evaluated
// at every sample of the map, into the samples texture; the pyramids are then built anew
// from it. Heights stay in [0, 1] (flood: in the map's range), finite and >= 0.
//
//  0 waves:   four travelling sine waves; their wave numbers are whole per map width, so the
//             field joins across a curved base's seam.
//  1 ripples: rings running out from the middle, fading with the distance.
//  2 flood:   the map (`base`) under water whose level rises and falls, waves on it; stones
//             come out of it and go under again.
#include "microrelief/precision.glsl"

uniform sampler2D base;  // the map's own samples (flood)
uniform ivec2 mapSize;   // W, H
uniform float time;      // seconds
uniform int field;       // 0 waves, 1 ripples, 2 flood

layout(location = 0) out vec4 height;

const float kTau = 6.28318530718;

float waves(vec2 uv, float t) {
    const vec4 kx = vec4(3.0, -2.0, 5.0, 1.0), ky = vec4(1.0, 4.0, -3.0, 7.0);
    const vec4 speed = vec4(1.1, 1.7, 2.3, 0.9), amplitude = vec4(1.0, 0.6, 0.35, 0.25);
    vec4 phase = kTau * (kx * uv.x + ky * uv.y) - speed * t + vec4(0.0, 1.3, 2.1, 4.0);
    return 0.5 + 0.5 * dot(amplitude, sin(phase)) / dot(amplitude, vec4(1.0));
}

float ripples(vec2 uv, float t) {
    vec2 aspect = vec2(mapSize) / float(max(mapSize.x, mapSize.y));
    float r = length((uv - 0.5) * aspect);
    return 0.5 + 0.4 * sin(45.0 * r - 5.0 * t) * exp(-4.0 * r);
}

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    vec2 uv = (vec2(texel) + 0.5) / vec2(mapSize);
    float h;
    if (field == 0) {
        h = waves(uv, time);
    } else if (field == 1) {
        h = ripples(uv, time);
    } else {
        float water = 0.45 + 0.3 * sin(0.6 * time) + 0.03 * (waves(uv * 2.0, 2.0 * time) - 0.5);
        h = max(texelFetch(base, texel, 0).r, water);
    }
    height = vec4(clamp(h, 0.0, 1e6), 0.0, 0.0, 0.0);
}
