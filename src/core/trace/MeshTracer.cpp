#include "microrelief/core/trace/MeshTracer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <vector>

#include "microrelief/core/Error.h"
#include "microrelief/core/GlslConstants.h"
#include "microrelief/core/heightmap/SurfacePatch.h"
#include "microrelief/core/trace/MultilevelTracer.h"
#include "microrelief/core/trace/SegmentWalk.h"

namespace microrelief {

namespace {


constexpr double kInf = std::numeric_limits<double>::infinity();

// ---- Polynomials in t of degree <= 4 (fixed arrays, no allocation: the GLSL's vec4 + float) --

double value(const MeshPolynomial& p, double t) {
    return (((p[4] * t + p[3]) * t + p[2]) * t + p[1]) * t + p[0];
}

MeshPolynomial derivative(const MeshPolynomial& p) {
    return {p[1], 2.0 * p[2], 3.0 * p[3], 4.0 * p[4], 0.0};
}

// The product, truncated to degree 4 (every product taken here has degree <= 4).
MeshPolynomial times(const MeshPolynomial& a, const MeshPolynomial& b) {
    MeshPolynomial r{};
    for (int i = 0; i < 5; ++i)
        for (int j = 0; i + j < 5; ++j) r[i + j] += a[i] * b[j];
    return r;
}

MeshPolynomial plus(const MeshPolynomial& a, const MeshPolynomial& b, double sb = 1.0) {
    MeshPolynomial r{};
    for (int i = 0; i < 5; ++i) r[i] = a[i] + sb * b[i];
    return r;
}

MeshPolynomial scaled(const MeshPolynomial& a, double s) {
    MeshPolynomial r{};
    for (int i = 0; i < 5; ++i) r[i] = s * a[i];
    return r;
}

// The numerator of (n / c)' : n' c - n c'.
MeshPolynomial turnNumerator(const MeshPolynomial& n, const MeshPolynomial& c) {
    return plus(times(derivative(n), c), times(n, derivative(c)), -1.0);
}

// A vector polynomial of degree <= 2: m0 + t m1 + t^2 m2.
using VectorQuadratic = std::array<glm::dvec3, 3>;

// (a0 + t a1) x (b0 + t b1).
VectorQuadratic crossLinear(glm::dvec3 a0, glm::dvec3 a1, glm::dvec3 b0, glm::dvec3 b1) {
    return {glm::cross(a0, b0), glm::cross(a0, b1) + glm::cross(a1, b0), glm::cross(a1, b1)};
}

MeshPolynomial dotConstant(glm::dvec3 v, const VectorQuadratic& m) {
    return {glm::dot(v, m[0]), glm::dot(v, m[1]), glm::dot(v, m[2]), 0.0, 0.0};
}

// (w0 + t w1) . m
MeshPolynomial dotLinear(glm::dvec3 w0, glm::dvec3 w1, const VectorQuadratic& m) {
    return {glm::dot(w0, m[0]), glm::dot(w0, m[1]) + glm::dot(w1, m[0]),
            glm::dot(w0, m[2]) + glm::dot(w1, m[1]), glm::dot(w1, m[2]), 0.0};
}

// The point of [a, b] where p changes sign (p(a) has the sign `fa`), to the last bit: the end
// on p(b)'s side. Bounded: at most 2100 halvings reach adjacent doubles from any interval.
double bisect(const MeshPolynomial& p, double a, double b, double fa) {
    for (int k = 0; k < 2100; ++k) {
        const double m = 0.5 * (a + b);
        if (m == a || m == b) break;  // adjacent doubles (a and b in either order)
        const double fm = value(p, m);
        if (fm != 0.0 && (fm < 0.0) == (fa < 0.0)) {
            a = m;
        } else {
            b = m;
        }
    }
    return b;
}

// The real roots of p in the open interval (lo, hi), ascending (at most 4): those of each
// derivative isolate the next one's, from the linear up to p itself, and a sign change between
// neighbouring isolating points is bisected. No recursion: the degree is the loop.
int rootsIn(const MeshPolynomial& p, double lo, double hi, double* out) {
    MeshPolynomial d[5];
    d[0] = p;
    for (int k = 1; k < 5; ++k) d[k] = derivative(d[k - 1]);
    double roots[4];
    int count = 0;
    for (int k = 3; k >= 0; --k) {
        double points[6];
        int n = 0;
        points[n++] = lo;
        for (int r = 0; r < count; ++r) points[n++] = roots[r];
        points[n++] = hi;
        int next = 0;
        double found[4];
        for (int r = 0; r + 1 < n; ++r) {
            const double a = points[r], b = points[r + 1];
            const double fa = value(d[k], a), fb = value(d[k], b);
            if (fa == 0.0 && r > 0) {
                if (next < 4) found[next++] = a;  // a root exactly at an isolating point
            } else if ((fa < 0.0 && fb > 0.0) || (fa > 0.0 && fb < 0.0)) {
                if (next < 4) found[next++] = bisect(d[k], a, b, fa);
            }
        }
        count = next;
        for (int r = 0; r < count; ++r) roots[r] = found[r];
    }
    for (int r = 0; r < count; ++r) out[r] = roots[r];
    return count;
}

// A cut of [0, H] and what a piece that starts there below the surface enters through.
struct Cut {
    double t;
    MeshSurface reason;
    int wall = -1;  // reason Wall: b_wall = 0
};

}  // namespace

std::vector<std::uint8_t> smoothEdges(const TriangleMesh& mesh) {
    // Each triangle's edge opposite vertex i runs from vertex i + 1 to vertex i + 2; keyed by
    // its two positions in a fixed order, so that both triangles of an edge meet in one entry.
    using Key = std::array<float, 6>;
    struct Side {
        std::size_t triangle;
        int edge;
        bool reversed;  // the key's order is the edge's i + 2 -> i + 1
    };
    std::map<Key, std::vector<Side>> edges;
    const auto keyOf = [&](std::uint32_t a, std::uint32_t b, bool& reversed) {
        const glm::vec3 pa = mesh.positions[a], pb = mesh.positions[b];
        const Key ab{pa.x, pa.y, pa.z, pb.x, pb.y, pb.z}, ba{pb.x, pb.y, pb.z, pa.x, pa.y, pa.z};
        reversed = ba < ab;
        return reversed ? ba : ab;
    };
    for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
        const glm::uvec3 v = mesh.triangles[k];
        for (int i = 0; i < 3; ++i) {
            bool reversed = false;
            const Key key = keyOf(v[(i + 1) % 3], v[(i + 2) % 3], reversed);
            edges[key].push_back({k, i, reversed});
        }
    }
    std::vector<std::uint8_t> smooth(mesh.triangles.size(), 0);
    for (const auto& [key, sides] : edges) {
        if (sides.size() != 2 || sides[0].reversed == sides[1].reversed) continue;
        // The two ends of each side in the key's order.
        std::uint32_t ends[2][2];
        for (int s = 0; s < 2; ++s) {
            const glm::uvec3 v = mesh.triangles[sides[s].triangle];
            const std::uint32_t a = v[(sides[s].edge + 1) % 3], b = v[(sides[s].edge + 2) % 3];
            ends[s][0] = sides[s].reversed ? b : a;
            ends[s][1] = sides[s].reversed ? a : b;
        }
        bool same = true;
        glm::dvec2 shift{0.0};
        for (int e = 0; e < 2; ++e) {
            const std::uint32_t a = ends[0][e], b = ends[1][e];
            same = same && mesh.normals[a] == mesh.normals[b];
            const glm::dvec2 d = glm::dvec2(mesh.texCoords[b]) - glm::dvec2(mesh.texCoords[a]);
            same = same && d == glm::floor(d) && (e == 0 || d == shift);
            shift = d;
        }
        if (!same) continue;
        for (const Side& side : sides)
            smooth[side.triangle] |= static_cast<std::uint8_t>(1u << side.edge);
    }
    return smooth;
}

