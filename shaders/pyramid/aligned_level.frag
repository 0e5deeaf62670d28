// aligned_level.frag: the aligned pyramid's level k (padded to powers of two) from its
// level k - 1: texel (p, q) the max of children 2p..2p+1 by 2q..2q+1 (those that exist).
// The host draws into level k with the texture's base and max level set to k - 1, so the
// level read is the only one sampled and no feedback loop arises.
#include "microrelief/precision.glsl"

uniform sampler2D aligned;  // the aligned pyramid, base level k - 1

layout(location = 0) out vec4 bound;

void main() {
    ivec2 p = 2 * ivec2(gl_FragCoord.xy);
    ivec2 last = textureSize(aligned, 0) - 1;
    float best = texelFetch(aligned, min(p, last), 0).r;
    best = max(best, texelFetch(aligned, min(p + ivec2(1, 0), last), 0).r);
    best = max(best, texelFetch(aligned, min(p + ivec2(0, 1), last), 0).r);
    best = max(best, texelFetch(aligned, min(p + 1, last), 0).r);
    bound = vec4(best, 0.0, 0.0, 0.0);
}
