// finest_level.frag: the finest texel bounds from the map's samples, texel for texel what
// MaxPyramid keeps (microrelief/pyramid_bound.glsl), stored as halves divided by 2^S; 0
// past the map. Into the aligned pyramid's finest level (maxmip's quadtree, padded to
// powers of two: its padding 0), or a band of rows into the builder's scratch texture,
// from which window_blocks.frag makes the windows' finest level.
#include "microrelief/pyramid_bound.glsl"

uniform sampler2D heights;  // the W x H samples, R32F
uniform ivec2 mapSize;      // W, H
uniform int wrapU;          // 1: u is periodic (a curved base)
uniform int scaleExponent;  // S
uniform ivec2 texelOrigin;  // the map texel drawn at the target's (0, 0)

layout(location = 0) out vec4 bound;

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy) + texelOrigin;
    float value = 0.0;
    if (all(lessThan(texel, mapSize))) {
        uint bits = floatBitsToUint(mr_texelSquareBound(heights, mapSize, texel, wrapU != 0));
        value = mr_storedHalf(bits, scaleExponent);
    }
    bound = vec4(value, 0.0, 0.0, 0.0);
}
