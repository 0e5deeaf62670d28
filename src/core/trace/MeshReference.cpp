// The mesh's exact reference (core/trace/MeshReference.h, which states the design and the
// accuracy). Written from docs/bases.md, "The mesh": nothing here comes from the shaders,
// the traversal or the other references.
//
// Notation, per triangle: P_0, E_k = P_k - P_0, N_0, F_k = N_k - N_0 (k = 1, 2), s the
// height scale. At height t the offset triangle has corner Q(t) = P_0 + s t N_0 and edges
// A_k(t) = E_k + s t F_k; its (unnormalised) normal m(t) = A_1 x A_2 is a quadratic in t.
// The ray, moved to start where it enters the triangle's box, is Y(mu) = O + mu V (O
// relative to P_0). Y(mu) is on the offset plane of height t iff
//     (Y - Q(t)) . m(t) = 0   <=>   num(t) - mu c(t) = 0,
//     c(t) = V . m(t)  (degree 2),   num(t) = (Q(t) - P_0 - O) . m(t)  (degree 3),
// and there (Cramer, dotting Y - Q = b_1 A_1 + b_2 A_2 with A_2 x V and V x A_1)
//     b_1 = n_1(t) / c(t),  n_1 = (O - s t N_0) . (A_2 x V),
//     b_2 = n_2(t) / c(t),  n_2 = (O - s t N_0) . (V x A_1),   b_0 = 1 - b_1 - b_2,
// all numerators of degree 2. These closed forms serve to cut the curve into monotone
// pieces; the values along a piece are computed from mu (t as a bracketed root, b by
// projection), which stays well conditioned where c is small (a ray nearly parallel to
// the offset planes), where the closed forms divide by almost nothing.
#include "microrelief/core/trace/MeshReference.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

namespace microrelief {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// The hit's tolerance and the boxes' padding, relative to the diagonal of the mesh's shell.
constexpr double kTolerance = 1e-12;
constexpr double kBoxPadding = 1e-9;
// A hit at least this far (relative to the diagonal) from the top, the mesh and every wall
// is on a fold.
constexpr double kFoldMargin = 1e-5;
// Stretches examined on one piece of a triangle's curve before contact is assumed (a ray
// that runs within the tolerance of the surface for long); never reached in the tests.
constexpr int kMaxStretches = 200000;
// A uv rectangle over more cells than this is bounded by the map's largest sample.
constexpr double kMaxCellsBounded = 256.0;

// ---- h(uv): the map repeated in u and v (the contract's addressing) ----

class HeightSurface {
public:
    HeightSurface(const HeightMap& map, Interpolation interpolation)
        : map_(map), quadratic_(interpolation == Interpolation::Biquadratic) {
        assert(!map.empty());
        largest_ = *std::max_element(map.samples.begin(), map.samples.end());
    }

    double largest() const { return largest_; }

    // Bilinear between sample centres: sample (i, j) at uv ((i + 1/2) / W, (j + 1/2) / H).
    // Biquadratic: over texel square (i, j) the uniform quadratic B-spline of samples
    // i - 1 .. i + 1 by j - 1 .. j + 1.
    double height(glm::dvec2 uv) const {
        if (!quadratic_) {
            const double x = uv.x * map_.width - 0.5, y = uv.y * map_.height - 0.5;
            const double i = std::floor(x), j = std::floor(y);
            return bilinear(i, j, x - i, y - j);
        }
        const double x = uv.x * map_.width, y = uv.y * map_.height;
        const double i = std::floor(x), j = std::floor(y);
        const auto weights = [](double f, double w[3]) {  // f in [-1/2, 1/2]
            w[0] = 0.5 * (0.5 - f) * (0.5 - f);
            w[1] = 0.75 - f * f;
            w[2] = 0.5 * (0.5 + f) * (0.5 + f);
        };
        double wx[3], wy[3];
        weights(x - i - 0.5, wx);
        weights(y - j - 0.5, wy);
        double h = 0.0;
        for (int b = 0; b < 3; ++b)
            for (int a = 0; a < 3; ++a) h += wx[a] * wy[b] * sample(i - 1 + a, j - 1 + b);
        return h;
    }

