// base_mesh.glsl: the mesh base's traversal in one triangle's prism (docs/bases.md, "The mesh",
// "The mesh's traversal"; issue 50), the GLSL of core/trace/MeshTracer.cpp, function for
// function: mr_meshPath (MeshTracer::path), mr_meshPointOn (pointOn), the cuts and pieces
// (pieces), mr_meshFootprintBound (footprintBound), mr_meshWalkPiece (walkSegments, in
// core/trace/SegmentWalk.h, over MeshTracer::PiecePath), mr_meshLeaf (leaf),
// mr_meshSolvePiece and mr_meshTraceTriangle (traceTriangle); and mr_meshNormal, the exact
// surface's normal at the hit (MeshReference's MeshHit::normal). One fragment of a prism's hull
// (shaders/mesh_relief.frag) traces its ray in that prism; the depth test keeps the least
// over prisms, which is MeshTracer::trace's least.
//
// The prism of triangle k: X(b, t) = B(b) + s t D(b), b in the triangle, 0 <= t <= H (H the
// pyramid's top). The ray's preimage is parametrised by the height t: lambda = num / c,
// b_1 = n1 / c, b_2 = n2 / c (c quadratic, num cubic, n quadratic). [0, H] is cut at the
// roots of c, of b's numerators and of the turning numerators of lambda, b, u and v, so that
// on each piece lambda, t, b, u and v are monotone and b lies on one side of each wall.
//
// What is reused and what is not:
//  * segment_walk.glsl's naming and stepping of segments (mr_SegmentWalk, mr_walkDescend,
//    mr_walkNext) and max_pyramid.glsl's window read (mr_windowOver) are used as they are:
//    the walk over a piece's parameter p in [0, 1] visits segments by the same rules as the
//    plane's walk over its ray.
//  * mr_walkFootprint and mr_baseFootprintOf are not: they place a segment on a straight
//    line start + t dir and map its ends through one base (mr_baseEnd: one frame for the
//    whole map), where a piece's points come from per-triangle polynomials in t (a rational
//    curve in map space), and the piece's footprint must be read through the map repeated
//    in u and v (both axes wrap; the library's MICRORELIEF_BASE_WRAPS_U wraps u alone). The
//    few lines that place a segment are here, in the piece's terms.
//  * the last level is relief_patch.glsl's, as the host chooses it (MICRORELIEF_INTERPOLATION):
//    its patch type and mr_patchValue, mr_patchTop and mr_patchSlope (bilinear_patch.glsl's
//    corners, biquadratic_patch.glsl's Bezier net, mr_biquadraticNetOf) in the leaf, as
//    MeshTracer's leaf takes SurfacePatch; the patch's samples are read here with both
//    indices wrapped (the library's reads clamp v): mr_meshPatch.
//
// Float: the parameter is t, so a ray at a grazing angle g to the mesh resolves a texel of
// size e only while g e is well above H 2^-24 (docs/bases.md).
#ifndef MICRORELIEF_BASE_MESH_GLSL
#define MICRORELIEF_BASE_MESH_GLSL

#include "bilinear_patch.glsl"
#include "biquadratic_patch.glsl"
#include "final_piece.glsl"
#include "max_pyramid.glsl"
#include "relief_map.glsl"
#include "relief_patch.glsl"
#include "segment_walk.glsl"

// The triangle table: per mesh triangle 8 RGBA32F texels, triangle k's at texel
// ((k % MR_MESH_TABLE_ROW) * 8 + j, k / MR_MESH_TABLE_ROW):
// j = 0..2: P_i, T_i.x; j = 3..5: N_i, T_i.y; j = 6: H_tri, the smooth edges (core/trace/
// MeshTracer.h's smoothEdges: bit i where the wall b_i = 0 is no surface, as a float), 0, 0;
// j = 7 unused.
const int MR_MESH_TABLE_ROW = 256;

struct mr_MeshTriangle {
    vec3 p0, e1, e2;  // P0, P1 - P0, P2 - P0
    vec3 n0, f1, f2;  // N0, N1 - N0, N2 - N0
    vec2 uv0, uv1, uv2;
    int smoothEdges;  // bit i: the wall b_i = 0 is on a smooth edge, no surface
};

mr_MeshTriangle mr_meshTriangle(sampler2D table, int k) {
    ivec2 at = ivec2((k % MR_MESH_TABLE_ROW) * 8, k / MR_MESH_TABLE_ROW);
    vec4 a0 = texelFetch(table, at, 0), a1 = texelFetch(table, at + ivec2(1, 0), 0);
    vec4 a2 = texelFetch(table, at + ivec2(2, 0), 0), m0 = texelFetch(table, at + ivec2(3, 0), 0);
    vec4 m1 = texelFetch(table, at + ivec2(4, 0), 0), m2 = texelFetch(table, at + ivec2(5, 0), 0);
    int smoothEdges = int(texelFetch(table, at + ivec2(6, 0), 0).y);
    return mr_MeshTriangle(a0.xyz, a1.xyz - a0.xyz, a2.xyz - a0.xyz, m0.xyz, m1.xyz - m0.xyz,
                           m2.xyz - m0.xyz, vec2(a0.w, m0.w), vec2(a1.w, m1.w), vec2(a2.w, m2.w), smoothEdges);
}

// ---- Polynomials in t of degree <= 4: float[5], coefficients of t^0 .. t^4 ----

float mr_polyValue(float p[5], float t) {
    return (((p[4] * t + p[3]) * t + p[2]) * t + p[1]) * t + p[0];
}

float[5] mr_polyDerivative(float p[5]) {
    return float[5](p[1], 2.0 * p[2], 3.0 * p[3], 4.0 * p[4], 0.0);
}

// a + sb b.
float[5] mr_polyPlus(float a[5], float b[5], float sb) {
    return float[5](a[0] + sb * b[0], a[1] + sb * b[1], a[2] + sb * b[2], a[3] + sb * b[3], a[4] + sb * b[4]);
}

float[5] mr_polyScaled(float a[5], float s) {
    return float[5](s * a[0], s * a[1], s * a[2], s * a[3], s * a[4]);
}