MeshTracer::MeshTracer(const TriangleMesh& mesh, HeightMap map, double heightScale,
                       Interpolation interpolation)
    : map_(std::move(map)),
      interpolation_(interpolation),
      repeat_{false, 3, 3},
      pyramid_(map_, repeat_, BoundPrecision::Half),
      heightScale_(heightScale),
      // A shell of some height even over a map of zeros, so that t has a range to walk.
      top_(std::max(static_cast<double>(pyramid_.maxHeight()), 1e-6)),
      maxIterations_(traversalBudget(map_.width, map_.height)) {
    if (map_.empty()) throwRuntime("MeshTracer: an empty map");
    const std::vector<std::uint8_t> smooth = smoothEdges(mesh);
    for (const glm::uvec3& k : mesh.triangles) {
        Triangle tri;
        tri.smooth = smooth[triangles_.size()];
        const glm::dvec3 p[3] = {mesh.positions[k[0]], mesh.positions[k[1]],
                                 mesh.positions[k[2]]};
        const glm::dvec3 n[3] = {mesh.normals[k[0]], mesh.normals[k[1]], mesh.normals[k[2]]};
        tri.p0 = p[0];
        tri.e1 = p[1] - p[0];
        tri.e2 = p[2] - p[0];
        tri.n0 = n[0];
        tri.f1 = n[1] - n[0];
        tri.f2 = n[2] - n[0];
        tri.uv0 = mesh.texCoords[k[0]];
        tri.uv1 = mesh.texCoords[k[1]];
        tri.uv2 = mesh.texCoords[k[2]];
        // X(b, t) is a convex combination of the six corners P_i + s t' N_i, t' in {0, H}:
        // the prism lies in their box.
        tri.boxLo = tri.boxHi = p[0];
        for (int i = 0; i < 3; ++i) {
            for (const glm::dvec3 corner : {p[i], p[i] + heightScale_ * top_ * n[i]}) {
                tri.boxLo = glm::min(tri.boxLo, corner);
                tri.boxHi = glm::max(tri.boxHi, corner);
            }
        }
        triangles_.push_back(tri);
    }
}

