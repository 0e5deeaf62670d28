// window_level.frag: the overlapping pyramid's level k from the aligned one's: texel
// (p, q) the max of aligned texels p..p+1 by q..q+1 (0 past the level's last row or
// column), as MaxPyramid's windows.
#include "microrelief/precision.glsl"

uniform sampler2D aligned;  // the aligned pyramid
uniform int level;          // k

layout(location = 0) out vec4 bound;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 last = textureSize(aligned, level) - 1;
    float best = texelFetch(aligned, p, level).r;
    if (p.x < last.x) best = max(best, texelFetch(aligned, p + ivec2(1, 0), level).r);
    if (p.y < last.y) best = max(best, texelFetch(aligned, p + ivec2(0, 1), level).r);
    if (p.x < last.x && p.y < last.y) best = max(best, texelFetch(aligned, p + 1, level).r);
    bound = vec4(best, 0.0, 0.0, 0.0);
}