    // (dh/du, dh/dv) at uv: the derivative of the patch that height() evaluates there (on a
    // bilinear cell's edge, where h has a kink, the cell height() reads: its floor).
    glm::dvec2 gradient(glm::dvec2 uv) const {
        if (!quadratic_) {
            const double x = uv.x * map_.width - 0.5, y = uv.y * map_.height - 0.5;
            const double i = std::floor(x), j = std::floor(y), fx = x - i, fy = y - j;
            const double h00 = sample(i, j), h10 = sample(i + 1, j);
            const double h01 = sample(i, j + 1), h11 = sample(i + 1, j + 1);
            return {map_.width * ((1.0 - fy) * (h10 - h00) + fy * (h11 - h01)),
                    map_.height * ((1.0 - fx) * (h01 - h00) + fx * (h11 - h10))};
        }
        const double x = uv.x * map_.width, y = uv.y * map_.height;
        const double i = std::floor(x), j = std::floor(y);
        const double fx = x - i - 0.5, fy = y - j - 0.5;
        // The weights of height() and their derivatives in f.
        const double wx[3] = {0.5 * (0.5 - fx) * (0.5 - fx), 0.75 - fx * fx,
                              0.5 * (0.5 + fx) * (0.5 + fx)};
        const double wy[3] = {0.5 * (0.5 - fy) * (0.5 - fy), 0.75 - fy * fy,
                              0.5 * (0.5 + fy) * (0.5 + fy)};
        const double dx[3] = {fx - 0.5, -2.0 * fx, 0.5 + fx};
        const double dy[3] = {fy - 0.5, -2.0 * fy, 0.5 + fy};
        glm::dvec2 g(0.0);
        for (int b = 0; b < 3; ++b) {
            for (int a = 0; a < 3; ++a) {
                const double h = sample(i - 1 + a, j - 1 + b);
                g.x += dx[a] * wy[b] * h;
                g.y += wx[a] * dy[b] * h;
            }
        }
        return {map_.width * g.x, map_.height * g.y};
    }

    // An upper bound of h over the uv rectangle [lo, hi], never below it: the exact max
    // for bilinear cells (a bilinear patch is linear along each axis, so it peaks at a
    // corner of the rectangle's part in each cell); the largest point of the Bezier net of
    // each biquadratic square's part (a Bezier patch lies in its net's convex hull), which
    // converges to the max as the rectangle shrinks. The largest sample beyond
    // kMaxCellsBounded cells, or for a rectangle that is not finite.
    double maxOver(glm::dvec2 lo, glm::dvec2 hi) const {
        const double shift = quadratic_ ? 0.0 : 0.5;
        const double x0 = lo.x * map_.width - shift, x1 = hi.x * map_.width - shift;
        const double y0 = lo.y * map_.height - shift, y1 = hi.y * map_.height - shift;
        if (!(x0 <= x1 && y0 <= y1) || !std::isfinite(x1 - x0) || !std::isfinite(y1 - y0))
            return largest_;
        const double i0 = std::floor(x0), i1 = std::floor(x1);
        const double j0 = std::floor(y0), j1 = std::floor(y1);
        if ((i1 - i0 + 1.0) * (j1 - j0 + 1.0) > kMaxCellsBounded) return largest_;
        double best = -kInfinity;
        for (double j = j0; j <= j1; j += 1.0) {
            const double fy0 = std::clamp(y0 - j, 0.0, 1.0), fy1 = std::clamp(y1 - j, 0.0, 1.0);
            for (double i = i0; i <= i1; i += 1.0) {
                const double fx0 = std::clamp(x0 - i, 0.0, 1.0);
                const double fx1 = std::clamp(x1 - i, 0.0, 1.0);
                best = std::max(
                    best, quadratic_
                              ? netMax(i, j, fx0, fx1, fy0, fy1)
                              : std::max({bilinear(i, j, fx0, fy0), bilinear(i, j, fx1, fy0),
                                          bilinear(i, j, fx0, fy1), bilinear(i, j, fx1, fy1)}));
            }
        }
        return best;
    }

private:
    // Repeat in both directions.
    double sample(double i, double j) const {
        if (!std::isfinite(i) || !std::isfinite(j)) return largest_;
        const double w = map_.width, h = map_.height;
        const double ii = i - w * std::floor(i / w), jj = j - h * std::floor(j / h);
        return map_.at(std::min(static_cast<int>(ii), map_.width - 1),
                       std::min(static_cast<int>(jj), map_.height - 1));
    }
    // Cell (i, j) between samples i, i + 1 and j, j + 1, at local (fx, fy) in [0, 1]^2.
    double bilinear(double i, double j, double fx, double fy) const {
        const double h00 = sample(i, j), h10 = sample(i + 1, j);
        const double h01 = sample(i, j + 1), h11 = sample(i + 1, j + 1);
        return (1.0 - fy) * ((1.0 - fx) * h00 + fx * h10) + fy * ((1.0 - fx) * h01 + fx * h11);
    }
    // The largest point of the Bezier net of square (i, j) restricted to local
    // [fx0, fx1] x [fy0, fy1] (local f = X - i in [0, 1]). In one direction the B-spline
    // segment of control points c0, c1, c2 is the quadratic Bezier of points
    // (c0 + c1) / 2, c1, (c1 + c2) / 2; its part over [a, b] has the points p(a), the
    // blossom p(a, b) and p(b). The tensor product does it in x, then in y.
    double netMax(double i, double j, double fx0, double fx1, double fy0, double fy1) const {
        const auto restrict = [](const double c[3], double a, double b, double out[3]) {
            const double p0 = 0.5 * (c[0] + c[1]), p1 = c[1], p2 = 0.5 * (c[1] + c[2]);
            const auto blossom = [&](double x, double y) {
                return (1 - x) * (1 - y) * p0 + ((1 - x) * y + x * (1 - y)) * p1 + x * y * p2;
            };
            out[0] = blossom(a, a);
            out[1] = blossom(a, b);
            out[2] = blossom(b, b);
        };
        double rows[3][3];  // rows[b][k]: row j - 1 + b restricted in x, point k
        for (int b = 0; b < 3; ++b) {
            const double c[3] = {sample(i - 1, j - 1 + b), sample(i, j - 1 + b),
                                 sample(i + 1, j - 1 + b)};
            restrict(c, fx0, fx1, rows[b]);
        }
        double best = -kInfinity;
        for (int k = 0; k < 3; ++k) {
            const double c[3] = {rows[0][k], rows[1][k], rows[2][k]};
            double net[3];
            restrict(c, fy0, fy1, net);
            best = std::max({best, net[0], net[1], net[2]});
        }
        return best;
    }

