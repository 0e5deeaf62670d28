// animate.frag: a height field that changes with time (gl/AnimatedHeights.h), evaluated
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
// The phases the fields' motions have reached, each reduced modulo 2 pi on the host in
// double (AnimatedHeights::evaluate): a float time would put a 5 rad/s phase off by a
// thousandth of a radian past 1000 s, and a GPU's sin is only accurate over a few periods.
uniform vec4 wavePhase;       // waves' four motions
uniform vec4 floodWavePhase;  // the flood's waves, running at twice the speed
uniform float ripplePhase;    // ripples' rings
uniform float floodPhase;     // the flood's water level
uniform int field;            // 0 waves, 1 ripples, 2 flood

layout(location = 0) out vec4 height;

const float kTau = 6.28318530718;

float waves(vec2 uv, vec4 motion) {
    const vec4 kx = vec4(3.0, -2.0, 5.0, 1.0), ky = vec4(1.0, 4.0, -3.0, 7.0);
    const vec4 amplitude = vec4(1.0, 0.6, 0.35, 0.25);
    vec4 phase = kTau * (kx * uv.x + ky * uv.y) - motion + vec4(0.0, 1.3, 2.1, 4.0);
    return 0.5 + 0.5 * dot(amplitude, sin(phase)) / dot(amplitude, vec4(1.0));
}

float ripples(vec2 uv, float motion) {
    vec2 aspect = vec2(mapSize) / float(max(mapSize.x, mapSize.y));
    float r = length((uv - 0.5) * aspect);
    return 0.5 + 0.4 * sin(45.0 * r - motion) * exp(-4.0 * r);
}

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    vec2 uv = (vec2(texel) + 0.5) / vec2(mapSize);
    float h;
    if (field == 0) {
        h = waves(uv, wavePhase);
    } else if (field == 1) {
        h = ripples(uv, ripplePhase);
    } else {
        float water = 0.45 + 0.3 * sin(floodPhase) + 0.03 * (waves(uv * 2.0, floodWavePhase) - 0.5);
        h = max(texelFetch(base, texel, 0).r, water);
    }
    height = vec4(clamp(h, 0.0, 1e6), 0.0, 0.0, 0.0);
}