glm::dvec2 MeshTracer::boxSpan(const Ray& ray, std::size_t k) const {
    const Triangle& tri = triangles_[k];
    const glm::dvec3 pad(1e-9 * (1.0 + glm::length(tri.boxHi - tri.boxLo)));
    const glm::dvec3 lo = tri.boxLo - pad, hi = tri.boxHi + pad;
    double enter = -kInf, exit = kInf;
    for (int a = 0; a < 3; ++a) {
        if (ray.direction[a] == 0.0) {
            if (ray.origin[a] < lo[a] || ray.origin[a] > hi[a]) return {1.0, 0.0};
            continue;
        }
        double t0 = (lo[a] - ray.origin[a]) / ray.direction[a];
        double t1 = (hi[a] - ray.origin[a]) / ray.direction[a];
        if (t0 > t1) std::swap(t0, t1);
        enter = std::max(enter, t0);
        exit = std::min(exit, t1);
    }
    return {enter, exit};
}

PrismPath MeshTracer::path(const Ray& ray, const Triangle& tri) const {
    PrismPath path;
    const double s = heightScale_;
    const glm::dvec3 v = ray.direction;
    // A_k(t) = E_k + s t F_k; W(t) = O - Q(t) = (O - P0) - s t N0. Cramer on
    // W + lambda V = b1 A1 + b2 A2 (MeshReference.h): with m = A1 x A2,
    // lambda = -W.m / V.m, b1 = V.(W x A2) / V.m, b2 = V.(A1 x W) / V.m.
    const glm::dvec3 w0 = ray.origin - tri.p0, w1 = -s * tri.n0;
    const VectorQuadratic m = crossLinear(tri.e1, s * tri.f1, tri.e2, s * tri.f2);
    path.c = dotConstant(v, m);
    path.num = scaled(dotLinear(w0, w1, m), -1.0);
    path.n1 = dotConstant(v, crossLinear(w0, w1, tri.e2, s * tri.f2));
    path.n2 = dotConstant(v, crossLinear(tri.e1, s * tri.f1, w0, w1));
    path.uv0 = tri.uv0;
    path.uv1 = tri.uv1;
    path.uv2 = tri.uv2;
    // Parallel to every offset plane: |c| is below 1e-14 of |V| |m| over [0, H] (an angle of
    // 1e-14 to each plane; as level, t then moves by 1e-14 of the ray's length in the box).
    const double h = top_;
    const double cSize = std::abs(path.c[0]) + std::abs(path.c[1]) * h + std::abs(path.c[2]) * h * h;
    const double mSize = glm::length(m[0]) + glm::length(m[1]) * h + glm::length(m[2]) * h * h;
    path.level = cSize <= 1e-14 * glm::length(v) * mSize;
    return path;
}

MeshPathPoint MeshTracer::pointOn(const PrismPath& path, const MeshPiece& piece, double p) const {
    MeshPathPoint m;
    if (piece.level) {
        m.t = piece.tA;
        m.lambda = p >= 1.0 ? piece.lambdaB : piece.lambdaA + p * (piece.lambdaB - piece.lambdaA);
        m.b = piece.levelB0 + m.lambda * piece.levelB1;
    } else {
        m.t = p >= 1.0 ? piece.tB : piece.tA + p * (piece.tB - piece.tA);
        const double c = value(path.c, m.t);
        m.lambda = value(path.num, m.t) / c;
        m.b.y = value(path.n1, m.t) / c;
        m.b.z = value(path.n2, m.t) / c;
        m.b.x = 1.0 - m.b.y - m.b.z;
    }
    m.uv = m.b.x * path.uv0 + m.b.y * path.uv1 + m.b.z * path.uv2;
    return m;
}

