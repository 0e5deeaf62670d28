// window_blocks.frag: the overlapping pyramid's finest level from a band of finest texel
// bounds (finest_level.frag's, in the builder's scratch texture, one row more than the
// band): window (p, q) the max of texels p..p+1 by q..q+1 that lie in the map. The same
// bits as window_finest.frag, which makes the four bounds itself, for a quarter of the
// arithmetic: each bound is made once here, not once for each window that covers it.
#include "microrelief/precision.glsl"

uniform sampler2D bounds;  // texel (i, j - firstRow) the stored bound of texel (i, j)
uniform ivec2 mapSize;     // W, H
uniform int firstRow;      // the map row of the scratch's row 0

layout(location = 0) out vec4 bound;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 local = p - ivec2(0, firstRow);
    float best = texelFetch(bounds, local, 0).r;
    bool nextColumn = p.x + 1 < mapSize.x, nextRow = p.y + 1 < mapSize.y;
    if (nextColumn) best = max(best, texelFetch(bounds, local + ivec2(1, 0), 0).r);
    if (nextRow) best = max(best, texelFetch(bounds, local + ivec2(0, 1), 0).r);
    if (nextColumn && nextRow) best = max(best, texelFetch(bounds, local + 1, 0).r);
    bound = vec4(best, 0.0, 0.0, 0.0);
}
