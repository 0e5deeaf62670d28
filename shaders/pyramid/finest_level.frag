// finest_level.frag: the aligned pyramid's finest level from the map's samples, texel for
// texel what MaxPyramid computes (microrelief/pyramid_bound.glsl); 0 in the padding past
// the map.
#include "microrelief/pyramid_bound.glsl"

uniform sampler2D heights;  // the W x H samples, R32F
uniform ivec2 mapSize;      // W, H
uniform int wrapU;          // 1: u is periodic (a curved base)

layout(location = 0) out vec4 bound;

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    float value = 0.0;
    if (all(lessThan(texel, mapSize))) value = mr_texelSquareBound(heights, mapSize, texel, wrapU != 0);
    bound = vec4(value, 0.0, 0.0, 0.0);
}