int MeshTracer::pieces(const Ray& ray, std::size_t k, double lambdaMax, PrismPath& out,
                       std::array<MeshPiece, kMaxPieces>& pieces) const {
    const Triangle& tri = triangles_[k];
    out = path(ray, tri);
    const PrismPath& path = out;
    const double h = top_;
    int count = 0;
    const auto add = [&](const MeshPiece& piece) {
        if (count >= kMaxPieces) return;
        // Ordered by lambdaA (insertion: a handful).
        int at = count++;
        while (at > 0 && pieces[at - 1].lambdaA > piece.lambdaA) {
            pieces[at] = pieces[at - 1];
            --at;
        }
        pieces[at] = piece;
    };

    if (path.level) {
        // The ray lies in the offset plane of each root t* of num: b linear in lambda there.
        double roots[6];
        int n = rootsIn(path.num, 0.0, h, roots);
        for (const double end : {0.0, h})
            if (value(path.num, end) == 0.0 && n < 6) roots[n++] = end;
        for (int r = 0; r < n; ++r) {
            const double t = roots[r], s = heightScale_;
            const glm::dvec3 a1 = tri.e1 + s * t * tri.f1, a2 = tri.e2 + s * t * tri.f2;
            const glm::dvec3 q = tri.p0 + s * t * tri.n0;
            const double g11 = glm::dot(a1, a1), g12 = glm::dot(a1, a2), g22 = glm::dot(a2, a2);
            const double det = g11 * g22 - g12 * g12;
            if (!(det > 0.0)) continue;  // a focal height: the offset triangle collapsed
            const auto solve = [&](glm::dvec3 r3) {
                const double x = glm::dot(a1, r3), y = glm::dot(a2, r3);
                return glm::dvec2((g22 * x - g12 * y) / det, (g11 * y - g12 * x) / det);
            };
            const glm::dvec2 at0 = solve(ray.origin - q), slope = solve(ray.direction);
            MeshPiece piece;
            piece.level = true;
            piece.tA = piece.tB = t;
            piece.levelB0 = {1.0 - at0.x - at0.y, at0.x, at0.y};
            piece.levelB1 = {-slope.x - slope.y, slope.x, slope.y};
            double lo = 0.0, hi = lambdaMax;
            MeshSurface entry = MeshSurface::Inside;
            int wall = -1;
            bool empty = false;
            for (int i = 0; i < 3; ++i) {
                const double b0 = piece.levelB0[i], b1 = piece.levelB1[i];
                if (b1 == 0.0) {
                    empty = empty || b0 < 0.0;
                } else if (b1 > 0.0) {
                    if (-b0 / b1 > lo) {
                        lo = -b0 / b1;
                        entry = MeshSurface::Wall;
                        wall = i;
                    }
                } else {
                    hi = std::min(hi, -b0 / b1);
                }
            }
            if (empty || lo > hi) continue;
            piece.lambdaA = lo;
            piece.lambdaB = hi;
            piece.entry = entry;
            piece.wall = wall;
            add(piece);
        }
        return count;
    }

    // The cuts of [0, H]: the ends, the roots of c, of each b's numerator and of the turning
    // numerators of lambda, b_0..2, u and v.
    const MeshPolynomial n0 = plus(plus(path.c, path.n1, -1.0), path.n2, -1.0);
    const glm::dvec2 du1 = path.uv1 - path.uv0, du2 = path.uv2 - path.uv0;
    const MeshPolynomial nu =
        plus(plus(scaled(path.c, path.uv0.x), scaled(path.n1, du1.x)), scaled(path.n2, du2.x));
    const MeshPolynomial nv =
        plus(plus(scaled(path.c, path.uv0.y), scaled(path.n1, du1.y)), scaled(path.n2, du2.y));
    struct Source {
        MeshPolynomial p;
        MeshSurface reason;
        int wall = -1;
    };
    const Source sources[] = {
        {path.c, MeshSurface::Fold},
        {n0, MeshSurface::Wall, 0},
        {path.n1, MeshSurface::Wall, 1},
        {path.n2, MeshSurface::Wall, 2},
        {turnNumerator(path.num, path.c), MeshSurface::Fold},
        {turnNumerator(n0, path.c), MeshSurface::Top},
        {turnNumerator(path.n1, path.c), MeshSurface::Top},
        {turnNumerator(path.n2, path.c), MeshSurface::Top},
        {turnNumerator(nu, path.c), MeshSurface::Top},
        {turnNumerator(nv, path.c), MeshSurface::Top},
    };
    Cut cuts[48];
    int cutCount = 0;
    cuts[cutCount++] = {0.0, MeshSurface::Base};
    cuts[cutCount++] = {h, MeshSurface::Top};
    for (const Source& source : sources) {
        double roots[4];
        const int n = rootsIn(source.p, 0.0, h, roots);
        for (int r = 0; r < n; ++r) cuts[cutCount++] = {roots[r], source.reason, source.wall};
    }
    std::sort(cuts, cuts + cutCount, [](const Cut& a, const Cut& b) { return a.t < b.t; });

    const double lambdaMin = 0.0;
    for (int i = 0; i + 1 < cutCount; ++i) {
        const double ta = cuts[i].t, tb = cuts[i + 1].t;
        if (!(tb > ta)) continue;
        const double tm = 0.5 * (ta + tb), cm = value(path.c, tm);
        if (cm == 0.0) continue;
        // b's signs are fixed inside the piece (cut at the roots of its numerators and of c).
        const double b1 = value(path.n1, tm) / cm, b2 = value(path.n2, tm) / cm;
        if (b1 < 0.0 || b2 < 0.0 || value(n0, tm) / cm < 0.0) continue;
        // lambda at an end: at a pole (c = 0, or rounded to the other sign) the infinity it
        // tends to from inside.
        const auto lambdaAt = [&](double t) {
            const double c = value(path.c, t), num = value(path.num, t);
            if (c == 0.0 || (c > 0.0) != (cm > 0.0)) return num * cm >= 0.0 ? kInf : -kInf;
            return num / c;
        };
        const double la = lambdaAt(ta), lb = lambdaAt(tb);
        if (std::max(la, lb) < lambdaMin || std::min(la, lb) > lambdaMax) continue;
        // A = ta where lambda grows from ta to tb: by la <= lb, unless the two are equal to
        // rounding (a shell thinner than the eye's distance resolves: every t of the piece one
        // lambda), where the sign of lambda' = (num' c - num c') / c^2 in the middle decides,
        // when it is clear of the factors' rounding (base_mesh.glsl's mr_meshForward, the same
        // rule; 2^-16 and 2^-12 there, 2^-40 and 2^-30 in double). It keeps one sign on the
        // piece (cut at the roots of num' c - num c').
        bool forward = la <= lb;
        if (std::abs(lb - la) <= (std::abs(la) + std::abs(lb)) * 0x1p-40) {
            const double a = value(derivative(path.num), tm) * value(path.c, tm);
            const double b = value(path.num, tm) * value(derivative(path.c), tm);
            if (std::abs(a - b) > (std::abs(a) + std::abs(b)) * 0x1p-30) forward = a > b;
        }
        double tA = forward ? ta : tb, tB = forward ? tb : ta;
        double lambdaA = forward ? la : lb, lambdaB = forward ? lb : la;
        MeshSurface entry = forward ? cuts[i].reason : cuts[i + 1].reason;
        int wall = forward ? cuts[i].wall : cuts[i + 1].wall;
        // Where lambda = L between tA and tB: the sign of (num - L c) sign(c) is that of
        // lambda - L inside; the bracket's end where lambda >= L (a hair past L at most).
        const auto crossing = [&](double L) {
            MeshPolynomial g = plus(path.num, path.c, -L);
            if (cm < 0.0) g = scaled(g, -1.0);
            const double fa = value(g, tA);
            return fa >= 0.0 ? tA : bisect(g, tA, tB, fa);
        };
        if (lambdaA < lambdaMin) {
            tA = crossing(lambdaMin);
            lambdaA = std::max(lambdaMin, lambdaAt(tA));
            entry = MeshSurface::Inside;
            wall = -1;
        }
        if (lambdaB > lambdaMax) {
            tB = crossing(lambdaMax);
            lambdaB = lambdaAt(tB);
        }
        MeshPiece piece;
        piece.tA = tA;
        piece.tB = tB;
        piece.lambdaA = lambdaA;
        piece.lambdaB = lambdaB;
        piece.entry = entry;
        piece.wall = wall;
        add(piece);
    }
    return count;
}