// The product truncated to degree 4 (every product taken here has degree <= 4).
float[5] mr_polyTimes(float a[5], float b[5]) {
    float r[5] = float[5](0.0, 0.0, 0.0, 0.0, 0.0);
    for (int i = 0; i < 5; ++i)
        for (int j = 0; i + j < 5; ++j) r[i + j] += a[i] * b[j];
    return r;
}

// The numerator of (n / c)': n' c - n c'.
float[5] mr_turnNumerator(float n[5], float c[5]) {
    return mr_polyPlus(mr_polyTimes(mr_polyDerivative(n), c), mr_polyTimes(n, mr_polyDerivative(c)), -1.0);
}

// Where p changes sign in [a, b] (p(a) has the sign of fa), to adjacent floats: the end on
// p(b)'s side. 160 halvings reach adjacent floats from any interval of [0, H].
float mr_polyBisect(float p[5], float a, float b, float fa) {
    for (int k = 0; k < 160; ++k) {
        float m = 0.5 * (a + b);
        if (m == a || m == b) break;
        float fm = mr_polyValue(p, m);
        if (fm != 0.0 && (fm < 0.0) == (fa < 0.0)) a = m;
        else b = m;
    }
    return b;
}

// Whether p, evaluated in float by mr_polyValue, has one strict sign at every t in [0, h]:
// its Bernstein coefficients over [0, h] all of one sign by more than 2^-12 of
// M = sum |p_i| h^i (p's own units; M bounds |p| over [0, h]). Why that is enough:
// p(t) = sum_j beta_j B_j(t / h) with B_j >= 0 and sum_j B_j = 1 on [0, h] (the convex hull
// property), so |p(t)| >= min_j |beta_j| there; the beta_j below are sums of at most five
// terms each at most |p_i| h^i, computed within about 10 ulps of M (2^-24 M an ulp), and
// Horner's evaluation of a degree-4 p at 0 <= t <= h errs by at most 8 ulps of M (fused or
// not). 2^-12 M is 4096 ulps of M: float's evaluation of p keeps the exact sign with room
// to spare, even for arithmetic a few ulps worse than IEEE. A non-finite M (overflow, NaN)
// fails the test.
bool mr_polyKeepsSign(float p[5], float h) {
    float a1 = p[1] * h, a2 = p[2] * h * h, a3 = p[3] * h * h * h, a4 = p[4] * h * h * h * h;
    float size = abs(p[0]) + abs(a1) + abs(a2) + abs(a3) + abs(a4);
    // Bernstein coefficients of degree 4 over [0, h]: beta_j = sum_i C(j, i) / C(4, i) p_i h^i.
    float b1 = p[0] + 0.25 * a1, b2 = p[0] + 0.5 * a1 + (1.0 / 6.0) * a2;
    float b3 = p[0] + 0.75 * a1 + 0.5 * a2 + 0.25 * a3, b4 = p[0] + a1 + a2 + a3 + a4;
    float least = min(min(min(p[0], b1), min(b2, b3)), b4);
    float most = max(max(max(p[0], b1), max(b2, b3)), b4);
    float margin = size * (1.0 / 4096.0);
    return least > margin || most < -margin;
}

// The real roots of p in (lo, hi), ascending, at most 4 (MeshTracer's rootsIn): those of
// each derivative isolate the next one's, from the linear one up to p. Two shortcuts give
// exactly what the full search gives (the same roots, to the bit):
//  * p keeps one sign over [0, hi] in float (mr_polyKeepsSign, lo = 0): the last level's
//    scan sees that sign at every point it evaluates (all in [lo, hi]), so it finds no sign
//    change and no zero: no roots;
//  * the levels k >= deg p: p's k-th derivative is a non-zero constant or zero (its
//    coefficients exactly k! p_k or 0: products of p's floats by small integers), where the
//    scan over [lo, hi] alone (no roots below to split it) finds nothing: they are skipped.
int mr_polyRoots(float p[5], float lo, float hi, out float roots[4]) {
    int count = 0;
    roots = float[4](0.0, 0.0, 0.0, 0.0);
    if (lo == 0.0 && mr_polyKeepsSign(p, hi)) return 0;
    int degree = 0;
    for (int i = 1; i < 5; ++i)
        if (p[i] != 0.0) degree = i;
    for (int k = 3; k >= 0; --k) {
        if (k >= degree) continue;
        float dk[5] = p;  // p's k-th derivative (no arrays of arrays in GLSL 3.30 / ES 3.00)
        for (int i = 0; i < 3; ++i)
            if (i < k) dk = mr_polyDerivative(dk);
        float points[6];
        int n = 0;
        points[n++] = lo;
        for (int r = 0; r < 4; ++r)
            if (r < count) points[n++] = roots[r];
        points[n++] = hi;
        int next = 0;
        float found[4] = float[4](0.0, 0.0, 0.0, 0.0);
        for (int r = 0; r + 1 < n; ++r) {
            float a = points[r], b = points[r + 1];
            float fa = mr_polyValue(dk, a), fb = mr_polyValue(dk, b);
            if (fa == 0.0 && r > 0) {
                if (next < 4) found[next++] = a;
            } else if ((fa < 0.0 && fb > 0.0) || (fa > 0.0 && fb < 0.0)) {
                if (next < 4) found[next++] = mr_polyBisect(dk, a, b, fa);
            }
        }
        count = next;
        roots = found;
    }
    return count;
}

// ---- One ray in one prism ----

// lambda = num / c, b_1 = n1 / c, b_2 = n2 / c (MeshTracer::path; the algebra in
// MeshReference.h): A_k(t) = E_k + s t F_k, W(t) = (O - P0) - s t N0, m = A1 x A2.
struct mr_MeshPath {
    float c[5], num[5], n1[5], n2[5];
    vec2 uv0, uv1, uv2;
    bool level;
};

// Coefficients of a x b with a = a0 + t a1, b = b0 + t b1: t^0, t^1, t^2.
void mr_crossLinear(vec3 a0, vec3 a1, vec3 b0, vec3 b1, out vec3 m0, out vec3 m1, out vec3 m2) {
    m0 = cross(a0, b0);
    m1 = cross(a0, b1) + cross(a1, b0);
    m2 = cross(a1, b1);
}