    HeightMap map_;
    bool quadratic_;
    double largest_ = 0.0;
};

// ---- Polynomials in t of degree <= 4 ----

struct Poly {
    std::array<double, 5> c{};  // c[k] t^k

    int degree() const {
        for (int k = 4; k >= 0; --k)
            if (c[k] != 0.0) return k;
        return -1;
    }
    double operator()(double t) const {
        double v = 0.0;
        for (int k = 4; k >= 0; --k) v = v * t + c[k];
        return v;
    }
    Poly derivative() const {
        Poly d;
        for (int k = 1; k < 5; ++k) d.c[k - 1] = k * c[k];
        return d;
    }
};

Poly operator-(Poly a, const Poly& b) {
    for (int k = 0; k < 5; ++k) a.c[k] -= b.c[k];
    return a;
}
Poly operator+(Poly a, const Poly& b) {
    for (int k = 0; k < 5; ++k) a.c[k] += b.c[k];
    return a;
}
Poly operator*(double s, Poly a) {
    for (double& x : a.c) x *= s;
    return a;
}
Poly operator*(const Poly& a, const Poly& b) {
    assert(a.degree() + b.degree() <= 4);
    Poly p;
    for (int i = 0; i < 5; ++i)
        for (int j = 0; i + j < 5; ++j) p.c[i + j] += a.c[i] * b.c[j];
    return p;
}
// p' q - p q': zero where p / q turns.
Poly turning(const Poly& p, const Poly& q) {
    return p.derivative() * q - p * q.derivative();
}

// Vector polynomials: linear a + b t and quadratic a + b t + c t^2.
struct Linear3 {
    glm::dvec3 a, b;
};
struct Quadratic3 {
    glm::dvec3 a, b, c;
};
Quadratic3 cross(const Linear3& p, const Linear3& q) {
    return {glm::cross(p.a, q.a), glm::cross(p.a, q.b) + glm::cross(p.b, q.a),
            glm::cross(p.b, q.b)};
}
Poly dot(const Quadratic3& m, const glm::dvec3& v) {
    return {{glm::dot(m.a, v), glm::dot(m.b, v), glm::dot(m.c, v), 0.0, 0.0}};
}
Poly dot(const Quadratic3& m, const Linear3& l) {
    return {{glm::dot(m.a, l.a), glm::dot(m.a, l.b) + glm::dot(m.b, l.a),
             glm::dot(m.b, l.b) + glm::dot(m.c, l.a), glm::dot(m.c, l.b), 0.0}};
}
Poly dot(const Linear3& p, const Linear3& q) {
    return {{glm::dot(p.a, q.a), glm::dot(p.a, q.b) + glm::dot(p.b, q.a), glm::dot(p.b, q.b), 0.0,
             0.0}};
}

// p / (t - r), the remainder dropped: p less its root r.
Poly deflate(const Poly& p, double r) {
    Poly q;
    for (int k = 3; k >= 0; --k) q.c[k] = p.c[k + 1] + r * q.c[k + 1];
    return q;
}

// A root of p in [l, r], where p is monotone there and p(l), p(r) differ in sign:
// bisection down to `width`.
double bisectMonotone(const Poly& p, double l, double r, double width) {
    const bool risingToPositive = p(l) < 0.0;
    while (r - l > width) {
        const double m = 0.5 * (l + r);
        if (m <= l || m >= r) break;
        const double pm = p(m);
        if (pm == 0.0) return m;
        ((pm < 0.0) == risingToPositive ? l : r) = m;
    }
    return 0.5 * (l + r);
}

// Appends the t in [lo, hi] where p is zero or changes sign, in increasing order (a root
// may appear twice). Between consecutive roots of p' (found the same way) p is monotone,
// so each such stretch has at most one root, bracketed by a sign change; a zero at a stop
// (a double root, or one at an end) is taken as it is.
void appendRoots(const Poly& p, double lo, double hi, std::vector<double>& out) {
    const int degree = p.degree();
    if (degree <= 0) return;  // a constant: no isolated root
    const double width = 4e-16 * std::max({std::abs(lo), std::abs(hi), hi - lo});
    std::vector<double> stops{lo};
    if (degree >= 2) appendRoots(p.derivative(), lo, hi, stops);
    stops.push_back(hi);
    for (std::size_t k = 0; k + 1 < stops.size(); ++k) {
        const double l = stops[k], r = stops[k + 1];
        if (r <= l) continue;
        const double pl = p(l), pr = p(r);
        if (pl == 0.0) out.push_back(l);
        if ((pl < 0.0 && pr > 0.0) || (pl > 0.0 && pr < 0.0))
            out.push_back(bisectMonotone(p, l, r, width));
    }
    if (p(hi) == 0.0) out.push_back(hi);
}

// ---- One triangle's prism ----

struct Prism {
    glm::dvec3 p0, e1, e2;  // P_0, P_1 - P_0, P_2 - P_0
    glm::dvec3 n0, f1, f2;  // N_0, N_1 - N_0, N_2 - N_0
    glm::dvec2 t0, dt1, dt2;
    glm::dvec3 altitude;  // distance from vertex i to the line of the opposite edge (t = 0)
    double top = 0.0;     // >= h over the triangle's uv rectangle
    glm::dvec3 boxLo, boxHi;
};

// A point of a triangle's curve: ray parameter mu (from the box entry), height t, b, uv.
struct ArcPoint {
    double mu = 0.0, t = 0.0;
    glm::dvec3 b{0.0};
    glm::dvec2 uv{0.0};
};

// One monotone piece of the ray's preimage in a triangle: the curve over the t bracket
// [tA, tB] (mu from muA to muB, monotone), or the ray in the offset plane of height tA
// (`level`, b linear in mu). Searched over [muLo, muHi].
struct Piece {
    bool level = false;
    double tA = 0.0, tB = 0.0, muA = 0.0, muB = 0.0;
    double muLo = 0.0, muHi = 0.0;
};

// The ray against one triangle's prism.
class RayInPrism {
public:
    RayInPrism(const Prism& prism, double s, const HeightSurface& surface, const glm::dvec3& origin,
               const glm::dvec3& direction, double muMax, double muTolerance)
        : prism_(prism),
          s_(s),
          surface_(surface),
          o_(origin - prism.p0),
          v_(direction),
          muMax_(muMax),
          muTolerance_(muTolerance) {
        const Linear3 a1{prism.e1, s * prism.f1}, a2{prism.e2, s * prism.f2};
        m_ = cross(a1, a2);
        c_ = dot(m_, v_);
        num_ = dot(m_, Linear3{-o_, s * prism.n0});
        const Linear3 rest{o_, -s * prism.n0};  // O - (Q(t) - P_0)
        n1_ = dot(rest, Linear3{glm::cross(prism.e2, v_), s * glm::cross(prism.f2, v_)});
        n2_ = dot(rest, Linear3{glm::cross(v_, prism.e1), s * glm::cross(v_, prism.f1)});
        curveNum_ = num_;
        curveC_ = c_;
        const double top = prism.top;
        mScale_ =
            std::max({glm::length(m_.a), glm::length(m_.b) * top, glm::length(m_.c) * top * top});
    }