// ---- The map repeated in u and v ----

BoundRead MeshTracer::footprintBound(glm::dvec2 lo, glm::dvec2 hi) const {
    // Per axis the finest texels floor(lo)..floor(hi), taken into one period: one range, two
    // where it crosses the period's edge, the whole axis where it spans a period.
    struct Range {
        int lo, hi;
    };
    Range ranges[2][2];
    int counts[2];
    const int size[2] = {map_.width, map_.height};
    for (int axis = 0; axis < 2; ++axis) {
        const double a = std::floor(lo[axis]), b = std::floor(hi[axis]);
        if (!(b - a < size[axis] - 1)) {
            ranges[axis][0] = {0, size[axis] - 1};
            counts[axis] = 1;
            continue;
        }
        const int first = static_cast<int>(a - size[axis] * std::floor(a / size[axis]));
        const int last = first + static_cast<int>(b - a);
        if (last < size[axis]) {
            ranges[axis][0] = {first, last};
            counts[axis] = 1;
        } else {
            ranges[axis][0] = {first, size[axis] - 1};
            ranges[axis][1] = {0, last - size[axis]};
            counts[axis] = 2;
        }
    }
    BoundRead read{0.0, -1, 0};
    for (int x = 0; x < counts[0]; ++x) {
        for (int y = 0; y < counts[1]; ++y) {
            const BoundRead r = pyramid_.segmentBound(
                {ranges[0][x].lo + 0.5, ranges[1][y].lo + 0.5},
                {ranges[0][x].hi + 0.5, ranges[1][y].hi + 0.5});
            read.bound = std::max(read.bound, r.bound);
            read.level = std::max(read.level, r.level);
            read.fetches += r.fetches;
        }
    }
    return read;
}

