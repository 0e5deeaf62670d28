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

#include "base_surface.glsl"
#include "bilinear_patch.glsl"
#include "fetch_count.glsl"
#include "final_piece.glsl"
#include "map_addressing.glsl"
#include "relief_map.glsl"
#include "texture_reads.glsl"

// One sample, its column clamped or wrapped, its row clamped (map_addressing.glsl).
float mr_biquadraticSample(mr_Relief relief, MICRORELIEF_SAMPLER heights, ivec2 p) {
    return MICRORELIEF_READ_SAMPLE(heights, mr_sampleTexel(relief, p));
}

// The Bezier net of the square whose 3 x 3 B-spline control points (samples) are c (c[a][b]:
// column a, row b): per axis (c0 + c1) / 2, c1, (c1 + c2) / 2.
mat3 mr_biquadraticNetOf(mat3 c) {
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

// The Bezier net of texel square `square` (net[a][b]: column a, row b, as a mat3 is
// indexed). The 3 x 3 samples are four textureGathers of 2 x 2 samples each where the GL
// has them (one fetch each), nine texelFetch otherwise.
mat3 mr_biquadraticNet(mr_Relief relief, MICRORELIEF_SAMPLER heights, ivec2 square) {
    mat3 c;
#if MICRORELIEF_TEXTURE_GATHER
#if MICRORELIEF_TILING
    // A tiled map's REPEATing texture carries the gathers across the seams between tiles,
    // from the square's sample clamped to the map; at the map's own clamped edges the
    // gathered columns and rows are then chosen as the clamped map has them (below).
    vec2 size = mr_tileSize(relief.map), corner = vec2(mr_sampleTexel(relief, square));
#else
    vec2 size = relief.map.size, corner = vec2(square);
#endif
    {
        // Each gather reads the 2 x 2 samples whose centres surround the point between
        // them: samples (i - 1..i, j - 1..j) around (i, j) in texel coordinates, and so on.
        vec4 g00 = MICRORELIEF_GATHER_SAMPLES(heights, (corner + vec2(0.0, 0.0)) / size);
        vec4 g10 = MICRORELIEF_GATHER_SAMPLES(heights, (corner + vec2(1.0, 0.0)) / size);
        vec4 g01 = MICRORELIEF_GATHER_SAMPLES(heights, (corner + vec2(0.0, 1.0)) / size);
        vec4 g11 = MICRORELIEF_GATHER_SAMPLES(heights, (corner + vec2(1.0, 1.0)) / size);
        MICRORELIEF_FETCHED(4);
        // Gather order: (i0, j1), (i1, j1), (i1, j0), (i0, j0).
        c[0] = vec3(g00.w, g00.x, g01.x);
        c[1] = vec3(g00.z, g00.y, g01.y);
        c[2] = vec3(g10.z, g10.y, g11.y);
    }
#if MICRORELIEF_TILING
    // Gathered column k holds sample s - 1 + k of the clamped square s; the square's column
    // a needs sample clamp(square - 1 + a), which is column clamp(square - 1 + a) - s + 1:
    // never the wrapped column 0 when s is the first sample, nor 2 when it is the last.
    ivec2 last = ivec2(relief.map.size) - 1, s = clamp(square, ivec2(0), last);
    mat3 gathered = c;
    for (int k = 0; k < 3; ++k) {
        ivec2 pick = clamp(square - 1 + k, ivec2(0), last) - s + 1;
#if MICRORELIEF_BASE_WRAPS_U
        pick.x = k;  // u wraps: the gathered columns are the square's
#endif
        c[k] = gathered[pick.x];
    }
    gathered = c;
    for (int k = 0; k < 3; ++k) {
        int pick = clamp(square.y - 1 + k, 0, last.y) - s.y + 1;
        for (int a = 0; a < 3; ++a) c[a][k] = gathered[a][pick];
    }
#endif
#else
    for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) c[a][b] = mr_biquadraticSample(relief, heights, square + ivec2(a - 1, b - 1));
    }
    MICRORELIEF_FETCHED(9);
#endif
    return mr_biquadraticNetOf(c);
}

// The quadratic Bernstein polynomials at u.
vec3 mr_quadraticBernstein(float u) {
    float w = 1.0 - u;
    return vec3(w * w, 2.0 * u * w, u * u);
}

// The net summed along v with weights w: (sum over b of net[a][b] w[b]) for each column a.
vec3 mr_netAlongV(mat3 net, vec3 w) { return vec3(dot(net[0], w), dot(net[1], w), dot(net[2], w)); }

// Height of the patch at local (u, v): the sum of net[a][b] B_a(u) B_b(v).
float mr_biquadraticHeight(mat3 net, vec2 uv) {
    return dot(mr_quadraticBernstein(uv.x), mr_netAlongV(net, mr_quadraticBernstein(uv.y)));
}