    // The first point of the prism's solid with mu in [0, min(muMax, muBest)), or nothing.
    std::optional<ArcPoint> first(double muBest) {
        std::vector<Piece> pieces = cut();
        std::sort(pieces.begin(), pieces.end(),
                  [](const Piece& a, const Piece& b) { return a.muLo < b.muLo; });
        std::optional<ArcPoint> best;
        for (const Piece& piece : pieces) {
            if (piece.muLo >= muBest) break;
            if (const auto hit = search(piece, muBest)) {
                muBest = hit->mu;
                best = hit;
            }
        }
        return best;
    }

    // b by projection of Y(mu) - Q(t) on the offset plane of height t (the least-squares
    // solve of b_1 A_1 + b_2 A_2 = Y - Q, exact when the point is on the plane): its error
    // is that of the triangle's shape, not of c.
    ArcPoint at(double mu, double t) const {
        const glm::dvec3 w = o_ + mu * v_ - s_ * t * prism_.n0;
        const glm::dvec3 a1 = prism_.e1 + s_ * t * prism_.f1, a2 = prism_.e2 + s_ * t * prism_.f2;
        const double g11 = glm::dot(a1, a1), g12 = glm::dot(a1, a2), g22 = glm::dot(a2, a2);
        const double r1 = glm::dot(a1, w), r2 = glm::dot(a2, w);
        const double det = g11 * g22 - g12 * g12;  // |A_1 x A_2|^2
        ArcPoint p;
        p.mu = mu;
        p.t = t;
        const double b1 = (g22 * r1 - g12 * r2) / det, b2 = (g11 * r2 - g12 * r1) / det;
        p.b = {1.0 - b1 - b2, b1, b2};
        p.uv = prism_.t0 + b1 * prism_.dt1 + b2 * prism_.dt2;
        return p;
    }

private:
    // The monotone pieces of the ray's preimage with t in [0, top], mu in [0, muMax].
    std::vector<Piece> cut() {
        std::vector<Piece> pieces;
        if (c_.degree() < 0) {
            // Parallel to every offset plane: the ray meets none of them but those it lies
            // in, at the roots of num (not a focal one: there the determinant is 0 at every
            // point).
            std::vector<double> roots;
            appendRoots(num_, 0.0, prism_.top, roots);
            roots.erase(std::unique(roots.begin(), roots.end()), roots.end());
            for (double t : roots)
                if (!focal(t)) pieces.push_back(levelPiece(t));
            return pieces;
        }
        const std::vector<double> stops = commonRootsAndStops(pieces);
        for (std::size_t k = 0; k + 1 < stops.size(); ++k) {
            if (const auto p = curvePiece(stops[k], stops[k + 1])) pieces.push_back(*p);
        }
        return pieces;
    }