mr_MeshPath mr_meshPath(mr_MeshTriangle tri, vec3 origin, vec3 v, float s, float top) {
    mr_MeshPath path;
    vec3 w0 = origin - tri.p0, w1 = -s * tri.n0;
    vec3 m0, m1, m2;
    mr_crossLinear(tri.e1, s * tri.f1, tri.e2, s * tri.f2, m0, m1, m2);
    path.c = float[5](dot(v, m0), dot(v, m1), dot(v, m2), 0.0, 0.0);
    path.num = float[5](-dot(w0, m0), -(dot(w0, m1) + dot(w1, m0)), -(dot(w0, m2) + dot(w1, m1)), -dot(w1, m2), 0.0);
    vec3 q0, q1, q2;
    mr_crossLinear(w0, w1, tri.e2, s * tri.f2, q0, q1, q2);
    path.n1 = float[5](dot(v, q0), dot(v, q1), dot(v, q2), 0.0, 0.0);
    mr_crossLinear(tri.e1, s * tri.f1, w0, w1, q0, q1, q2);
    path.n2 = float[5](dot(v, q0), dot(v, q1), dot(v, q2), 0.0, 0.0);
    path.uv0 = tri.uv0;
    path.uv1 = tri.uv1;
    path.uv2 = tri.uv2;
    // Parallel to every offset plane, to float's resolution: |c| below 2^-20 of |V| |m|.
    float cSize = abs(path.c[0]) + abs(path.c[1]) * top + abs(path.c[2]) * top * top;
    float mSize = length(m0) + length(m1) * top + length(m2) * top * top;
    path.level = cSize <= 1e-6 * length(v) * mSize;
    return path;
}

// Which surface of the solid a hit is on (core/trace/MeshReference.h, MeshSurface): the top
// t = h(uv), the mesh itself t = 0, the side wall b_i = 0 (i = kind - MR_MESH_WALL0), a fold
// (where lambda(t) turns: the envelope of the offset triangles), or the eye inside the solid.
// A piece's entry is the kind of its lower-lambda end: the cut it starts at (t = 0 the mesh,
// t = H the top, a root of b_i's numerator that wall, of lambda's turning numerator or of c a
// fold, a turn of b, u or v the top: the ray was inside before it only where the piece before
// ends on the surface there) or the eye where lambda was clipped to 0.
const int MR_MESH_NONE = 0;
const int MR_MESH_TOP = 1;
const int MR_MESH_BASE = 2;
const int MR_MESH_WALL0 = 3;  // 3, 4, 5: b_0, b_1, b_2 = 0
const int MR_MESH_FOLD = 6;
const int MR_MESH_INSIDE = 7;

// A prism's first hit: the ray parameter, the contract's height t, the barycentrics b and
// texture coordinate uv (not wrapped) of its preimage, and the surface it is on.
struct mr_MeshHit {
    float lambda, t;
    vec3 b;
    vec2 uv;
    int surface;
};

// A stretch of [0, H] on which lambda, t, b, u and v are monotone and b lies in the triangle;
// p in [0, 1] runs from its lower-lambda end A to B, t linear in p; on a level piece t is
// fixed at tA, lambda linear in p and b = b0 + lambda b1.
struct mr_MeshPiece {
    float tA, tB, lambdaA, lambdaB;
    bool level;
    vec3 b0, b1;
    int entry;  // what the ray crosses into the prism through at A (MR_MESH_*)
};

struct mr_MeshPoint {
    float lambda, t;
    vec3 b;
    vec2 uv;
};

mr_MeshPoint mr_meshPointOn(mr_MeshPath path, mr_MeshPiece piece, float p) {
    mr_MeshPoint m;
    if (piece.level) {
        m.t = piece.tA;
        m.lambda = p >= 1.0 ? piece.lambdaB : piece.lambdaA + p * (piece.lambdaB - piece.lambdaA);
        m.b = piece.b0 + m.lambda * piece.b1;
        m.uv = m.b.x * path.uv0 + m.b.y * path.uv1 + m.b.z * path.uv2;
        return m;
    }
    m.t = p >= 1.0 ? piece.tB : piece.tA + p * (piece.tB - piece.tA);
    float c = mr_polyValue(path.c, m.t);
    m.lambda = mr_polyValue(path.num, m.t) / c;
    m.b.y = mr_polyValue(path.n1, m.t) / c;
    m.b.z = mr_polyValue(path.n2, m.t) / c;
    m.b.x = 1.0 - m.b.y - m.b.z;
    m.uv = m.b.x * path.uv0 + m.b.y * path.uv1 + m.b.z * path.uv2;
    return m;
}

// ---- The map repeated in u and v ----

// The pyramid's bound over the texel rectangle [lo, hi] (X = u W, Y = v H, any values: the map
// repeats), never below the repeated surface there (MeshTracer::footprintBound): per axis the
// finest texels floor(lo)..floor(hi) taken into one period, split in two where they cross the
// period's edge, the whole axis where they span a period; one window (mr_windowOver) over
// each of the at most four rectangles. The finest texels bound their squares with the
// wrapped neighbours (the pyramid of the map tiled 3 x 3, MaxPyramid's tiled addressing), so
// each window bounds the repeated surface over its rectangle's texel squares.
float mr_meshFootprintBound(mr_Relief relief, MICRORELIEF_SAMPLER windows, vec2 lo, vec2 hi) {
    ivec2 size = ivec2(relief.map.size);
    ivec2 first[2], last[2];  // [range] per axis in .x (u) and .y (v)
    ivec2 counts = ivec2(1);
    for (int axis = 0; axis < 2; ++axis) {
        float a = floor(lo[axis]), b = floor(hi[axis]);
        int n = size[axis];
        if (!(b - a < float(n - 1))) {
            first[0][axis] = 0;
            last[0][axis] = n - 1;
            continue;
        }
        // In integers (mr_wrapIndex): a float quotient a / n may be 2.5 ulp off in GLSL.
        int f = mr_wrapIndex(int(a), n);
        int l = f + int(b - a);
        if (l < n) {
            first[0][axis] = f;
            last[0][axis] = l;
        } else {
            first[0][axis] = f;
            last[0][axis] = n - 1;
            first[1][axis] = 0;
            last[1][axis] = l - n;
            counts[axis] = 2;
        }
    }
    float bound = 0.0;
    for (int x = 0; x < 2; ++x) {
        for (int y = 0; y < 2; ++y) {
            if (x >= counts.x || y >= counts.y) continue;
            int level;
            ivec2 a = ivec2(first[x].x, first[y].y), b = ivec2(last[x].x, last[y].y);
            bound = max(bound, mr_windowOver(relief, windows, a, b, level));
        }
    }
    return bound;
}