glm::dvec3 MeshTracer::texelPoint(const MeshPathPoint& m) const {
    return {m.uv.x * map_.width, m.uv.y * map_.height, m.t};
}

namespace {

// Cell (i, j) of the map repeated in u and v, its samples read in the middle of 3 x 3 tiles so
// that neighbours on every side are the repeated ones.
SurfacePatch repeatedPatch(const HeightMap& map, const MapAddressing& repeat, long long i,
                           long long j, Interpolation interpolation) {
    const long long w = map.width, h = map.height;
    const int ii = static_cast<int>(((i % w) + w) % w + w), jj = static_cast<int>(((j % h) + h) % h + h);
    return SurfacePatch::at(map, ii, jj, repeat, interpolation);
}

}  // namespace

double MeshTracer::surfaceAt(glm::dvec2 uv, MeshTraceStats& stats) const {
    const double offset = SurfacePatch::offset(interpolation_);
    const double x = uv.x * map_.width - offset, y = uv.y * map_.height - offset;
    const double i = std::floor(x), j = std::floor(y);
    stats.fetches += interpolation_ == Interpolation::Biquadratic ? 4 : 1;
    const SurfacePatch patch = repeatedPatch(map_, repeat_, static_cast<long long>(i),
                                             static_cast<long long>(j), interpolation_);
    return patch.height(glm::clamp(glm::dvec2(x - i, y - j), 0.0, 1.0));
}

// A piece, p in [0, 1], as the segment walk's path (SegmentWalk.h). Why each answer is a
// bound, in texels for the footprint and map height units for t: MeshTracer.h.
class MeshTracer::PiecePath {
public:
    using Hit = double;  // p of the hit

    PiecePath(const MeshTracer& tracer, const PrismPath& path, const MeshPiece& piece)
        : tracer_(tracer), path_(path), piece_(piece) {}

    double span() const { return 1.0; }
    bool floorExit() const { return false; }  // a piece ends at a cut, not through a floor
    Footprint footprint(double pa, double pb) const {
        const glm::dvec3 xa = end(pa), xb = end(pb);
        Footprint f;
        f.lo = glm::min(glm::dvec2(xa), glm::dvec2(xb));
        f.hi = glm::max(glm::dvec2(xa), glm::dvec2(xb));
        // Margin of the footprint: double rounding of n / c and of the uv sums, in texels.
        const auto widen = [](double x) { return 1e-9 + 1e-12 * std::abs(x); };
        f.lo -= glm::dvec2(widen(f.lo.x), widen(f.lo.y));
        f.hi += glm::dvec2(widen(f.hi.x), widen(f.hi.y));
        // t is linear in p (fixed on a level piece): its least over [pa, pb] is at an end.
        f.lowest = std::min(xa.z, xb.z);
        f.drop = std::abs(xb.z - xa.z);
        return f;
    }
    double lowest(double pa, double pb) const {
        return std::min(tracer_.pointOn(path_, piece_, pa).t, tracer_.pointOn(path_, piece_, pb).t);
    }
    double bound(const Footprint& footprint, MeshTraceStats& stats) const {
        const BoundRead read = tracer_.footprintBound(footprint.lo, footprint.hi);
        stats.fetches += read.fetches;
        return read.bound;
    }
    // Where t comes down to h (t linear in p), never later: moved back by 1e-12 of the segment.
    double descendTo(double pa, double pb, double h) const {
        const double ta = tracer_.pointOn(path_, piece_, pa).t,
                     tb = tracer_.pointOn(path_, piece_, pb).t;
        double from = pa;
        if (ta > h && tb < ta) from = std::clamp(pa + (pb - pa) * (ta - h) / (ta - tb), pa, pb);
        return std::max(pa, from - 1e-12 * (pb - pa));
    }
    std::optional<double> leaf(double from, double to, MeshTraceStats& stats) const {
        const double p = tracer_.leaf(path_, piece_, from, to, stats);
        return p >= 0.0 ? std::optional<double>(p) : std::nullopt;
    }
    std::optional<double> floorHit(MeshTraceStats&) const { return std::nullopt; }

private:
    glm::dvec3 end(double p) const { return tracer_.texelPoint(tracer_.pointOn(path_, piece_, p)); }