    double normalAt(double t) const { return glm::length(m_.a + t * (m_.b + t * m_.c)); }
    // At a focal height the offset triangle is a segment or a point (m = 0: an inward
    // tube's normal lines all cross its axis at t = R / s); 1e-12 of its area or less.
    bool focal(double t) const { return normalAt(t) <= 1e-12 * mScale_; }

    Piece levelPiece(double t) const {
        Piece p;
        p.level = true;
        p.tA = p.tB = t;
        p.muLo = 0.0;
        p.muHi = muMax_;
        return p;
    }

    // Where the t range is cut (sorted), after the common roots tc of num and c are taken
    // out: the ray lies in the offset plane of height tc (to the tolerance: its distance
    // |num| / |m|), a level piece, or tc is a focal height, where num - mu c vanishes for
    // every mu. Either way the factor t - tc is divided out of both, so that each piece's
    // bracket holds one root for each mu.
    std::vector<double> commonRootsAndStops(std::vector<Piece>& pieces) {
        const double top = prism_.top;
        std::vector<double> cRoots;
        appendRoots(c_, 0.0, top, cRoots);
        cRoots.erase(std::unique(cRoots.begin(), cRoots.end()), cRoots.end());
        for (double t : cRoots) {
            const bool inPlane =
                !focal(t) && std::abs(num_(t)) <= muTolerance_ * glm::length(v_) * normalAt(t);
            if (inPlane) pieces.push_back(levelPiece(t));
            if (inPlane || focal(t)) {
                curveNum_ = deflate(curveNum_, t);
                curveC_ = deflate(curveC_, t);
            }
        }
        std::vector<double> stops{0.0, top};
        stops.insert(stops.end(), cRoots.begin(), cRoots.end());
        appendRoots(curveC_.derivative(), 0.0, top, stops);
        appendRoots(turning(curveNum_, curveC_), 0.0, top, stops);  // folds: lambda(t) turns
        const Poly n0 = c_ - n1_ - n2_;
        appendRoots(turning(n0, c_), 0.0, top, stops);
        appendRoots(turning(n1_, c_), 0.0, top, stops);
        appendRoots(turning(n2_, c_), 0.0, top, stops);
        const Poly qu = prism_.dt1.x * n1_ + prism_.dt2.x * n2_;
        const Poly qv = prism_.dt1.y * n1_ + prism_.dt2.y * n2_;
        appendRoots(turning(qu, c_), 0.0, top, stops);
        appendRoots(turning(qv, c_), 0.0, top, stops);
        std::sort(stops.begin(), stops.end());
        stops.erase(std::unique(stops.begin(), stops.end()), stops.end());
        return stops;
    }

    // The piece of the curve over [tA, tB] (consecutive stops), if it meets the box.
    std::optional<Piece> curvePiece(double tA, double tB) const {
        if (!(tB > tA)) return std::nullopt;
        // An end at a focal height (b undefined there) is moved into the piece, out of the
        // band |t - tc| < 1e-12 top or so where focal() holds; a piece inside that band is
        // a ray within rounding of the focal segment, and dropped.
        const double hair = std::max(1e-9 * (tB - tA), 4e-12 * prism_.top);
        if (focal(tA)) tA += hair;
        if (focal(tB)) tB -= hair;
        if (!(tB > tA) || focal(tA) || focal(tB)) return std::nullopt;
        const double cInside = curveC_(0.5 * (tA + tB));  // c keeps one sign inside
        if (cInside == 0.0) return std::nullopt;
        Piece p;
        p.tA = tA;
        p.tB = tB;
        p.muA = lambdaAtEnd(tA, cInside);
        p.muB = lambdaAtEnd(tB, cInside);
        p.muLo = std::max(std::min(p.muA, p.muB), 0.0);
        p.muHi = std::min(std::max(p.muA, p.muB), muMax_);
        if (!(p.muLo <= p.muHi)) return std::nullopt;  // off the box (or not finite)
        return p;
    }

    // lambda at a piece's end. Where c is 0 there or has the other sign than inside, the
    // end is a pole of lambda (a root of c, found to the last bit, may lie a hair on either
    // side of the true one): lambda there is the infinity num / c tends to from inside.
    double lambdaAtEnd(double t, double cInside) const {
        const double c = curveC_(t);
        if (c != 0.0 && (c > 0.0) == (cInside > 0.0)) return curveNum_(t) / c;
        const double num = curveNum_(t);
        if (num == 0.0) return std::numeric_limits<double>::quiet_NaN();
        return (num > 0.0) == (cInside > 0.0) ? kInfinity : -kInfinity;
    }

