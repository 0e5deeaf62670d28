// window_finest.frag: the overlapping pyramid's finest level from the map's samples:
// window (p, q) the max of the texel bounds of texels p..p+1 by q..q+1 in the map (its
// blocks are the finest texels), stored as a half divided by 2^S, as MaxPyramid keeps it.
// There is no aligned level to read it from: the windows are all the multilevel method
// needs, so the texel bounds are made here, four at a time from one 5 x 5 lattice.
#include "microrelief/pyramid_bound.glsl"

uniform sampler2D heights;  // the W x H samples, R32F
uniform ivec2 mapSize;      // W, H
uniform int wrapU;          // 1: u is periodic (a curved base)
uniform int scaleExponent;  // S

layout(location = 0) out vec4 bound;

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    uint bits = mr_texelBlockBoundBits(heights, mapSize, texel, wrapU != 0);
    bound = vec4(mr_storedHalf(bits, scaleExponent), 0.0, 0.0, 0.0);
}