    const MeshTracer& tracer_;
    const PrismPath& path_;
    const MeshPiece& piece_;
};

// The leaf: the cells the path crosses on [p0, p1] in order (u and v monotone), each cell's
// stretch ending where u or v crosses the cell's boundary ahead (bisection on the monotone
// coordinate), each solved as MultilevelTracer::cellStretchHit solves a curved stretch.
double MeshTracer::leaf(const PrismPath& path, const MeshPiece& piece, double p0, double p1,
                        MeshTraceStats& stats) const {
    const double offset = SurfacePatch::offset(interpolation_);
    const auto cellCoords = [&](double p) {
        const glm::dvec3 x = texelPoint(pointOn(path, piece, p));
        return glm::dvec3(x.x - offset, x.y - offset, x.z);
    };
    const glm::dvec3 start = cellCoords(p0), end = cellCoords(p1);
    long long at[2] = {static_cast<long long>(std::floor(start.x)),
                       static_cast<long long>(std::floor(start.y))};
    const long long last[2] = {static_cast<long long>(std::floor(end.x)),
                               static_cast<long long>(std::floor(end.y))};
    const int step[2] = {last[0] > at[0] ? 1 : -1, last[1] > at[1] ? 1 : -1};
    const long long cells = std::llabs(last[0] - at[0]) + std::llabs(last[1] - at[1]) + 1;
    // The first p in [from, p1] at which coordinate `axis` is past `boundary` (monotone).
    const auto crossing = [&](int axis, double boundary, double from) {
        double a = from, b = p1;
        const auto past = [&](double p) {
            const double x = cellCoords(p)[axis];
            return step[axis] > 0 ? x >= boundary : x <= boundary;
        };
        if (!past(b)) return p1;
        for (int k = 0; k < 200; ++k) {
            const double m = 0.5 * (a + b);
            if (m <= a || m >= b) break;
            (past(m) ? b : a) = m;
        }
        return b;
    };
    double pc = p0;
    for (long long k = 0; k < cells; ++k) {
        double exits[2] = {p1, p1};
        for (int axis = 0; axis < 2; ++axis) {
            if (at[axis] != last[axis])
                exits[axis] = crossing(axis, static_cast<double>(at[axis] + (step[axis] > 0 ? 1 : 0)), pc);
        }
        const double pe = std::min(exits[0], exits[1]);
        stats.fetches += interpolation_ == Interpolation::Biquadratic ? 4 : 1;
        const SurfacePatch patch = repeatedPatch(map_, repeat_, at[0], at[1], interpolation_);
        // The first p in [pc, pe] with patch(uv(p)) - t(p) >= 0.
        const glm::dvec2 cell(static_cast<double>(at[0]), static_cast<double>(at[1]));
        const auto local = [&](double p) {
            const glm::dvec3 x = cellCoords(p);
            return glm::dvec3(x.x - cell.x, x.y - cell.y, x.z);
        };
        const auto gap = [&](const glm::dvec3& f) {
            return patch.height(glm::clamp(glm::dvec2(f), 0.0, 1.0)) - f.z;
        };
        constexpr int kFinalDepth = 40;
        const double finalFootprint = std::ldexp(1.0, -12), finalDrop = std::ldexp(top_, -12);
        int depth = 0;
        std::uint64_t index = 0;
        for (int guard = 0; guard < (1 << 20); ++guard) {
            const double width = (pe - pc) / static_cast<double>(std::uint64_t(1) << depth);
            const double a = pc + static_cast<double>(index) * width;
            const double b = index + 1 == (std::uint64_t(1) << depth) ? pe : a + width;
            const glm::dvec3 fa = local(a), fb = local(b);
            const glm::dvec2 lo = glm::min(glm::dvec2(fa), glm::dvec2(fb)),
                             hi = glm::max(glm::dvec2(fa), glm::dvec2(fb));
            // u, v monotone: the stretch's path lies over [lo, hi]; t linear: its least at an end.
            const double top = patch.maxOver(lo - 1e-9, hi + 1e-9);
            const bool may = std::min(fa.z, fb.z) <= top;
            const bool final = depth == kFinalDepth ||
                               (std::max(hi.x - lo.x, hi.y - lo.y) <= finalFootprint &&
                                std::abs(fb.z - fa.z) <= finalDrop);
            if (may && !final) {
                ++depth;
                index *= 2u;
                continue;
            }
            if (may) {
                const double m = 0.5 * (a + b);
                if (const auto s = parabolaFirstRoot(gap(fa), gap(local(m)), gap(fb)))
                    return a + *s * (b - a);
            }
            ++index;
            while (depth > 0 && (index & 1u) == 0u) {
                index >>= 1;
                --depth;
            }
            if (depth == 0) break;
        }
        if (pe >= p1) break;
        const int axis = exits[0] <= exits[1] ? 0 : 1;
        at[axis] += step[axis];
        pc = pe;
    }
    return -1.0;
}