    // t on the piece at mu: the root of num - mu c in the piece's bracket (Illinois, with a
    // bisection every fourth step so that the bracket at least halves).
    double heightAt(const Piece& piece, double mu) const {
        if (piece.level) return piece.tA;
        if (mu == piece.muA) return piece.tA;
        if (mu == piece.muB) return piece.tB;
        const auto f = [&](double t) { return curveNum_(t) - mu * curveC_(t); };
        double a = piece.tA, b = piece.tB, fa = f(a), fb = f(b);
        if (fa == 0.0) return a;
        if (fb == 0.0) return b;
        if ((fa > 0.0) == (fb > 0.0)) return std::abs(fa) <= std::abs(fb) ? a : b;
        const double width = 4e-16 * std::max(prism_.top, std::abs(b));
        int side = 0;
        for (int k = 0; k < 400 && b - a > width; ++k) {
            double m = (a * fb - b * fa) / (fb - fa);
            if (k % 4 == 3 || !(m > a && m < b)) m = 0.5 * (a + b);
            if (m <= a || m >= b) break;
            const double fm = f(m);
            if (fm == 0.0) return m;
            if ((fm > 0.0) == (fa > 0.0)) {
                a = m;
                fa = fm;
                if (side == -1) fb *= 0.5;
                side = -1;
            } else {
                b = m;
                fb = fm;
                if (side == 1) fa *= 0.5;
                side = 1;
            }
        }
        return std::abs(fa) <= std::abs(fb) ? a : b;
    }

    ArcPoint point(const Piece& piece, double mu) const { return at(mu, heightAt(piece, mu)); }

    // Whether no point of the stretch between a and b (on one piece: t, b, u and v
    // monotone, so each between its values at a and b) can lie in the prism's solid.
    bool excluded(const ArcPoint& a, const ArcPoint& b) const {
        for (int i = 0; i < 3; ++i)
            if (a.b[i] < 0.0 && b.b[i] < 0.0) return true;  // outside the triangle
        const double lowest = std::min(a.t, b.t);
        return lowest > surface_.maxOver(glm::min(a.uv, b.uv), glm::max(a.uv, b.uv));
    }

    // The first point of the solid on the piece before muBest: its stretches bisected
    // near half first, the excluded ones dropped; the first left at the tolerance.
    std::optional<ArcPoint> search(const Piece& piece, double muBest) const {
        const double hi = std::min(piece.muHi, muBest);
        if (!(piece.muLo <= hi)) return std::nullopt;
        std::vector<std::pair<ArcPoint, ArcPoint>> stack{
            {point(piece, piece.muLo), point(piece, hi)}};
        for (int examined = 0; !stack.empty(); ++examined) {
            const auto [a, b] = stack.back();
            stack.pop_back();
            if (excluded(a, b)) continue;
            const double mid = 0.5 * (a.mu + b.mu);
            if (b.mu - a.mu <= muTolerance_ || mid <= a.mu || mid >= b.mu ||
                examined >= kMaxStretches)
                return a;
            const ArcPoint m = point(piece, mid);
            stack.push_back({m, b});  // the far half after the near one
            stack.push_back({a, m});
        }
        return std::nullopt;
    }

