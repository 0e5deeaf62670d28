// window_level.frag: the overlapping pyramid's level k from its level k - 1 (GL's mip
// sizes of W x H, no padding). Window p of level k is the max of blocks p and p + 1, a
// block the max of its children 2p, 2p + 1 and, for the last of a row of n children when n
// is odd, child n - 1 too; and window x of level k - 1 (x even) is exactly the max of
// blocks x and x + 1 there. So window p reads windows 2p, 2p + 2 (when it exists) and
// 2p + 4 (when it is the odd last child, n - 1) of level k - 1, per axis: four reads,
// six or nine at the last row and column.
#include "microrelief/precision.glsl"

uniform sampler2D windows;  // the overlapping pyramid
uniform int level;          // k - 1, the level read

layout(location = 0) out vec4 bound;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 n = textureSize(windows, level);
    float best = 0.0;
    for (int b = 0; b < 3; ++b) {
        int y = 2 * p.y + 2 * b;
        if (y >= n.y || (b == 2 && y != n.y - 1)) continue;
        for (int a = 0; a < 3; ++a) {
            int x = 2 * p.x + 2 * a;
            if (x >= n.x || (a == 2 && x != n.x - 1)) continue;
            best = max(best, texelFetch(windows, ivec2(x, y), level).r);
        }
    }
    bound = vec4(best, 0.0, 0.0, 0.0);
}