// The corners of bilinear cell (i, j) of the repeated map (samples i..i+1 by j..j+1, both
// indices wrapped), in mr_patchHeight's order.
vec4 mr_meshCellCorners(mr_Relief relief, MICRORELIEF_SAMPLER heights, ivec2 cell) {
    ivec2 n = ivec2(relief.map.size);
    // In integers (map_addressing.glsl's mr_wrapIndex): GLSL's division may be 2.5 ulp off.
    ivec2 a = ivec2(mr_wrapIndex(cell.x, n.x), mr_wrapIndex(cell.y, n.y));
    ivec2 b = ivec2(a.x + 1 == n.x ? 0 : a.x + 1, a.y + 1 == n.y ? 0 : a.y + 1);
    MICRORELIEF_FETCHED(1);
    return vec4(texelFetch(heights, a, 0).r, texelFetch(heights, ivec2(b.x, a.y), 0).r,
                texelFetch(heights, ivec2(a.x, b.y), 0).r, texelFetch(heights, b, 0).r);
}

// The patch of cell `cell` of the repeated map at the last level the host chose
// (MICRORELIEF_INTERPOLATION, relief_patch.glsl): the bilinear cell's corners, or the
// biquadratic texel square's Bezier net from its 3 x 3 samples, both indices wrapped
// (biquadratic_patch.glsl's mr_biquadraticNetOf: the library's net; its own reads clamp v).
mr_ReliefPatch mr_meshPatch(mr_Relief relief, MICRORELIEF_SAMPLER heights, ivec2 cell) {
#if MICRORELIEF_INTERPOLATION == MR_INTERPOLATION_BIQUADRATIC
    ivec2 n = ivec2(relief.map.size);
    mat3 c;
    for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) {
            ivec2 p = cell + ivec2(a - 1, b - 1);
            c[a][b] = texelFetch(heights, ivec2(mr_wrapIndex(p.x, n.x), mr_wrapIndex(p.y, n.y)), 0).r;
        }
    }
    MICRORELIEF_FETCHED(4);  // as MeshTracer counts a net: four gathers' worth
    return mr_biquadraticNetOf(c);
#else
    return mr_meshCellCorners(relief, heights, cell);
#endif
}

// The cell of the repeated map holding uv and uv's local coordinates in it.
ivec2 mr_meshCellOf(mr_Relief relief, vec2 uv, out vec2 local) {
    vec2 x = uv * relief.map.size - MR_PATCH_OFFSET;
    vec2 cell = floor(x);
    local = clamp(x - cell, 0.0, 1.0);
    return ivec2(cell);
}

float mr_meshSurfaceAt(mr_Relief relief, MICRORELIEF_SAMPLER heights, vec2 uv) {
    vec2 f;
    ivec2 cell = mr_meshCellOf(relief, uv, f);
    return mr_patchValue(mr_meshPatch(relief, heights, cell), f);
}

// The gradient of the surface h over (u, v) (map height units per unit of u and of v) at uv.
vec2 mr_meshSurfaceGradient(mr_Relief relief, MICRORELIEF_SAMPLER heights, vec2 uv) {
    vec2 f;
    ivec2 cell = mr_meshCellOf(relief, uv, f);
    return mr_patchSlope(mr_meshPatch(relief, heights, cell), f) * relief.map.size;
}

// Cell coordinates (X - offset, Y - offset, t) of a piece's point (offset: where cell 0
// starts, MR_PATCH_OFFSET).
vec3 mr_meshCellPoint(mr_Relief relief, mr_MeshPath path, mr_MeshPiece piece, float p) {
    mr_MeshPoint m = mr_meshPointOn(path, piece, p);
    return vec3(m.uv * relief.map.size - MR_PATCH_OFFSET, m.t);
}

// ---- The leaf: MeshTracer::leaf ----