    const Prism& prism_;
    double s_;
    const HeightSurface& surface_;
    glm::dvec3 o_, v_;
    double muMax_, muTolerance_;
    Quadratic3 m_;
    Poly c_, num_, n1_, n2_;
    Poly curveC_, curveNum_;  // c and num less their common roots (cut())
    double mScale_ = 0.0;     // the largest |m| a term of m(t) could reach over [0, top]
};

// The closed ray-box slab test: the parameter interval inside [lo, hi], if any.
std::optional<glm::dvec2> clipToBox(const Ray& ray, const glm::dvec3& lo, const glm::dvec3& hi) {
    double enter = -kInfinity, leave = kInfinity;
    for (int k = 0; k < 3; ++k) {
        const double o = ray.origin[k], d = ray.direction[k];
        if (d == 0.0) {
            if (o < lo[k] || o > hi[k]) return std::nullopt;
            continue;
        }
        const double a = (lo[k] - o) / d, b = (hi[k] - o) / d;
        enter = std::max(enter, std::min(a, b));
        leave = std::min(leave, std::max(a, b));
    }
    if (enter > leave || leave < 0.0) return std::nullopt;
    return glm::dvec2(std::max(enter, 0.0), leave);
}

// The outward unit normal at a hit of surface Top, Base, Wall or Fold (MeshHit::normal),
// from the hit's b, t (the contract's) and uv. Each surface is a level set of a function
// of the prism's coordinates (b, t), whose gradient in space is the normal; its sign is
// where that function leaves the solid.
glm::dvec3 outwardNormal(const Prism& p, double s, const HeightSurface& surface, const MeshHit& hit,
                         int wall, const glm::dvec3& rayDirection) {
    const glm::dvec3 b = hit.barycentric;
    const double t = hit.height;
    const glm::dvec3 along = p.n0 + b.y * p.f1 + b.z * p.f2;  // D(b): dX/dt = s D
    // The offset triangle's edges at height t: dX/db_k at fixed t (k = 1, 2, b_0 the rest).
    const glm::dvec3 a1 = p.e1 + s * t * p.f1, a2 = p.e2 + s * t * p.f2;
    // n oriented so that n . w < 0 for a w pointing into the solid; as a unit vector.
    const auto facing = [](glm::dvec3 n, const glm::dvec3& into) {
        if (glm::dot(n, into) > 0.0) n = -n;
        const double length = glm::length(n);
        return length > 0.0 ? n / length : n;
    };
    switch (hit.surface) {
        case MeshSurface::Top: {
            // The top X(b, h(uv(b))): dX/db_k = A_k + s (dh/db_k) D, dh/db_k = grad h . dT_k
            // (A_k = E_k + s h F_k, t = h on it). Its normal is the gradient of
            // t - h(uv(b)) in space, which grows along dX/dt = s D (moving up at fixed b
            // leaves the solid): -D points into it.
            const glm::dvec2 g = surface.gradient(hit.uv);
            const glm::dvec3 d1 = a1 + s * glm::dot(g, p.dt1) * along;
            const glm::dvec3 d2 = a2 + s * glm::dot(g, p.dt2) * along;
            return facing(glm::cross(d1, d2), -along);
        }
        case MeshSurface::Base:
            // The mesh itself, t = 0, the plane of E_1 and E_2; the solid is at t > 0, up
            // along D.
            return facing(glm::cross(p.e1, p.e2), along);
        case MeshSurface::Wall: {
            // The side wall b_i = 0 (i = `wall`), the ruled surface between the offset
            // corners Q_j(t), Q_k(t) of the other two vertices (Q_v = P_v + s t N_v):
            // X(w, t) = (1 - w) Q_j + w Q_k, w = b_k. Its normal is the gradient of b_i,
            // which grows towards Q_i at fixed t: from the wall into the triangle.
            const int i = wall;
            const glm::dvec3 q[3] = {p.p0 + s * t * p.n0, p.p0 + a1 + s * t * p.n0,
                                     p.p0 + a2 + s * t * p.n0};
            const int j = (i + 1) % 3, k = (i + 2) % 3;
            const double w = b[j] + b[k] > 0.0 ? b[k] / (b[j] + b[k]) : 0.5;
            const glm::dvec3 nj = j == 0 ? p.n0 : p.n0 + (j == 1 ? p.f1 : p.f2);
            const glm::dvec3 nk = k == 0 ? p.n0 : p.n0 + (k == 1 ? p.f1 : p.f2);
            const glm::dvec3 onWall = (1.0 - w) * q[j] + w * q[k];
            return facing(glm::cross(q[k] - q[j], (1.0 - w) * nj + w * nk), q[i] - onWall);
        }
        case MeshSurface::Fold: {
            // The envelope of the offset triangles, where X(b, t) is singular: the Jacobian
            // (A_1, A_2, s D) has rank 2 there, and the envelope's tangent plane is its
            // range, normal to each cross product of two of its columns (all parallel at
            // rank 2: the longest is the best conditioned). Which side the folded sheets
            // cover is a second-order matter; the ray enters the solid there (the hit is
            // its first point), so the outward side is the one the ray comes from.
            const glm::dvec3 c[3] = {glm::cross(a1, a2), glm::cross(a2, along),
                                     glm::cross(along, a1)};
            glm::dvec3 n = c[0];
            for (const glm::dvec3& x : c)
                if (glm::length(x) > glm::length(n)) n = x;
            return facing(n, rayDirection);
        }
        default:
            return glm::dvec3(0.0);  // Inside: the origin; no surface there
    }
}

}  // namespace

struct MeshReference::Data {
    HeightSurface surface;
    double s;
    std::vector<Prism> prisms;
    double diagonal = 1.0;  // of the box of all prisms
    double tolerance = 0.0;
};

MeshReference::MeshReference(const TriangleMesh& mesh, const HeightMap& map, double heightScale,
                             Interpolation interpolation)
    : data_(std::make_unique<Data>(
          Data{HeightSurface(map, interpolation), heightScale, {}, 1.0, 0.0})) {
    assert(heightScale >= 0.0 && std::isfinite(heightScale));
    glm::dvec3 lo(kInfinity), hi(-kInfinity);
    for (const glm::uvec3& tri : mesh.triangles) {
        Prism p;
        const glm::dvec3 P[3] = {mesh.positions[tri[0]], mesh.positions[tri[1]],
                                 mesh.positions[tri[2]]};
        const glm::dvec3 N[3] = {mesh.normals[tri[0]], mesh.normals[tri[1]], mesh.normals[tri[2]]};
        const glm::dvec2 T[3] = {mesh.texCoords[tri[0]], mesh.texCoords[tri[1]],
                                 mesh.texCoords[tri[2]]};
        p.p0 = P[0];
        p.e1 = P[1] - P[0];
        p.e2 = P[2] - P[0];
        p.n0 = N[0];
        p.f1 = N[1] - N[0];
        p.f2 = N[2] - N[0];
        p.t0 = T[0];
        p.dt1 = T[1] - T[0];
        p.dt2 = T[2] - T[0];
        const double twiceArea = glm::length(glm::cross(p.e1, p.e2));
        for (int i = 0; i < 3; ++i)
            p.altitude[i] = twiceArea / glm::length(P[(i + 2) % 3] - P[(i + 1) % 3]);
        // Not 0 where the map is 0 over the triangle (its solid is then the triangle):
        // the search needs a t range, and the bound keeps t > 0 out of the solid.
        const double largest = data_->surface.largest();
        p.top = std::max(data_->surface.maxOver(glm::min(T[0], glm::min(T[1], T[2])),
                                                glm::max(T[0], glm::max(T[1], T[2]))),
                         largest > 0.0 ? 1e-9 * largest : 1e-9);
        p.boxLo = glm::dvec3(kInfinity);
        p.boxHi = glm::dvec3(-kInfinity);
        for (int i = 0; i < 3; ++i) {
            for (const glm::dvec3& corner : {P[i], P[i] + heightScale * p.top * N[i]}) {
                p.boxLo = glm::min(p.boxLo, corner);
                p.boxHi = glm::max(p.boxHi, corner);
            }
        }
        lo = glm::min(lo, p.boxLo);
        hi = glm::max(hi, p.boxHi);
        data_->prisms.push_back(p);
    }
    const double diagonal = data_->prisms.empty() ? 1.0 : glm::length(hi - lo);
    data_->diagonal = diagonal;
    data_->tolerance = kTolerance * diagonal;
    for (Prism& p : data_->prisms) {
        p.boxLo -= glm::dvec3(kBoxPadding * diagonal);
        p.boxHi += glm::dvec3(kBoxPadding * diagonal);
    }
}