// Gradient (dh/du, dh/dv) = (dh/dX, dh/dY) of the patch at local (u, v).
vec2 mr_biquadraticGradient(mat3 net, vec2 uv) {
    vec3 bu = mr_quadraticBernstein(uv.x), bv = mr_quadraticBernstein(uv.y);
    vec3 du = vec3(-2.0 * (1.0 - uv.x), 2.0 - 4.0 * uv.x, 2.0 * uv.x);
    vec3 dv = vec3(-2.0 * (1.0 - uv.y), 2.0 - 4.0 * uv.y, 2.0 * uv.y);
    return vec2(dot(du, mr_netAlongV(net, bv)), dot(bu, mr_netAlongV(net, dv)));
}

// The Bezier points over [a, b] of a quadratic whose Bezier points over [0, 1] are p: its
// values and polar form at (a, a), (a, b), (b, b). Column k holds the weights of p0, p1,
// p2 in the k-th point.
mat3 mr_quadraticRestriction(float a, float b) {
    // The polar form of the Bernstein basis: (1-a)(1-b), a(1-b) + b(1-a), ab.
    vec3 polar = vec3((1.0 - a) * (1.0 - b), a * (1.0 - b) + b * (1.0 - a), a * b);
    return mat3(mr_quadraticBernstein(a), polar, mr_quadraticBernstein(b));
}

// The patch's max over the rectangle [lo, hi] of local coordinates (clamped to the
// square): never below it, since the patch over the rectangle lies in the convex hull of
// the rectangle's own Bezier net (the net restricted to it), whose largest entry this is.
float mr_biquadraticMaxOver(mat3 net, vec2 lo, vec2 hi) {
    lo = clamp(lo, 0.0, 1.0);
    hi = clamp(hi, 0.0, 1.0);
    mat3 su = mr_quadraticRestriction(lo.x, hi.x), sv = mr_quadraticRestriction(lo.y, hi.y);
    float top = -1e30;
    for (int k = 0; k < 3; ++k) {
        // Restricted along u: column k of the sub-net, still over [0, 1] in v.
        vec3 column = net[0] * su[k][0] + net[1] * su[k][1] + net[2] * su[k][2];
        // Then along v: its three Bezier points over [lo.y, hi.y].
        top = max(top, max(max(dot(sv[0], column), dot(sv[1], column)), dot(sv[2], column)));
    }
    return top;
}

// ---- Along a straight path (the plane): the patch minus the ray is a quartic ----
//
// Over a stretch of a straight ray inside one texel square, from local point fa to fb
// (u, v and the ray's height z, each linear in s in [0, 1]), the gap g(s) = patch(u, v) - z
// is a quartic in s. Its Bernstein coefficients come from the net: restricting each axis
// to the path's range (mr_quadraticRestriction) gives a biquadratic net over [0, 1]^2 whose
// diagonal is the path, and the diagonal of a tensor-product quadratic is the quartic with
// coefficients N00, (N10 + N01) / 2, (N20 + 4 N11 + N02) / 6, (N21 + N12) / 2, N22. The
// quartic lies within the convex hull of its coefficients over any piece, which bounds it
// along the path itself (not over a rectangle of the patch, nor against the ray's lowest
// point): a piece whose coefficients are all below zero holds no hit.

// A quartic's five coefficients: (c0, c1, c2, c3) and c4.
struct mr_Quartic {
    vec4 c;
    float c4;
};

// The coefficients of g over [0, 1].
mr_Quartic mr_biquadraticPathGap(mat3 net, vec3 fa, vec3 fb) {
    mat3 su = mr_quadraticRestriction(fa.x, fb.x), sv = mr_quadraticRestriction(fa.y, fb.y);
    // n[k][l]: restricted along u (columns k) and v (rows l).
    mat3 n;
    for (int k = 0; k < 3; ++k) {
        vec3 column = net[0] * su[k][0] + net[1] * su[k][1] + net[2] * su[k][2];
        n[k] = vec3(dot(sv[0], column), dot(sv[1], column), dot(sv[2], column));
    }
    vec4 z = fa.z + vec4(0.0, 0.25, 0.5, 0.75) * (fb.z - fa.z);
    vec4 diagonal = vec4(n[0][0], 0.5 * (n[1][0] + n[0][1]), (n[2][0] + 4.0 * n[1][1] + n[0][2]) / 6.0,
                         0.5 * (n[2][1] + n[1][2]));
    return mr_Quartic(diagonal - z, n[2][2] - fb.z);
}

