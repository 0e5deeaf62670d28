// brush.frag: one dab of the sculpting brush (gl/HeightEditor.h) on the map's samples.
// Drawn over the samples the dab reaches; each reads its old height (and, to smooth, its
// 3 x 3 neighbours) from `source`, a copy of the samples around the dab made before it,
// and writes the new one, finite and >= 0 as a map's heights must be.
//
// Positions are the dab's own, unwrapped: on a curved base a dab over the seam reaches
// X < 0 or X >= W, drawn as two pieces, each shifted back by `shift` columns; `source`
// holds the columns round the dab in the same unwrapped order (the host copies them so).
//
// The falloff is (1 - d^2)^2 of the distance d from the centre in radii (0 at the rim,
// smooth there): raise and lower add or take away strength x falloff map units; smooth
// moves a sample towards the mean of its 3 x 3 neighbours, flatten towards `level`, each
// by strength x falloff of the way (at most all of it).
#include "microrelief/precision.glsl"

uniform sampler2D source;    // the samples round the dab, before it
uniform ivec2 sourceOrigin;  // the (unwrapped) map texel of source's texel (0, 0)
uniform ivec2 mapSize;       // W, H
uniform int wrapU;           // 1: columns wrap round (a curved base)
uniform int shift;           // unwrapped column = window column + shift
uniform vec2 centre;         // the dab's centre, map texels (X = u W, Y = v H), unwrapped
uniform float radius;        // map texels
uniform float strength;
uniform int mode;            // 0 raise, 1 lower, 2 smooth, 3 flatten
uniform float level;         // flatten's height, map units
uniform float ceiling;       // the largest height a dab leaves, map units

layout(location = 0) out vec4 height;

// The old sample at unwrapped texel p: rows clamped to the map, and columns too on the
// plane (the copy holds the map's columns only there).
float sourceAt(ivec2 p) {
    p.y = clamp(p.y, 0, mapSize.y - 1);
    if (wrapU == 0) p.x = clamp(p.x, 0, mapSize.x - 1);
    return texelFetch(source, p - sourceOrigin, 0).r;
}

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy) + ivec2(shift, 0);
    float old = sourceAt(texel), h = old;
    float d = length(vec2(texel) + 0.5 - centre) / radius;
    float falloff = d < 1.0 ? (1.0 - d * d) * (1.0 - d * d) : 0.0;
    float amount = strength * falloff;
    if (!(amount > 0.0)) {
        height = vec4(old, 0.0, 0.0, 0.0);  // outside the dab: the very bits it had
        return;
    }
    if (mode == 0) {
        h += amount;
    } else if (mode == 1) {
        h -= amount;
    } else if (mode == 2) {
        float sum = 0.0;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) sum += sourceAt(texel + ivec2(dx, dy));
        h = mix(h, sum / 9.0, clamp(amount, 0.0, 1.0));
    } else {
        h = mix(h, level, clamp(amount, 0.0, 1.0));
    }
    height = vec4(clamp(h, 0.0, max(ceiling, old)), 0.0, 0.0, 0.0);
}