MeshReference::~MeshReference() = default;
MeshReference::MeshReference(MeshReference&&) noexcept = default;
MeshReference& MeshReference::operator=(MeshReference&&) noexcept = default;

double MeshReference::tolerance() const {
    return data_->tolerance;
}

MeshHit MeshReference::trace(const Ray& ray) const {
    const Data& d = *data_;
    const double speed = glm::length(ray.direction);
    assert(speed > 0.0);
    const double muTolerance = d.tolerance / speed;

    // The triangles whose boxes the ray meets, in the order it enters them.
    struct Candidate {
        std::size_t index;
        glm::dvec2 span;
    };
    std::vector<Candidate> candidates;
    for (std::size_t k = 0; k < d.prisms.size(); ++k) {
        if (const auto span = clipToBox(ray, d.prisms[k].boxLo, d.prisms[k].boxHi))
            candidates.push_back({k, *span});
    }
    std::sort(candidates.begin(), candidates.end(),
              [](const Candidate& a, const Candidate& b) { return a.span.x < b.span.x; });

    double best = kInfinity;
    std::size_t bestIndex = 0;
    ArcPoint bestPoint;
    for (const Candidate& c : candidates) {
        if (c.span.x >= best) break;
        const glm::dvec3 origin = ray.origin + c.span.x * ray.direction;
        RayInPrism solve(d.prisms[c.index], d.s, d.surface, origin, ray.direction,
                         c.span.y - c.span.x, muTolerance);
        if (const auto hit = solve.first(best - c.span.x)) {
            best = c.span.x + hit->mu;
            bestIndex = c.index;
            bestPoint = *hit;
        }
    }
    if (best == kInfinity) return {};

    // The hit, b clamped into the triangle and t into [0, h], named by the constraint
    // closest to holding with equality there (each as a distance in the mesh's units).
    const Prism& p = d.prisms[bestIndex];
    MeshHit hit;
    hit.t = best;
    hit.position = ray.origin + best * ray.direction;
    hit.triangle = bestIndex;
    glm::dvec3 b = glm::max(bestPoint.b, glm::dvec3(0.0));
    b /= b.x + b.y + b.z;
    hit.barycentric = b;
    hit.uv = p.t0 + b.y * p.dt1 + b.z * p.dt2;
    const double h = d.surface.height(hit.uv);
    hit.height = std::clamp(bestPoint.t, 0.0, h);
    if (best == 0.0) {
        hit.surface = MeshSurface::Inside;
        return hit;
    }
    const glm::dvec3 normal = p.n0 + b.y * p.f1 + b.z * p.f2;  // D(b): t grows along it
    const double unitHeight = d.s * glm::length(normal);
    const double base = std::abs(bestPoint.t) * unitHeight;
    const double top = std::abs(h - bestPoint.t) * unitHeight;
    // Where h = 0 the top and the mesh coincide: a ray going up along D comes from below.
    const bool fromBelow = glm::dot(ray.direction, normal) > 0.0;
    const bool baseFirst = std::abs(base - top) <= d.tolerance ? fromBelow : base < top;
    double closest = baseFirst ? base : top;
    hit.surface = baseFirst ? MeshSurface::Base : MeshSurface::Top;
    int wall = 0;
    for (int i = 0; i < 3; ++i) {
        if (const double distance = std::abs(bestPoint.b[i]) * p.altitude[i]; distance < closest) {
            closest = distance;
            hit.surface = MeshSurface::Wall;
            wall = i;
        }
    }
    // None of them holds: the ray came in where the prism folds over itself. (At a fold t
    // is found to about the square root of the tolerance, hence the margin.)
    if (closest > kFoldMargin * d.diagonal) hit.surface = MeshSurface::Fold;
    hit.normal = outwardNormal(p, d.s, d.surface, hit, wall, ray.direction);
    return hit;
}

}  // namespace microrelief