// The first p in [p0, p1] where the piece's path is on or under the surface, or -1: the cells
// it crosses in order (u and v monotone on the piece, so the cells' sequence is a staircase:
// each cell's exit is where u or v first passes the cell's boundary ahead, found by
// bisection on that monotone coordinate), each stretch subdivided near half first, a part
// dropped when its lowest t (an end's: t linear in p) is above the bilinear patch's max over
// its ends' box (exact: the patch peaks at a corner of any rectangle, and u, v monotone keep
// the part's path in the box of its ends), final parts solved by the parabola.
float mr_meshLeaf(mr_Relief relief, MICRORELIEF_SAMPLER heights, mr_MeshPath path, mr_MeshPiece piece,
                  float p0, float p1, float top) {
    vec3 start = mr_meshCellPoint(relief, path, piece, p0), end = mr_meshCellPoint(relief, path, piece, p1);
    ivec2 at = ivec2(floor(start.xy)), last = ivec2(floor(end.xy));
    ivec2 stepDir = ivec2(last.x > at.x ? 1 : -1, last.y > at.y ? 1 : -1);
    int cells = abs(last.x - at.x) + abs(last.y - at.y) + 1;
    float pc = p0;
    for (int k = 0; k < 4096; ++k) {
        if (k >= cells) break;
        float exits[2] = float[2](p1, p1);
        for (int axis = 0; axis < 2; ++axis) {
            if (at[axis] == last[axis]) continue;
            float boundary = float(at[axis] + (stepDir[axis] > 0 ? 1 : 0));
            float a = pc, b = p1;
            for (int i = 0; i < 60; ++i) {
                float m = 0.5 * (a + b);
                if (m <= a || m >= b) break;
                float x = mr_meshCellPoint(relief, path, piece, m)[axis];
                bool past = stepDir[axis] > 0 ? x >= boundary : x <= boundary;
                if (past) b = m;
                else a = m;
            }
            exits[axis] = b;
        }
        float pe = min(exits[0], exits[1]);
        mr_ReliefPatch h = mr_meshPatch(relief, heights, at);
        vec2 cell = vec2(at);
        const int kFinalDepth = 20;
        float finalFootprint = 1.0 / 4096.0, finalDrop = top / 4096.0;
        int depth = 0;
        uint index = 0u;
        for (int guard = 0; guard < 1 << 16; ++guard) {
            float width = (pe - pc) / float(1 << depth);
            float a = pc + float(index) * width;
            float b = index + 1u == (1u << depth) ? pe : a + width;
            vec3 fa = mr_meshCellPoint(relief, path, piece, a) - vec3(cell, 0.0);
            vec3 fb = mr_meshCellPoint(relief, path, piece, b) - vec3(cell, 0.0);
            vec2 lo = min(fa.xy, fb.xy), hi = max(fa.xy, fb.xy);
            // Widened by float's rounding of the path's points (n / c), in texels.
            float widen = 1.0 / 1024.0;
            float peak = mr_patchTop(h, lo - widen, hi + widen);
#if MICRORELIEF_INTERPOLATION == MR_INTERPOLATION_BIQUADRATIC
            // The restricted net's float rounding, a few ulps of the largest height
            // (relief_patch.glsl's margin, as the analytic bases' biquadratic leaves pad it).
            peak += MR_PATCH_TOP_MARGIN * top;
#endif
            bool may = min(fa.z, fb.z) <= peak;
            bool final = depth == kFinalDepth ||
                         (max(hi.x - lo.x, hi.y - lo.y) <= finalFootprint && abs(fb.z - fa.z) <= finalDrop);
            if (may && !final) {
                depth += 1;
                index *= 2u;
                continue;
            }
            if (may) {
                vec3 fm = mr_meshCellPoint(relief, path, piece, 0.5 * (a + b)) - vec3(cell, 0.0);
                float ga = mr_patchValue(h, clamp(fa.xy, 0.0, 1.0)) - fa.z;
                float gm = mr_patchValue(h, clamp(fm.xy, 0.0, 1.0)) - fm.z;
                float gb = mr_patchValue(h, clamp(fb.xy, 0.0, 1.0)) - fb.z;
                float s = mr_parabolaFirstRoot(ga, gm, gb);
                if (s >= 0.0) return a + s * (b - a);
            }
            index += 1u;
            while (depth > 0 && (index & 1u) == 0u) {
                index >>= 1;
                depth -= 1;
            }
            if (depth == 0) break;
        }
        if (pe >= p1) break;
        int axis = exits[0] <= exits[1] ? 0 : 1;
        at[axis] += stepDir[axis];
        pc = pe;
    }
    return -1.0;
}

// ---- The walk over a piece: walkSegments over MeshTracer::PiecePath ----

// The binary subdivision of p in [0, 1], near half first, one window read per segment
// unless the parent's bound clears it, with the piece's answers to what the plane's
// mr_baseFootprintOf gives:
//  * lowest: the lesser of t at the segment's ends. Exact: t is linear in p, so its least
//    over [pa, pb] is at an end;
//  * footprint: the box of the ends' uv, in texels, widened by float's rounding of the
//    points. A bound: u and v are monotone on the piece, so every point of the segment's
//    path lies between its ends';
//  * the leaf from where t comes down to the bound (t linear in p), never later.
// Returns the hit's p, or -1.
float mr_meshWalkPiece(mr_Relief relief, MICRORELIEF_SAMPLER windows, MICRORELIEF_SAMPLER heights,
                       mr_MeshPath path, mr_MeshPiece piece, float top, int budget) {
    const float kUnit = 1.0 / float(1 << MICRORELIEF_MAX_DEPTH);
    mr_SegmentWalk walk = mr_segmentWalk();
    for (int iteration = 0; iteration < budget; ++iteration) {
        int shift = MICRORELIEF_MAX_DEPTH - walk.depth;
        float pa = float(walk.index << shift) * kUnit, pb = float((walk.index + 1u) << shift) * kUnit;
        mr_MeshPoint ma = mr_meshPointOn(path, piece, pa), mb = mr_meshPointOn(path, piece, pb);
        vec2 xa = ma.uv * relief.map.size, xb = mb.uv * relief.map.size;
        // Float's rounding of n / c and of the uv sums: a few ulps of the coordinate, and of
        // the path's own rounding near its ends; 2^-10 texel plus 2^-18 of the coordinate.
        vec2 lo = min(xa, xb), hi = max(xa, xb);
        lo -= 1.0 / 1024.0 + abs(lo) * (1.0 / 262144.0);
        hi += 1.0 / 1024.0 + abs(hi) * (1.0 / 262144.0);
        float lowest = min(ma.t, mb.t), drop = abs(mb.t - ma.t);
        bool mayHit = false;
        float bound = walk.parentBound;
        if (lowest <= walk.parentBound) {
            bound = min(bound, mr_meshFootprintBound(relief, windows, lo, hi));
            mayHit = lowest <= bound;
        }
        if (mayHit) {
            bool leaf = max(hi.x - lo.x, hi.y - lo.y) <= float(MICRORELIEF_LEAF_TEXELS) ||
                        walk.depth >= MICRORELIEF_MAX_DEPTH;
            if (leaf) {
                float from = pa;
                if (ma.t > bound && mb.t < ma.t)
                    from = clamp(pa + (pb - pa) * (ma.t - bound) / (ma.t - mb.t), pa, pb);
                from = max(pa, from - (1.0 / 65536.0) * (pb - pa));
                float hit = mr_meshLeaf(relief, heights, path, piece, from, pb, top);
                if (hit >= 0.0) return hit;
            } else {
                float tm = mr_meshPointOn(path, piece, 0.5 * (pa + pb)).t;
                mr_walkDescend(walk, bound, min(ma.t, tm) > bound);
                continue;
            }
        }
        // After a far half, climb to the parent when the segment cleared its bound by more
        // than twice its drop (the next one, as long, cannot reach it).
        if (!mr_walkNext(walk, lowest - bound > 2.0 * drop)) return -1.0;
    }
    return -1.0;
}

// ---- The pieces and the trace: MeshTracer::pieces and traceTriangle ----