MeshTraceHit MeshTracer::traceTriangle(const Ray& ray, std::size_t k, double lambdaMax,
                                       MeshTraceStats& stats) const {
    ++stats.triangles;
    PrismPath path;
    std::array<MeshPiece, kMaxPieces> list;
    const int n = pieces(ray, k, lambdaMax, path, list);
    MeshTraceHit best;
    for (int i = 0; i < n; ++i) {
        const MeshPiece& piece = list[i];
        if (best && piece.lambdaA > best.t) break;
        ++stats.pieces;
        // Starting at or below the surface: entered through the piece's start.
        const MeshPathPoint m0 = pointOn(path, piece, 0.0);
        double p = -1.0;
        MeshSurface surface = MeshSurface::Top;
        if (const double h = surfaceAt(m0.uv, stats); h >= m0.t) {
            p = 0.0;
            surface = piece.entry;
            // A wall on a smooth edge (smoothEdges) is no surface where the two prisms lie on
            // its two sides. Starting on it within rounding of the top or the mesh (1e-9 H
            // here, 2^-12 H in float), the piece starts where the neighbour's top or mesh
            // reaches the edge, the neighbour's own hit a rounding later or level: named as
            // MeshReference names a hit, by the nearest surface (distances in the mesh's units:
            // s |D| (h - t), s |D| t, |b_j| times the altitude over edge j for a wall that is a
            // surface; top and mesh tied, h = 0, the mesh for a ray going up along D). Further
            // from both it stays a wall: the ray came into the union earlier through another
            // prism, unless the prisms fold to one side of the wall, where it is the surface.
            // No hit is moved or dropped, only named (base_mesh.glsl's mr_meshSolvePiece).
            const Triangle& tri = triangles_[k];
            const double band = 1e-9 * top_;
            if (surface == MeshSurface::Wall && piece.wall >= 0 && ((tri.smooth >> piece.wall) & 1u) &&
                (h - m0.t <= band || m0.t <= band)) {
                const glm::dvec3 along = tri.n0 + m0.b.y * tri.f1 + m0.b.z * tri.f2;
                const double unit = heightScale_ * glm::length(along);
                const double toTop = (h - m0.t) * unit, toBase = std::abs(m0.t) * unit;
                const bool base =
                    toBase < toTop || (toBase == toTop && glm::dot(ray.direction, along) > 0.0);
                surface = base ? MeshSurface::Base : MeshSurface::Top;
                double closest = base ? toBase : toTop;
                const double twiceArea = glm::length(glm::cross(tri.e1, tri.e2));
                const double edges[3] = {glm::length(tri.e2 - tri.e1), glm::length(tri.e2),
                                         glm::length(tri.e1)};  // opposite P_j
                for (int j = 0; j < 3; ++j) {
                    if ((tri.smooth >> j) & 1u) continue;
                    if (const double d = std::abs(m0.b[j]) * twiceArea / edges[j]; d < closest) {
                        closest = d;
                        surface = MeshSurface::Wall;
                    }
                }
            }
        } else {
            p = walkSegments(PiecePath(*this, path, piece), maxIterations_, stats).value_or(-1.0);
        }
        if (p < 0.0) continue;
        const MeshPathPoint m = pointOn(path, piece, p);
        if (best && m.lambda >= best.t) continue;
        best.surface = surface;
        best.t = m.lambda;
        best.position = ray.origin + m.lambda * ray.direction;
        best.triangle = k;
        best.barycentric = m.b;
        best.height = m.t;
        best.uv = m.uv;
    }
    return best;
}

MeshTraceHit MeshTracer::trace(const Ray& ray, MeshTraceStats* statsOut) const {
    MeshTraceStats stats;
    std::vector<std::pair<double, std::size_t>> order;
    for (std::size_t k = 0; k < triangles_.size(); ++k) {
        const glm::dvec2 span = boxSpan(ray, k);
        if (span.y >= 0.0 && span.x <= span.y) order.push_back({std::max(span.x, 0.0), k});
    }
    std::sort(order.begin(), order.end());
    MeshTraceHit best;
    for (const auto& [enter, k] : order) {
        if (best && enter > best.t) break;
        const double exit = boxSpan(ray, k).y;
        const MeshTraceHit hit = traceTriangle(ray, k, best ? std::min(best.t, exit) : exit, stats);
        if (hit && (!best || hit.t < best.t)) best = hit;
    }
    if (statsOut) *statsOut = stats;
    return best;
}

}  // namespace microrelief
