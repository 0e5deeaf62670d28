// cone_map.frag: the conservative cone map of the `cone` peer on the GPU, texel (i, j)'s
// (apex, ratio) as RG16F (peers/ConeMap.h has the cone's definition and the CPU build this
// one follows; gl/PyramidBuilder.h draws it). The same branch-and-bound walk of maxmip's
// quadtree (the aligned pyramid), nearest nodes first, each finest texel square that might
// narrow the cone bounded piece by piece on the half-texel grid, in float arithmetic where
// the CPU works in doubles. So that float rounding can only narrow a cone:
//  * the surface's values on the half-texel grid are upper bounds (means rounded up on the
//    floats' bits, pyramid_bound.glsl: mr_texelNineBits), which only lowers each ratio;
//    by up to a few float ulps of h, which can be many halves of the ratio where h - B is
//    small beside h (a terrain 3000 high with relief 3 high): narrower, never wider;
//  * h - B is at least 2^-126 where h > B (a difference flushed to 0 would make a ratio
//    infinite);
//  * a prune test (nodeBound) never exceeds the ratios under its node, by construction: a
//    node's bound is the largest of the nine values of its texels (the quadtree's finest
//    level is mr_texelSquareBound of the same nine), stored rounded up, and the pieces'
//    corners are those nine values;
//  * each ratio is a quotient of a distance (exact sums of half texels, or a few products,
//    a sum and a square root) by h - B (one subtraction): float errors of some 13 ulp in
//    all by GLSL 4's precision table (sqrt inherited from inversesqrt, about 4.5 ulp;
//    division 2.5 ulp; GLSL 3.30 states none, and GPUs keep to 4's), about 2^-20 relative,
//    in the prune tests as in the pieces; the walk's result is multiplied by 1 - 2^-16
//    before it is rounded down to a half, far more than those errors take, far less than a
//    half's step (2^-11).
// The apex is the CPU's bit for bit: the pyramid's finest bound (mr_texelSquareBound, the
// same bits as MaxPyramid) rounded up to a half on its bits, and at least 2^-14 where not
// 0 (a half denormal could be flushed to 0 where the output is converted to RG16F).
#include "microrelief/pyramid_bound.glsl"

uniform sampler2D heights;  // the W x H samples, R32F
uniform sampler2D aligned;  // maxmip's quadtree (padded to powers of two), halves / 2^S
uniform ivec2 mapSize;      // W, H
uniform int levelCount;     // the quadtree's levels, 1 x 1 the last
uniform int scaleExponent;  // S

layout(location = 0) out vec4 cone;

const float kConeRatioCap = 65504.0;  // peers/ConeMap.h
const float kLeastDifference = 1.17549435e-38;  // 2^-126
const float kLeastNormalHalf = 6.10351562e-5;   // 2^-14
// "No bound": above every ratio kept (an infinity, without dividing by a constant 0).
const float kFar = 3.0e38;

// The gap in texels from coordinate x to the interval [i, i + 1].
float gapTo(float x, int i) {
    return max(0.0, max(float(i) - x, x - float(i + 1)));
}

// pieceRatio of ConeMap.cpp: a lower bound of r*_T over piece (a, b) of the half-texel
// grid for square T = `texel` at plateau B, from the piece's corners h (index c: corner
// (a + (c & 1), b + (c >> 1))). Why each bound holds is said there.
float pieceRatio(ivec2 texel, float plateau, int a, int b, vec4 h) {
    float highest = max(max(h.x, h.y), max(h.z, h.w));
    if (!(highest > plateau)) return kFar;
    vec4 gx = vec4(gapTo(0.5 * float(a), texel.x), gapTo(0.5 * float(a + 1), texel.x),
                   gapTo(0.5 * float(a), texel.x), gapTo(0.5 * float(a + 1), texel.x));
    vec4 gy = vec4(gapTo(0.5 * float(b), texel.y), gapTo(0.5 * float(b), texel.y),
                   gapTo(0.5 * float(b + 1), texel.y), gapTo(0.5 * float(b + 1), texel.y));
    vec4 rise = max(h - plateau, vec4(kLeastDifference));
    bvec4 above = greaterThan(h, vec4(plateau));
    bool levelInX = a >= 2 * texel.x && a + 1 <= 2 * texel.x + 2;
    bool levelInY = b >= 2 * texel.y && b + 1 <= 2 * texel.y + 2;
    float r = kFar;
    if (levelInX || levelInY) {
        for (int c = 0; c < 4; ++c)
            if (above[c]) r = min(r, (gx[c] + gy[c]) / rise[c]);  // one gap is 0
        return r;
    }
    float mx = gapTo(0.5 * float(a) + 0.25, texel.x), my = gapTo(0.5 * float(b) + 0.25, texel.y);
    float norm = sqrt(mx * mx + my * my);
    float dmin = kFar;
    for (int c = 0; c < 4; ++c) {
        dmin = min(dmin, sqrt(gx[c] * gx[c] + gy[c] * gy[c]));
        if (above[c]) r = min(r, (mx * gx[c] + my * gy[c]) / norm / rise[c]);
    }
    return max(r, dmin / max(highest - plateau, kLeastDifference));
}