// Whether lambda grows from ta to tb on a piece (la, lb its ends' lambda, tm its middle,
// turnL = num' c - num c', lambda' = turnL / c^2; MeshTracer's forward). By la <= lb unless the
// two are equal to float's rounding (2^-16 of their size: a shell thinner than float resolves
// against the eye's distance, s H below about 2^-16 |lambda V|, where every t of a piece gives
// one lambda in float): then by the sign of lambda' in the middle of the piece, where it is
// clear of its rounding. turnL keeps one sign on the piece (cut at its roots), and at tm it is
// num'(tm) c(tm) - num(tm) c'(tm): each factor's t-terms come from s-scaled vectors, not as
// differences of large ones, so in a thin shell they keep their relative precision where
// num / c does not; clear: beyond 2^-12 of |num' c| + |num c'| (each factor a few ulps off).
// Only which end is the piece's entry depends on it, never a hit's lambda.
bool mr_meshForward(mr_MeshPath path, float la, float lb, float tm) {
    if (abs(lb - la) > (abs(la) + abs(lb)) * (1.0 / 65536.0)) return la <= lb;
    float a = mr_polyValue(mr_polyDerivative(path.num), tm) * mr_polyValue(path.c, tm);
    float b = mr_polyValue(path.num, tm) * mr_polyValue(mr_polyDerivative(path.c), tm);
    return abs(a - b) > (abs(a) + abs(b)) * (1.0 / 4096.0) ? a > b : la <= lb;
}

// One piece's first hit, kept in `best` when it is before the best so far (MeshTracer::
// traceTriangle's loop body): at the piece's start when that is on or under the surface (the
// ray entered through it: piece.entry), else where the walk finds the path coming down to the
// top.
//
// A wall on a smooth edge (tri.smoothEdges: the neighbour's prism continues this one there) is
// no surface where the two prisms lie on its two sides. A piece that starts on it within
// rounding of the top or of the mesh (2^-12 H: float's error in the cut's t and in h at its
// uv is far below) starts where the neighbour's top or mesh reaches the edge, the neighbour's
// own hit a rounding later or level (which the depth test may lose to this one): named as
// MeshReference names a hit, by the nearest surface (distances in the mesh's units:
// s |D| (h - t) to the top, s |D| t to the mesh, |b_j| times the altitude over edge j to a
// wall that is a surface; the top and the mesh tied, h = 0, the mesh for a ray going up
// along D). Further from both it keeps the wall's name: there the ray came into the union
// earlier, through another prism, whose hit the depth test keeps, unless the prisms fold so
// that both lie on one side of the wall, where the wall is the surface. Not dropped (the
// fragment cannot tell the two apart), and no hit is moved, only named.
void mr_meshSolvePiece(mr_Relief relief, MICRORELIEF_SAMPLER windows, MICRORELIEF_SAMPLER heights,
                       mr_MeshTriangle tri, vec3 v, float s, mr_MeshPath path, mr_MeshPiece piece,
                       float top, int budget, inout mr_MeshHit best) {
    mr_MeshPoint m0 = mr_meshPointOn(path, piece, 0.0);
    float h0 = mr_meshSurfaceAt(relief, heights, m0.uv);
    bool entered = h0 >= m0.t;
    int surface = entered ? piece.entry : MR_MESH_TOP;
    float band = top * (1.0 / 4096.0);
    if (entered && surface >= MR_MESH_WALL0 && surface <= MR_MESH_WALL0 + 2 &&
        ((tri.smoothEdges >> (surface - MR_MESH_WALL0)) & 1) != 0 && (h0 - m0.t <= band || m0.t <= band)) {
        vec3 along = tri.n0 + m0.b.y * tri.f1 + m0.b.z * tri.f2;
        float unit = s * length(along), toTop = (h0 - m0.t) * unit, toBase = abs(m0.t) * unit;
        bool base = toBase < toTop || (toBase == toTop && dot(v, along) > 0.0);
        surface = base ? MR_MESH_BASE : MR_MESH_TOP;
        float closest = base ? toBase : toTop;
        float twiceArea = length(cross(tri.e1, tri.e2));
        vec3 edges = vec3(length(tri.e2 - tri.e1), length(tri.e2), length(tri.e1));  // opposite P_j
        for (int j = 0; j < 3; ++j) {
            if (((tri.smoothEdges >> j) & 1) != 0) continue;
            float distance = abs(m0.b[j]) * twiceArea / edges[j];
            if (distance < closest) {
                closest = distance;
                surface = MR_MESH_WALL0 + j;
            }
        }
    }
    float p = entered ? 0.0 : mr_meshWalkPiece(relief, windows, heights, path, piece, top, budget);
    if (p < 0.0) return;
    mr_MeshPoint m = mr_meshPointOn(path, piece, p);
    if (best.surface != MR_MESH_NONE && m.lambda >= best.lambda) return;
    best = mr_MeshHit(max(m.lambda, 0.0), m.t, m.b, m.uv, surface);
}