// The coefficients over [sa, sb] of the quartic whose coefficients over [0, 1] are q: de
// Casteljau at sa keeps the right part, then at the piece's end within it the left part.
mr_Quartic mr_quarticPiece(mr_Quartic q, float sa, float sb) {
    // Right of sa: the last point of each level.
    vec4 l1 = mix(q.c, vec4(q.c.yzw, q.c4), sa);  // 4 points of level 1
    vec3 l2 = mix(l1.xyz, l1.yzw, sa);
    vec2 l3 = mix(l2.xy, l2.yz, sa);
    float l4 = mix(l3.x, l3.y, sa);
    vec4 r = vec4(l4, l3.y, l2.z, l1.w);
    float r4 = q.c4;
    // Left of tau within it: the first point of each level.
    float tau = sa < 1.0 ? (sb - sa) / (1.0 - sa) : 1.0;
    vec4 m1 = mix(r, vec4(r.yzw, r4), tau);
    vec3 m2 = mix(m1.xyz, m1.yzw, tau);
    vec2 m3 = mix(m2.xy, m2.yz, tau);
    float m4 = mix(m3.x, m3.y, tau);
    return mr_Quartic(vec4(r.x, m1.x, m2.x, m3.x), m4);
}

// The quartic at s in [0, 1]: de Casteljau.
float mr_quarticValue(mr_Quartic q, float s) {
    vec4 l1 = mix(q.c, vec4(q.c.yzw, q.c4), s);
    vec3 l2 = mix(l1.xyz, l1.yzw, s);
    vec2 l3 = mix(l2.xy, l2.yz, s);
    return mix(l3.x, l3.y, s);
}

// The one root of a quartic that rises from q(0) < 0 to q(1) >= 0 with coefficients that
// never fall (so it is monotone): regula falsi with the Illinois rule, the bracket [lo, hi]
// (q(lo) < 0 <= q(hi)) shrinking superlinearly, until it is 2^-18 of the piece wide.
float mr_quarticRisingRoot(mr_Quartic q) {
    float lo = 0.0, hi = 1.0, qlo = q.c.x, qhi = q.c4;
    int side = 0;
    for (int k = 0; k < 16 && hi - lo > 1.0 / 262144.0; ++k) {
        float s = clamp((lo * qhi - hi * qlo) / (qhi - qlo), lo, hi);
        float qs = mr_quarticValue(q, s);
        if (qs >= 0.0) {
            hi = s;
            qhi = qs;
            if (side < 0) qlo *= 0.5;
            side = -1;
        } else {
            lo = s;
            qlo = qs;
            if (side > 0) qhi *= 0.5;
            side = 1;
        }
    }
    return hi;
}

// Pieces 2^-12 of the stretch at the finest (a tenth of the final footprint on the
// longest stretch a square holds).
const int MR_QUARTIC_DEPTH = 12;

// The first s in [0, 1] where g(s) >= 0 (the ray on or under the patch), or -1: the binary
// tree of pieces in order, each skipped when all its coefficients are below -margin (the
// float rounding of the net and of the restriction), down to pieces `finalWidth` wide,
// solved by the parabola through their ends and middle (leaf_walk.glsl: mr_cellStretchHit).
float mr_quarticFirstHit(mr_Quartic g, float finalWidth, float margin) {
    int depth = 0;
    uint index = 0u;
    for (int guard = 0; guard < (2 << MR_QUARTIC_DEPTH); ++guard) {
        float scale = exp2(-float(depth));
        float sa = float(index) * scale, sb = float(index + 1u) * scale;
        // Not `depth == 0 ? g : ...`: GLSL ES (WebGL) allows no ?: on structures.
        mr_Quartic c = g;
        if (depth != 0) c = mr_quarticPiece(g, sa, sb);
        float top = max(max(max(c.c.x, c.c.y), max(c.c.z, c.c.w)), c.c4);
        if (top >= -margin) {
            if (c.c.x >= 0.0) return sa;
            // Rising all the way to a point in the solid: one root, found directly.
            vec4 rise = vec4(c.c.yzw, c.c4) - c.c;
            if (c.c4 >= 0.0 && all(greaterThanEqual(rise, vec4(0.0))))
                return sa + (sb - sa) * mr_quarticRisingRoot(c);
            if (sb - sa > finalWidth && depth < MR_QUARTIC_DEPTH) {
                depth += 1;
                index *= 2u;
                continue;
            }
            // The final piece: the parabola through s = 0, 1/2, 1 of it.
            float middle = (dot(c.c, vec4(1.0, 4.0, 6.0, 4.0)) + c.c4) / 16.0;
            float s = mr_parabolaFirstRoot(c.c.x, middle, c.c4);
            if (s >= 0.0) return sa + s * (sb - sa);
        }
        // On to the next piece in order, as high up as it is unvisited.
        index += 1u;
        while (depth > 0 && (index & 1u) == 0u) {
            index >>= 1;
            depth -= 1;
        }
        if (depth == 0) return -1.0;
    }
    return -1.0;
}

#endif
