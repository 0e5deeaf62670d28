// pyramid_bound.glsl: the finest level of the max pyramid, texel by texel, as MaxPyramid
// computes it (core/heightmap/MaxPyramid.h: texelSquareBound, roundUpMean), bit for bit.
//
// Texel (i, j) covers texel square [i, i+1] x [j, j+1] of map space and holds a bound of
// the surface over it: the largest of nine values made from the 3 x 3 samples around
// sample (i, j): the sample, the means of its neighbours along each axis, and of the 2 x 2
// blocks it shares (rows first, then columns). They are the bilinear surface's peaks over
// the square and the biquadratic piece's Bezier control net alike. Each mean is rounded up
// to a float, so the bound is never below the surface.
//
// Why integers: a mean computed in float arithmetic rounds to nearest (or however the GPU
// rounds: GLSL 3.30 leaves it open), may lose a denormal, and a compiler may rearrange
// it; none of that can make a bound one ulp low here. mr_roundUpMeanBits works on the
// floats' bits in 32-bit unsigned arithmetic, exact on every GPU and CPU alike. Heights
// are >= 0 and finite; the sign bit is cleared, so -0 reads as 0.
#ifndef MICRORELIEF_PYRAMID_BOUND_GLSL
#define MICRORELIEF_PYRAMID_BOUND_GLSL

#include "precision.glsl"
#include "texture_reads.glsl"

// The bits of the smallest float not below (a + b) / 2, from the bits of a and b
// (floats >= 0). Each float is f * 2^(Q - 150), f its 24-bit significand (a denormal: its
// mantissa, Q = 1). The larger one's significand is shifted left by three guard bits, the
// smaller one's aligned to it; bits that fall below the guard bits are only remembered as
// nonzero (`lost`), which is all the rounding needs, since they are less than the
// result's last place. The mean keeps 24 bits (fewer among the denormals); a nonzero
// dropped bit rounds it up by one unit, and a carry out of the significand moves into the
// exponent field by itself.
uint mr_roundUpMeanBits(uint a, uint b) {
    uint hi = max(a, b), lo = min(a, b);
    uint eh = hi >> 23u, el = lo >> 23u;
    uint fh = eh == 0u ? hi : ((hi & 0x7fffffu) | 0x800000u);
    uint fl = el == 0u ? lo : ((lo & 0x7fffffu) | 0x800000u);
    uint qh = max(eh, 1u), ql = max(el, 1u);
    uint d = qh - ql;
    uint sum = fh << 3u, lost = 0u;
    if (d <= 3u) {
        sum += fl << (3u - d);
    } else {
        uint k = min(d - 3u, 31u);
        sum += fl >> k;
        lost = fl & ((1u << k) - 1u);
    }
    uint shift = sum >= 0x8000000u ? 4u : 3u;
    uint q = qh - 4u + shift;
    if (q == 0u) {
        shift += 1u;
        q = 1u;
    }
    lost |= sum & ((1u << shift) - 1u);
    return ((q - 1u) << 23u) + (sum >> shift) + (lost != 0u ? 1u : 0u);
}

float mr_roundUpMean(float a, float b) {
    return uintBitsToFloat(mr_roundUpMeanBits(floatBitsToUint(a) & 0x7fffffffu, floatBitsToUint(b) & 0x7fffffffu));
}

// Sample (i, j) of the W x H map `heights` (texelFetch, level 0), the sign bit cleared:
// rows clamped to the edge, columns clamped too, or wrapped round when `wrapU` (a curved
// base's periodic u).
uint mr_sampleBits(MICRORELIEF_SAMPLER heights, ivec2 size, ivec2 p, bool wrapU) {
    p.y = clamp(p.y, 0, size.y - 1);
    p.x = wrapU ? (p.x < 0 ? p.x + size.x : (p.x >= size.x ? p.x - size.x : p.x)) : clamp(p.x, 0, size.x - 1);
    return floatBitsToUint(MICRORELIEF_READ_SAMPLE(heights, p)) & 0x7fffffffu;
}

// The nine values of texel (i, j) of a W x H map (see the top of this file) as bits: index
// 3 d + c for the point (i + c / 2, j + d / 2) of map space, c, d in 0..2 (so the bilinear
// surface's values at the texel square's corners, edge midpoints and sample; rounded up).
void mr_texelNineBits(MICRORELIEF_SAMPLER heights, ivec2 size, ivec2 texel, bool wrapU,
                      out uint nine[9]) {
    uint rows[9];
    for (int b = 0; b < 3; ++b) {
        uint c0 = mr_sampleBits(heights, size, texel + ivec2(-1, b - 1), wrapU);
        uint c1 = mr_sampleBits(heights, size, texel + ivec2(0, b - 1), wrapU);
        uint c2 = mr_sampleBits(heights, size, texel + ivec2(1, b - 1), wrapU);
        rows[3 * b] = mr_roundUpMeanBits(c0, c1);
        rows[3 * b + 1] = c1;
        rows[3 * b + 2] = mr_roundUpMeanBits(c1, c2);
    }
    for (int c = 0; c < 3; ++c) {
        nine[c] = mr_roundUpMeanBits(rows[c], rows[3 + c]);
        nine[3 + c] = rows[3 + c];
        nine[6 + c] = mr_roundUpMeanBits(rows[3 + c], rows[6 + c]);
    }
}

