// biquadratic_patch.glsl: the biquadratic surface (scene-and-cli.md, "Interpolation"), the
// paper's "bi-quadratic interpolation of elevation values" at the last level: the uniform
// quadratic B-spline whose control points are the samples, smooth (C1) across texel
// edges. Over texel square (i, j), local u, v in [0, 1] (X = i + u), it is a tensor-product
// quadratic of the 3 x 3 samples i - 1..i + 1 by j - 1..j + 1 (clamped, or wrapped in u on a
// curved base), held here as its Bezier control net: per axis (c0 + c1) / 2, c1,
// (c1 + c2) / 2, since the B-spline's weights (1 - u)^2 / 2, 1/2 + u - u^2, u^2 / 2 are
// exactly those combinations of the Bernstein polynomials. The net makes bounds easy: the
// patch over any sub-rectangle lies within the convex hull of the sub-rectangle's net.
//
// `heights` is the W x H sample texture (relief_map.glsl, bilinear_patch.glsl).
#ifndef MICRORELIEF_BIQUADRATIC_PATCH_GLSL
#define MICRORELIEF_BIQUADRATIC_PATCH_GLSL

#include "bilinear_patch.glsl"
#include "relief_map.glsl"

// One sample, its column clamped or wrapped, its row clamped.
float biquadraticSample(ReliefMap map, sampler2D heights, ivec2 p) {
    ivec2 last = ivec2(map.size) - 1;
#if MICRORELIEF_BASE != 0
    p.x = p.x < 0 ? p.x + last.x + 1 : p.x > last.x ? p.x - last.x - 1 : p.x;
#else
    p.x = clamp(p.x, 0, last.x);
#endif
    p.y = clamp(p.y, 0, last.y);
    return texelFetch(heights, p, 0).r;
}

// The Bezier net of texel square `square` (net[a][b]: column a, row b, as a mat3 is
// indexed). The 3 x 3 samples are four textureGathers of 2 x 2 samples each where the GL
// has them (one fetch each), nine texelFetch otherwise.
mat3 biquadraticNet(ReliefMap map, sampler2D heights, ivec2 square, inout int fetches) {
    mat3 c;
#if MICRORELIEF_TEXTURE_GATHER
    // Each gather reads the 2 x 2 samples whose centres surround the point between them:
    // samples (i - 1..i, j - 1..j) around (i, j) in texel coordinates, and so on.
    vec2 size = map.size;
    vec4 g00 = textureGather(heights, (vec2(square) + vec2(0.0, 0.0)) / size);
    vec4 g10 = textureGather(heights, (vec2(square) + vec2(1.0, 0.0)) / size);
    vec4 g01 = textureGather(heights, (vec2(square) + vec2(0.0, 1.0)) / size);
    vec4 g11 = textureGather(heights, (vec2(square) + vec2(1.0, 1.0)) / size);
    fetches += 4;
    // Gather order: (i0, j1), (i1, j1), (i1, j0), (i0, j0).
    c[0] = vec3(g00.w, g00.x, g01.x);
    c[1] = vec3(g00.z, g00.y, g01.y);
    c[2] = vec3(g10.z, g10.y, g11.y);
#else
    for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) c[a][b] = biquadraticSample(map, heights, square + ivec2(a - 1, b - 1));
    }
    fetches += 9;
#endif
    // B-spline control points to the Bezier net, along each axis.
    mat3 rows;
    for (int b = 0; b < 3; ++b) {
        rows[0][b] = 0.5 * (c[0][b] + c[1][b]);
        rows[1][b] = c[1][b];
        rows[2][b] = 0.5 * (c[1][b] + c[2][b]);
    }
    mat3 net;
    for (int a = 0; a < 3; ++a) net[a] = vec3(0.5 * (rows[a][0] + rows[a][1]), rows[a][1], 0.5 * (rows[a][1] + rows[a][2]));
    return net;
}

// The quadratic Bernstein polynomials at u.
vec3 quadraticBernstein(float u) {
    float w = 1.0 - u;
    return vec3(w * w, 2.0 * u * w, u * u);
}

// The net summed along v with weights w: (sum over b of net[a][b] w[b]) for each column a.
vec3 netAlongV(mat3 net, vec3 w) { return vec3(dot(net[0], w), dot(net[1], w), dot(net[2], w)); }

// Height of the patch at local (u, v): the sum of net[a][b] B_a(u) B_b(v).
float biquadraticHeight(mat3 net, vec2 uv) {
    return dot(quadraticBernstein(uv.x), netAlongV(net, quadraticBernstein(uv.y)));
}

// Gradient (dh/du, dh/dv) = (dh/dX, dh/dY) of the patch at local (u, v).
vec2 biquadraticGradient(mat3 net, vec2 uv) {
    vec3 bu = quadraticBernstein(uv.x), bv = quadraticBernstein(uv.y);
    vec3 du = vec3(-2.0 * (1.0 - uv.x), 2.0 - 4.0 * uv.x, 2.0 * uv.x);
    vec3 dv = vec3(-2.0 * (1.0 - uv.y), 2.0 - 4.0 * uv.y, 2.0 * uv.y);
    return vec2(dot(du, netAlongV(net, bv)), dot(bu, netAlongV(net, dv)));
}

// The Bezier points over [a, b] of a quadratic whose Bezier points over [0, 1] are p: its
// values and polar form at (a, a), (a, b), (b, b). Column k holds the weights of p0, p1,
// p2 in the k-th point.
mat3 quadraticRestriction(float a, float b) {
    // The polar form of the Bernstein basis: (1-a)(1-b), a(1-b) + b(1-a), ab.
    vec3 polar = vec3((1.0 - a) * (1.0 - b), a * (1.0 - b) + b * (1.0 - a), a * b);
    return mat3(quadraticBernstein(a), polar, quadraticBernstein(b));
}

// The patch's max over the rectangle [lo, hi] of local coordinates (clamped to the
// square): never below it, since the patch over the rectangle lies in the convex hull of
// the rectangle's own Bezier net (the net restricted to it), whose largest entry this is.
float biquadraticMaxOver(mat3 net, vec2 lo, vec2 hi) {
    lo = clamp(lo, 0.0, 1.0);
    hi = clamp(hi, 0.0, 1.0);
    mat3 su = quadraticRestriction(lo.x, hi.x), sv = quadraticRestriction(lo.y, hi.y);
    float top = -1e30;
    for (int k = 0; k < 3; ++k) {
        // Restricted along u: column k of the sub-net, still over [0, 1] in v.
        vec3 column = net[0] * su[k][0] + net[1] * su[k][1] + net[2] * su[k][2];
        // Then along v: its three Bezier points over [lo.y, hi.y].
        top = max(top, max(max(dot(sv[0], column), dot(sv[1], column)), dot(sv[2], column)));
    }
    return top;
}

#endif