// squareRatio of ConeMap.cpp: the bound over texel square `square`, its four pieces.
float squareRatio(ivec2 texel, float plateau, ivec2 square) {
    if (square == texel) return kFar;  // h <= B on T itself
    uint nine[9];  // the square's values on the half-texel grid, index 3 d + c
    mr_texelNineBits(heights, mapSize, square, false, nine);
    float corner[9];
    for (int k = 0; k < 9; ++k) corner[k] = uintBitsToFloat(nine[k]);
    float r = kFar;
    for (int d = 0; d < 2; ++d) {
        for (int c = 0; c < 2; ++c) {
            vec4 h = vec4(corner[3 * d + c], corner[3 * d + c + 1], corner[3 * d + c + 3],
                          corner[3 * d + c + 4]);
            r = min(r, pieceRatio(texel, plateau, 2 * square.x + c, 2 * square.y + d, h));
        }
    }
    return r;
}

// A lower bound of every piece ratio under quadtree node (level, p): its finest texels lie
// at least the node's gap from T and its pieces at most its bound high (ConeMap.cpp's
// lowerBound); +inf where the node is padding or no higher than the plateau.
float nodeBound(ivec2 texel, float plateau, ivec3 node) {
    ivec2 lo = node.yz << node.x, hi = min((node.yz + 1) << node.x, mapSize);
    if (any(lessThanEqual(hi, lo))) return kFar;
    // Times 2^S, built from its bits: exact (exp2 need not be).
    float bound = texelFetch(aligned, node.yz, node.x).r * uintBitsToFloat(uint(scaleExponent + 127) << 23u);
    if (!(bound > plateau)) return kFar;
    vec2 gap = vec2(max(ivec2(0), max(lo - (texel + 1), texel - hi)));
    return length(gap) / max(bound - plateau, kLeastDifference);
}

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);  // the viewport is a band of the map's rows
    float plateau = mr_halfRoundedUp(mr_texelSquareBound(heights, mapSize, texel, false));
    if (plateau > 0.0) plateau = max(plateau, kLeastNormalHalf);
    float r = kConeRatioCap;
    // Depth-first, each node's children pushed farthest first: at most 3 L - 2 entries for
    // L levels, 64 for 22 (a map of 2^21 a side; the host refuses more).
    ivec3 stack[64];
    stack[0] = ivec3(levelCount - 1, 0, 0);
    int top = 1;
    while (top > 0) {
        ivec3 node = stack[--top];
        if (!(nodeBound(texel, plateau, node) < r)) continue;
        if (node.x == 0) {
            r = min(r, squareRatio(texel, plateau, node.yz));
            continue;
        }
        vec4 bounds;
        ivec3 children[4];
        for (int k = 0; k < 4; ++k) {
            children[k] = ivec3(node.x - 1, 2 * node.yz + ivec2(k & 1, k >> 1));
            bounds[k] = nodeBound(texel, plateau, children[k]);
        }
        // Largest bound first onto the stack, so the most promising comes off first.
        for (int k = 1; k < 4; ++k) {
            for (int m = k; m > 0 && bounds[m - 1] < bounds[m]; --m) {
                float b = bounds[m];
                bounds[m] = bounds[m - 1];
                bounds[m - 1] = b;
                ivec3 c = children[m];
                children[m] = children[m - 1];
                children[m - 1] = c;
            }
        }
        for (int k = 0; k < 4; ++k)
            if (bounds[k] < r) stack[top++] = children[k];
    }
    cone = vec4(plateau, mr_halfRoundedDown(r * (1.0 - 1.0 / 65536.0)), 0.0, 0.0);
}