// The first hit of the ray origin + lambda v (lambda in [0, lambdaMax]) in the prism of `tri`:
// `hit`, its lambda returned, or -1 (hit.surface MR_MESH_NONE).
float mr_meshTraceTriangle(mr_Relief relief, MICRORELIEF_SAMPLER windows, MICRORELIEF_SAMPLER heights,
                           mr_MeshTriangle tri, vec3 origin, vec3 v, float s, float top, float lambdaMax,
                           int budget, out mr_MeshHit hit) {
    hit = mr_MeshHit(-1.0, 0.0, vec3(0.0), vec2(0.0), MR_MESH_NONE);
    mr_MeshPath path = mr_meshPath(tri, origin, v, s, top);
    if (path.level) {
        // The ray lies in the offset plane of each root t* of num (MeshTracer::pieces): there
        // b is linear in lambda, from the offset triangle's Gram system; the piece is where
        // all three b_i >= 0, lambda in [0, lambdaMax]. t is fixed on it, so its lowest
        // height is t* itself, exact; u and v are linear in lambda, so monotone.
        float roots[4];
        int n = mr_polyRoots(path.num, 0.0, top, roots);
        for (int r = 0; r < 4; ++r) {
            if (r >= n) break;
            float t = roots[r];
            vec3 a1 = tri.e1 + s * t * tri.f1, a2 = tri.e2 + s * t * tri.f2, q = tri.p0 + s * t * tri.n0;
            float g11 = dot(a1, a1), g12 = dot(a1, a2), g22 = dot(a2, a2);
            float det = g11 * g22 - g12 * g12;
            if (!(det > 0.0)) continue;  // a focal height: the offset triangle collapsed
            vec3 w = origin - q;
            vec2 at0 = vec2(g22 * dot(a1, w) - g12 * dot(a2, w), g11 * dot(a2, w) - g12 * dot(a1, w)) / det;
            vec2 slope = vec2(g22 * dot(a1, v) - g12 * dot(a2, v), g11 * dot(a2, v) - g12 * dot(a1, v)) / det;
            mr_MeshPiece piece;
            piece.level = true;
            piece.tA = piece.tB = t;
            piece.b0 = vec3(1.0 - at0.x - at0.y, at0.x, at0.y);
            piece.b1 = vec3(-slope.x - slope.y, slope.x, slope.y);
            // Entered at lambda = 0 (the eye) unless a wall b_i = 0 comes later.
            piece.entry = MR_MESH_INSIDE;
            float lo = 0.0, hi = hit.surface != MR_MESH_NONE ? min(hit.lambda, lambdaMax) : lambdaMax;
            bool empty = false;
            for (int i = 0; i < 3; ++i) {
                float b0 = piece.b0[i], b1 = piece.b1[i];
                if (b1 == 0.0) {
                    empty = empty || b0 < 0.0;
                } else if (b1 > 0.0) {
                    if (-b0 / b1 > lo) {
                        lo = -b0 / b1;
                        piece.entry = MR_MESH_WALL0 + i;
                    }
                } else {
                    hi = min(hi, -b0 / b1);
                }
            }
            if (empty || lo > hi) continue;
            piece.lambdaA = lo;
            piece.lambdaB = hi;
            mr_meshSolvePiece(relief, windows, heights, tri, v, s, path, piece, top, budget, hit);
        }
        return hit.surface != MR_MESH_NONE ? hit.lambda : -1.0;
    }
    float n0[5] = mr_polyPlus(mr_polyPlus(path.c, path.n1, -1.0), path.n2, -1.0);
    vec2 du1 = path.uv1 - path.uv0, du2 = path.uv2 - path.uv0;
    float nu[5] = mr_polyPlus(mr_polyPlus(mr_polyScaled(path.c, path.uv0.x), path.n1, du1.x), path.n2, du2.x);
    float nv[5] = mr_polyPlus(mr_polyPlus(mr_polyScaled(path.c, path.uv0.y), path.n1, du1.y), path.n2, du2.y);
    // The cuts of [0, H]: its ends, the roots of c, of b's numerators and of the turning
    // numerators of lambda, b_0..2, u and v; sorted by insertion as they come, each with the
    // surface a piece starting there enters through (mr_MeshPiece.entry).
    float cuts[42];
    int kinds[42];
    int cutCount = 0;
    cuts[cutCount] = 0.0;
    kinds[cutCount++] = MR_MESH_BASE;
    cuts[cutCount] = top;
    kinds[cutCount++] = MR_MESH_TOP;
    // The six turning numerators computed once, before the loop: chosen inside it by source,
    // each branch's work runs on a SIMD rasteriser (llvmpipe) under a mask for every source,
    // six times ten products where six are needed (measured: 1.5x to 1.8x the fragment's
    // time). The same polynomials, the same cuts.
    float turnL[5] = mr_turnNumerator(path.num, path.c), turn0[5] = mr_turnNumerator(n0, path.c);
    float turn1[5] = mr_turnNumerator(path.n1, path.c), turn2[5] = mr_turnNumerator(path.n2, path.c);
    float turnU[5] = mr_turnNumerator(nu, path.c), turnV[5] = mr_turnNumerator(nv, path.c);
    for (int source = 0; source < 10; ++source) {
        float p[5];
        int kind = MR_MESH_TOP;
        if (source == 0) {
            p = path.c;
            kind = MR_MESH_FOLD;
        } else if (source == 1) {
            p = n0;
            kind = MR_MESH_WALL0;
        } else if (source == 2) {
            p = path.n1;
            kind = MR_MESH_WALL0 + 1;
        } else if (source == 3) {
            p = path.n2;
            kind = MR_MESH_WALL0 + 2;
        } else if (source == 4) {
            p = turnL;
            kind = MR_MESH_FOLD;
        } else if (source == 5) p = turn0;
        else if (source == 6) p = turn1;
        else if (source == 7) p = turn2;
        else if (source == 8) p = turnU;
        else p = turnV;
        float roots[4];
        int n = mr_polyRoots(p, 0.0, top, roots);
        for (int r = 0; r < 4; ++r) {
            if (r >= n) break;
            int at = cutCount++;
            while (at > 0 && cuts[at - 1] > roots[r]) {
                cuts[at] = cuts[at - 1];
                kinds[at] = kinds[at - 1];
                at -= 1;
            }
            cuts[at] = roots[r];
            kinds[at] = kind;
        }
    }
    for (int i = 0; i + 1 < 42; ++i) {
        if (i + 1 >= cutCount) break;
        float ta = cuts[i], tb = cuts[i + 1];
        if (!(tb > ta)) continue;
        float tm = 0.5 * (ta + tb), cm = mr_polyValue(path.c, tm);
        if (cm == 0.0) continue;
        // b's signs are fixed inside the piece (cut at the roots of its numerators and of c).
        if (mr_polyValue(path.n1, tm) / cm < 0.0 || mr_polyValue(path.n2, tm) / cm < 0.0 ||
            mr_polyValue(n0, tm) / cm < 0.0)
            continue;
        // lambda at an end; at a pole the infinity it tends to from inside.
        float la, lb;
        {
            float c = mr_polyValue(path.c, ta), num = mr_polyValue(path.num, ta);
            la = (c == 0.0 || (c > 0.0) != (cm > 0.0)) ? (num * cm >= 0.0 ? MR_NEVER : -MR_NEVER) : num / c;
            c = mr_polyValue(path.c, tb);
            num = mr_polyValue(path.num, tb);
            lb = (c == 0.0 || (c > 0.0) != (cm > 0.0)) ? (num * cm >= 0.0 ? MR_NEVER : -MR_NEVER) : num / c;
        }
        float limit = hit.surface != MR_MESH_NONE ? min(hit.lambda, lambdaMax) : lambdaMax;
        if (max(la, lb) < 0.0 || min(la, lb) > limit) continue;
        bool forward = mr_meshForward(path, la, lb, tm);
        mr_MeshPiece piece = mr_MeshPiece(forward ? ta : tb, forward ? tb : ta, forward ? la : lb,
                                          forward ? lb : la, false, vec3(0.0), vec3(0.0),
                                          forward ? kinds[i] : kinds[i + 1]);
        // Clipped to lambda in [0, limit] where lambda = L: the sign of (num - L c) sign(c)
        // is that of lambda - L inside; the bracket's end where lambda >= L.
        for (int side = 0; side < 2; ++side) {
            float L = side == 0 ? 0.0 : limit;
            bool clip = side == 0 ? piece.lambdaA < 0.0 : piece.lambdaB > limit;
            if (!clip) continue;
            float g[5] = mr_polyPlus(path.num, path.c, -L);
            if (cm < 0.0) g = mr_polyScaled(g, -1.0);
            float fa = mr_polyValue(g, piece.tA);
            float t = fa >= 0.0 ? piece.tA : mr_polyBisect(g, piece.tA, piece.tB, fa);
            float lt = mr_polyValue(path.num, t) / mr_polyValue(path.c, t);
            if (side == 0) {
                piece.tA = t;
                piece.lambdaA = max(0.0, lt);
                piece.entry = MR_MESH_INSIDE;
            } else {
                piece.tB = t;
                piece.lambdaB = lt;
            }
        }
        mr_meshSolvePiece(relief, windows, heights, tri, v, s, path, piece, top, budget, hit);
    }
    return hit.surface != MR_MESH_NONE ? hit.lambda : -1.0;
}