// The finest level's texel (i, j) of a W x H map: the largest of its nine values, taken on
// the bits, which order as the values do. Not rounded for storage (mr_storedHalf).
float mr_texelSquareBound(MICRORELIEF_SAMPLER heights, ivec2 size, ivec2 texel, bool wrapU) {
    uint nine[9];
    mr_texelNineBits(heights, size, texel, wrapU, nine);
    uint best = 0u;
    for (int k = 0; k < 9; ++k) best = max(best, nine[k]);
    return uintBitsToFloat(best);
}

// The finest windows' bound (max_pyramid.glsl): the largest of the texel bounds of texels
// (i, j) to (i + 1, j + 1) that lie in the W x H map, as bits. Their nine values share a
// 5 x 5 lattice over the 4 x 4 samples round them: the row means of each sample row
// (rows first, as for one texel), then the means down the lattice's columns; each texel's
// nine are a 3 x 3 part of it, computed in the same order, so the same bits.
uint mr_texelBlockBoundBits(MICRORELIEF_SAMPLER heights, ivec2 size, ivec2 texel, bool wrapU) {
    uint rows[20];  // 4 sample rows x 5: mean, sample, mean, sample, mean
    for (int b = 0; b < 4; ++b) {
        uint c0 = mr_sampleBits(heights, size, texel + ivec2(-1, b - 1), wrapU);
        uint c1 = mr_sampleBits(heights, size, texel + ivec2(0, b - 1), wrapU);
        uint c2 = mr_sampleBits(heights, size, texel + ivec2(1, b - 1), wrapU);
        uint c3 = mr_sampleBits(heights, size, texel + ivec2(2, b - 1), wrapU);
        rows[5 * b] = mr_roundUpMeanBits(c0, c1);
        rows[5 * b + 1] = c1;
        rows[5 * b + 2] = mr_roundUpMeanBits(c1, c2);
        rows[5 * b + 3] = c2;
        rows[5 * b + 4] = mr_roundUpMeanBits(c2, c3);
    }
    // Lattice columns 0..2 belong to texel column i, 2..4 to i + 1; rows alike. Fixed
    // loops and masks rather than bounds that vary: the loops unroll and the array stays
    // in registers (with a varying bound llvmpipe kept it in memory: four times slower).
    bool nextColumn = texel.x + 1 < size.x, nextRow = texel.y + 1 < size.y;
    uint best = 0u;
    for (int c = 0; c < 5; ++c) {
        uint column = max(mr_roundUpMeanBits(rows[c], rows[5 + c]),
                          max(rows[5 + c], mr_roundUpMeanBits(rows[5 + c], rows[10 + c])));
        uint below = max(rows[10 + c], mr_roundUpMeanBits(rows[10 + c], rows[15 + c]));
        column = nextRow ? max(column, below) : column;
        best = (c < 3 || nextColumn) ? max(best, column) : best;
    }
    return best;
}

// A bound as the GPU stores it (MaxPyramid.h: storedBound, BoundPrecision::Half), divided
// by 2^S: rounded up to 11 significant bits, at least 2^-14 when not 0, so a normal half
// exactly (the conversion to R16F is exact, whatever its rounding), +inf past a half's
// range (which a stale S can give; the builder then builds again with a fitting one).
float mr_storedHalf(uint boundBits, int scaleExponent) {
    if (boundBits == 0u) return 0.0;
    uint rounded = (boundBits + 0x1fffu) & ~0x1fffu;
    uint smallest = uint(scaleExponent - 14 + 127) << 23u;
    uint bits = max(rounded, smallest);
    if (bits >= 0x7f800000u) return uintBitsToFloat(0x7f800000u);
    int exponent = int(bits >> 23u) - scaleExponent;  // biased, after the division
    if (exponent > 127 + 15) return uintBitsToFloat(0x7f800000u);  // 65536 or more
    return uintBitsToFloat((uint(exponent) << 23u) | (bits & 0x7fffffu));
}

// Half floats on a float's bits, as peers/ConeMap.h's halfRoundedUp and halfRoundedDown give
// them (the cone map's values, gl/PyramidBuilder.h): the smallest half not below x (x >= 0,
// finite; +inf past 65504), and the largest not above it (65504 past it). A half's normal
// range keeps 10 of the float's 23 mantissa bits; below 2^-14 halves are multiples of
// 2^-24, x / 2^-24 = m / 2^(126 - e) for x = m 2^(e - 150), a shift of 13 to 23 where x is at
// least 2^-24 (e >= 103); below that the answer is the least half or 0 (no shift of 32 or
// more, which GLSL leaves undefined).
float mr_halfRoundedUp(float x) {
    uint bits = floatBitsToUint(x), e = bits >> 23u;
    if (bits == 0u) return 0.0;
    if (x > 65504.0) return uintBitsToFloat(0x7f800000u);
    if (e >= 113u) return uintBitsToFloat((bits + 0x1fffu) & ~0x1fffu);
    if (e <= 102u) return 5.96046448e-8;  // below 2^-24: the least half
    uint m = (bits & 0x7fffffu) | 0x800000u, shift = 126u - e;
    uint units = (m >> shift) + ((m & ((1u << shift) - 1u)) != 0u ? 1u : 0u);
    return float(units) * 5.96046448e-8;
}

float mr_halfRoundedDown(float x) {
    if (!(x > 0.0)) return 0.0;
    if (x >= 65504.0) return 65504.0;
    uint bits = floatBitsToUint(x), e = bits >> 23u;
    if (e >= 113u) return uintBitsToFloat(bits & ~0x1fffu);
    if (e <= 102u) return 0.0;
    uint m = (bits & 0x7fffffu) | 0x800000u;
    return float(m >> (126u - e)) * 5.96046448e-8;
}

#endif
