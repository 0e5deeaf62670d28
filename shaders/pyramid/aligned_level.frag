// aligned_level.frag: the aligned pyramid's level k + 1 from the overlapping one's level
// k. Aligned texel (p, q) of level k + 1 is the max of its children 2p..2p+1 by 2q..2q+1
// (those that exist), which is window (2p, 2q) of level k: one read.
#include "microrelief/precision.glsl"

uniform sampler2D windows;  // the overlapping pyramid
uniform int level;          // k, the level read

layout(location = 0) out vec4 bound;

void main() {
    bound = vec4(texelFetch(windows, 2 * ivec2(gl_FragCoord.xy), level).r, 0.0, 0.0, 0.0);
}