// ---- The hit's surface normal ----

// The outward unit normal of the solid's surface at `hit` (MeshReference.h, MeshHit::normal:
// the same surfaces, its formulas derived again here), in the mesh's units; zero for
// MR_MESH_INSIDE (no surface at the eye). Each surface is a level set of a function of the
// prism's coordinates (b, t), X(b, t) = B(b) + s t D(b); its normal is the cross product of
// two tangents, turned to the side where that function leaves the solid:
//  * top, t = h(uv(b)): the surface X(b, h(uv(b))) over (b_1, b_2) (b_0 = 1 - b_1 - b_2) has
//    tangents dX/db_k = A_k + s (dh/db_k) D, A_k = E_k + s h F_k the offset triangle's edges
//    at height h, dh/db_k = grad h . (T_k - T_0) (the map's gradient over uv through
//    uv(b)); outward is up, along dX/dt = s D (moving up at fixed b leaves the solid:
//    t - h grows);
//  * the mesh itself, t = 0: the plane of E_1 and E_2, outward down, against D;
//  * a wall b_i = 0: the ruled surface between the normal lines of the other two vertices j,
//    k, X(w, t) = (1 - w) Q_j(t) + w Q_k(t), Q_v = P_v + s t N_v, w = b_k / (b_j + b_k), with
//    tangents Q_k - Q_j and (1 - w) N_j + w N_k; outward away from Q_i (b_i grows into the
//    triangle);
//  * a fold: the envelope of the offset triangles, where the Jacobian (A_1, A_2, s D) of X
//    has rank 2; its tangent plane is the Jacobian's range, normal to the cross product of
//    any two columns (the longest taken: the best conditioned); outward towards the ray,
//    which enters the solid there (`v` the ray's direction).
// Float: the tangents are sums of a few products of the table's floats, so the normal is
// good to a few ulps of their lengths over the sine of the angle between them.
vec3 mr_meshNormal(mr_Relief relief, MICRORELIEF_SAMPLER heights, mr_MeshTriangle tri, float s, mr_MeshHit hit,
                   vec3 v) {
    vec3 b = hit.b;
    float t = hit.t;
    vec3 along = tri.n0 + b.y * tri.f1 + b.z * tri.f2;  // D(b)
    vec3 a1 = tri.e1 + s * t * tri.f1, a2 = tri.e2 + s * t * tri.f2;
    vec3 n = vec3(0.0), into = vec3(0.0);  // a normal and a direction into the solid
    if (hit.surface == MR_MESH_TOP) {
        vec2 g = mr_meshSurfaceGradient(relief, heights, hit.uv);
        n = cross(a1 + s * dot(g, tri.uv1 - tri.uv0) * along, a2 + s * dot(g, tri.uv2 - tri.uv0) * along);
        into = -along;
    } else if (hit.surface == MR_MESH_BASE) {
        n = cross(tri.e1, tri.e2);
        into = along;
    } else if (hit.surface >= MR_MESH_WALL0 && hit.surface <= MR_MESH_WALL0 + 2) {
        int i = hit.surface - MR_MESH_WALL0, j = i == 2 ? 0 : i + 1, k = j == 2 ? 0 : j + 1;
        vec3 q[3] = vec3[3](tri.p0, tri.p0 + a1, tri.p0 + a2);
        vec3 normals[3] = vec3[3](tri.n0, tri.n0 + tri.f1, tri.n0 + tri.f2);
        float w = b[j] + b[k] > 0.0 ? b[k] / (b[j] + b[k]) : 0.5;
        vec3 qj = q[j] + s * t * tri.n0, qk = q[k] + s * t * tri.n0;
        n = cross(qk - qj, mix(normals[j], normals[k], w));
        into = q[i] + s * t * tri.n0 - mix(qj, qk, w);
    } else if (hit.surface == MR_MESH_FOLD) {
        vec3 sd = s * along;
        vec3 c0 = cross(a1, a2), c1 = cross(a2, sd), c2 = cross(sd, a1);
        n = c0;
        if (dot(c1, c1) > dot(n, n)) n = c1;
        if (dot(c2, c2) > dot(n, n)) n = c2;
        into = v;
    }
    if (dot(n, into) > 0.0) n = -n;
    float length2 = dot(n, n);
    return length2 > 0.0 ? n * inversesqrt(length2) : vec3(0.0);
}

#endif
