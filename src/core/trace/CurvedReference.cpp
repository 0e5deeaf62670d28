// The reference tracer on a cylinder or an ellipsoid (core/trace/ReferenceTracer.h), written
// from the spec's definitions alone (scene-and-cli.md, "Base surfaces") and sharing no
// code with the traversal or its base-surface seam (core/base/BaseSurface.h): its own frame
// and map coordinates, its own shell, its own cell walk, its own root search.
//
// In the canonical frame q the ray is a line. The solid is {radial(q) <= 1 + s h(u, v)}
// (and |q.y| <= 1 on the cylinder), radial the distance from the axis or the centre. The
// gap g(t) = 1 + s h(u(t), v(t)) - radial(t) is >= 0 exactly where the ray is in the
// solid; the hit is the first such t.
//
// The walk: every crossing of the ray with every cell boundary of the map (the
// half-planes of constant u through the axis, the planes or cones of constant v), each
// found in closed form, sorted. Between two consecutive crossings the ray stays in one
// cell, named by the point midway, whose bilinear patch is h there. No assumption about
// the order in which cells come is needed. O(W + H) per ray.
//
// The root: on each stretch, bisection, near half first, discarding a piece [a, b] when
// g(mid) + L (b - a) / 2 < 0, with L a Lipschitz bound of g over the piece built from the
// patch's slopes and the speed at which u, v and the radial distance change along the
// ray. Down to a piece of 1e-12 of the ray's span, whose start is reported: the first
// point where contact cannot be excluded, so a touching ray is a hit.
#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <vector>

#include "microrelief/core/trace/ReferenceTracer.h"

namespace microrelief::detail {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Pieces of the bisection examined per stretch before contact is assumed (a ray that
// runs within 1e-9 of the surface over a long stretch); never reached in the tests.
constexpr int kMaxPieces = 200000;

struct Surface {
    const HeightMap& map;
    double s;
    bool cylinder;
    int width, height;
    bool quadratic;  // the biquadratic surface: patches over texel squares, not between samples

    // Where the patches' boundaries lie: between sample centres (bilinear cells, X = i + 1/2)
    // or on texel edges (biquadratic squares, X = i).
    double offset() const { return quadratic ? 0.0 : 0.5; }

    double mapX(const glm::dvec3& q) const {
        const double u = 0.5 + std::atan2(q.x, q.z) / (2.0 * kPi);
        return width * (u - std::floor(u));
    }
    double mapY(const glm::dvec3& q) const {
        if (cylinder) return 0.5 * height * (1.0 - q.y);
        const double r = glm::length(q);
        return r > 0.0 ? height * std::acos(std::clamp(q.y / r, -1.0, 1.0)) / kPi : 0.5 * height;
    }
    double radial(const glm::dvec3& q) const {
        return cylinder ? std::sqrt(q.x * q.x + q.z * q.z) : glm::length(q);
    }
    double sample(int i, int j) const {
        i %= width;
        if (i < 0) i += width;
        return map.at(i, std::clamp(j, 0, height - 1));
    }
};

// The surface over cell (i, j), in local coordinates (fx, fy) in [0, 1]^2 from the cell's
// corner X = i + offset. Bilinear: between samples i, i + 1 (wrapped) and j, j + 1
// (clamped), h00 + e fx + g fy + k fx fy. Biquadratic: texel square (i, j), the B-spline
// sum of samples i - 1..i + 1 by j - 1..j + 1 at f = local - 1/2.
struct Patch {
    bool quadratic = false;
    double h00 = 0, e = 0, g = 0, k = 0;  // bilinear
    double c[3][3] = {};                  // biquadratic, c[b][a]: sample (i - 1 + a, j - 1 + b)

    double height(double fx, double fy) const {
        if (!quadratic) return h00 + e * fx + g * fy + k * fx * fy;
        double wx[3], wy[3];
        quadraticWeights(fx - 0.5, wx);
        quadraticWeights(fy - 0.5, wy);
        double h = 0.0;
        for (int b = 0; b < 3; ++b)
            for (int a = 0; a < 3; ++a) h += wx[a] * wy[b] * c[b][a];
        return h;
    }
    // Bounds of |dh/dfx|, |dh/dfy| over the cell. A bilinear patch's slope along x is
    // linear in fy, extreme at its edges; a quadratic B-spline's derivative is the linear
    // B-spline of the differences of its control points, so no steeper than the largest.
    glm::dvec2 slopes() const {
        if (!quadratic)
            return {std::max(std::abs(e), std::abs(e + k)), std::max(std::abs(g), std::abs(g + k))};
        glm::dvec2 slope(0.0);
        for (int b = 0; b < 3; ++b) {
            for (int a = 0; a < 2; ++a) {
                slope.x = std::max(slope.x, std::abs(c[b][a + 1] - c[b][a]));
                slope.y = std::max(slope.y, std::abs(c[a + 1][b] - c[a][b]));
            }
        }
        return slope;
    }
    // Never exceeded: a bilinear patch peaks at a corner, a B-spline within its control
    // points' range.
    double maxValue() const {
        if (!quadratic) return std::max({h00, h00 + e, h00 + g, h00 + e + g + k});
        double best = c[0][0];
        for (const auto& row : c)
            for (double v : row) best = std::max(best, v);
        return best;
    }
    // (dh/dfx, dh/dfy) at (fx, fy).
    glm::dvec2 gradient(double fx, double fy) const {
        if (!quadratic) return {e + k * fy, g + k * fx};
        double wx[3], wy[3];
        quadraticWeights(fx - 0.5, wx);
        quadraticWeights(fy - 0.5, wy);
        const double f = fx - 0.5, h = fy - 0.5;
        const double dx[3] = {-(0.5 - f), -2.0 * f, 0.5 + f},
                     dy[3] = {-(0.5 - h), -2.0 * h, 0.5 + h};
        glm::dvec2 gradient(0.0);
        for (int b = 0; b < 3; ++b)
            for (int a = 0; a < 3; ++a)
                gradient += c[b][a] * glm::dvec2(dx[a] * wy[b], wx[a] * dy[b]);
        return gradient;
    }
};

Patch patchOf(const Surface& m, int i, int j) {
    Patch p;
    p.quadratic = m.quadratic;
    if (m.quadratic) {
        for (int b = 0; b < 3; ++b)
            for (int a = 0; a < 3; ++a) p.c[b][a] = m.sample(i - 1 + a, j - 1 + b);
        return p;
    }
    const double h00 = m.sample(i, j), h10 = m.sample(i + 1, j);
    const double h01 = m.sample(i, j + 1), h11 = m.sample(i + 1, j + 1);
    p.h00 = h00;
    p.e = h10 - h00;
    p.g = h01 - h00;
    p.k = h00 - h10 - h01 + h11;
    return p;
}

// The line's parameters where a t^2 + b t + c = 0, both roots, by the cancellation-free
// form; 0, 1 or 2 of them.
int solveQuadratic(double a, double b, double c, double roots[2]) {
    if (a == 0.0) {
        if (b == 0.0) return 0;
        roots[0] = -c / b;
        return 1;
    }
    const double disc = b * b - 4.0 * a * c;
    if (disc < 0.0) return 0;
    const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
    roots[0] = q / a;
    if (q == 0.0) return 1;
    roots[1] = c / q;
    return 2;
}

// The interval of t where the line lies within `radius` of the axis (xz only) or the
// centre; empty (x > y) when it never does.
glm::dvec2 withinRadius(glm::dvec3 o, glm::dvec3 d, double radius, bool axis) {
    if (axis) o.y = d.y = 0.0;
    const double a = glm::dot(d, d);
    if (a == 0.0)
        return glm::dot(o, o) <= radius * radius ? glm::dvec2(-kInfinity, kInfinity)
                                                 : glm::dvec2(1.0, -1.0);
    double roots[2];
    if (solveQuadratic(a, 2.0 * glm::dot(o, d), glm::dot(o, o) - radius * radius, roots) < 2)
        return {1.0, -1.0};
    return {std::min(roots[0], roots[1]), std::max(roots[0], roots[1])};
}

// Every t in (t0, t1) at which the line crosses a cell boundary of the map.
std::vector<double> boundaryCrossings(const Surface& m, const CurvedBoundaries& boundaries,
                                      const glm::dvec3& o, const glm::dvec3& d, double t0,
                                      double t1) {
    std::vector<double> crossings;
    const auto keep = [&](double t) {
        if (t > t0 && t < t1) crossings.push_back(t);
    };
    // Where u and v may jump: a line through the axis turns u by half a turn there, one
    // through the centre turns the latitude. Splitting at the nearest points costs nothing
    // where nothing jumps.
    if (const double dd = d.x * d.x + d.z * d.z; dd > 0.0) keep(-(o.x * d.x + o.z * d.z) / dd);
    if (!m.cylinder) keep(-glm::dot(o, d) / glm::dot(d, d));
    // Constant u: the half-plane {lambda (sin phi, *, cos phi), lambda > 0}. The line's
    // point p has (p.x, p.z) = lambda (sin phi, cos phi): solve p.x cos phi = p.z sin phi.
    for (const glm::dvec2& angle : boundaries.u) {
        const double sn = angle.x, cs = angle.y;
        const double rate = d.x * cs - d.z * sn;
        if (rate == 0.0) continue;
        const double t = (o.z * sn - o.x * cs) / rate;
        const glm::dvec3 p = o + t * d;
        if (p.x * sn + p.z * cs > 0.0) keep(t);
    }
    for (const double v : boundaries.v) {
        if (m.cylinder) {
            // Constant v: the plane q.y = 1 - 2 v.
            if (d.y != 0.0) keep((v - o.y) / d.y);
            continue;
        }
        // Constant v: the cone of half-angle theta about +y, q.y = |q| cos theta, written
        // as (q.y)^2 = cos^2 |q|^2 on the nappe where q.y has the sign of cos theta.
        const double cs = v;
        if (std::abs(cs) < 1e-9) {  // the equator: the plane q.y = 0, not a cone
            if (d.y != 0.0) keep(-o.y / d.y);
            continue;
        }
        const double a = d.y * d.y - cs * cs * glm::dot(d, d);
        const double b = 2.0 * (o.y * d.y - cs * cs * glm::dot(o, d));
        const double c = o.y * o.y - cs * cs * glm::dot(o, o);
        double roots[2];
        const int count = solveQuadratic(a, b, c, roots);
        for (int r = 0; r < count; ++r) {
            if ((o.y + roots[r] * d.y) * cs >= 0.0) keep(roots[r]);
        }
    }
    std::sort(crossings.begin(), crossings.end());
    return crossings;
}

// The first t in [a, b] where the ray meets the patch of cell (i, j), or nothing.
struct CellSearch {
    const Surface& m;
    glm::dvec3 o, d;
    int i, j;
    Patch patch;
    double tolerance;

    glm::dvec2 local(double t) const {
        const glm::dvec3 q = o + t * d;
        double fx = m.mapX(q) - (i + m.offset());
        fx -= m.width * std::round(fx / m.width);  // the seam cell
        return {std::clamp(fx, 0.0, 1.0), std::clamp(m.mapY(q) - (j + m.offset()), 0.0, 1.0)};
    }
    double gap(double t) const {
        const glm::dvec2 f = local(t);
        return 1.0 + m.s * patch.height(f.x, f.y) - m.radial(o + t * d);
    }
    // The smallest radial distance over [a, b] (along a line it is convex: its minimum is
    // at the point nearest the axis or centre, or at an end).
    double nearestRadial(double a, double b, bool axisOnly) const {
        glm::dvec3 oo = o, dd = d;
        if (axisOnly) oo.y = dd.y = 0.0;
        const double speed2 = glm::dot(dd, dd);
        const double t = speed2 > 0.0 ? std::clamp(-glm::dot(oo, dd) / speed2, a, b) : a;
        return glm::length(oo + t * dd);
    }
    // A Lipschitz bound of the gap over [a, b]: |dg/dt| <= s (|dh/dfx| |dX/dt| + |dh/dfy|
    // |dY/dt|) + |d radial/dt|, each factor bounded over the piece.
    double lipschitz(double a, double b) const {
        const glm::dvec2 slope = patch.slopes();
        const double slopeX = slope.x, slopeY = slope.y;
        // u = atan2(x, z) / 2 pi: |du/dt| = |z dx - x dz| / (2 pi rho^2), the numerator
        // constant along the line.
        const double moment = std::abs(o.z * d.x - o.x * d.z);
        const double rho = nearestRadial(a, b, true);
        const double speedX = moment == 0.0 ? 0.0 : m.width * moment / (2.0 * kPi * rho * rho);
        const double speedXZ = std::hypot(d.x, d.z), speed = glm::length(d);
        // v: linear along the cylinder's axis. On the ellipsoid the direction w = q / |q|
        // moves on the unit sphere at |q x d| / |q|^2 = |o x d| / r^2 (the cross product is
        // constant along the line), and the polar angle no faster than that.
        const double turning = glm::length(glm::cross(o, d));
        const double r = nearestRadial(a, b, false);
        const double speedY = m.cylinder       ? 0.5 * m.height * std::abs(d.y)
                              : turning == 0.0 ? 0.0
                                               : m.height / kPi * turning / (r * r);
        return m.s * (slopeX * speedX + slopeY * speedY) + (m.cylinder ? speedXZ : speed);
    }

    std::optional<double> first(double a, double b) const {
        // A stretch wholly above its patch's highest corner cannot touch it.
        if (nearestRadial(a, b, m.cylinder) > 1.0 + m.s * patch.maxValue()) return std::nullopt;
        std::vector<glm::dvec2> pieces{{a, b}};
        for (int examined = 0; !pieces.empty(); ++examined) {
            const glm::dvec2 piece = pieces.back();
            pieces.pop_back();
            const double mid = 0.5 * (piece.x + piece.y), half = 0.5 * (piece.y - piece.x);
            // The bound of each piece its own: near the axis u turns fast, away from it
            // slowly, and one bound for the whole stretch would be the axis's.
            if (gap(mid) + lipschitz(piece.x, piece.y) * half < 0.0) continue;  // no contact
            if (2.0 * half <= tolerance || examined >= kMaxPieces) return piece.x;
            pieces.push_back({mid, piece.y});  // the far half after the near one
            pieces.push_back({piece.x, mid});
        }
        return std::nullopt;
    }
};

// The outward normal of the top surface at map point (X, Y), world space: the cross
// product of the surface's partial derivatives along X and Y.
glm::dvec3 topNormal(const Surface& m, const Patch& patch, glm::dvec2 f, double x, double y,
                     const glm::dvec3& scale) {
    const double h = patch.height(f.x, f.y);
    const glm::dvec2 slope = patch.gradient(f.x, f.y);  // per texel
    const double hx = slope.x, hy = slope.y;
    const double radius = 1.0 + m.s * h;
    const double phi = 2.0 * kPi * (x / m.width - 0.5);
    const glm::dvec3 outward(std::sin(phi), 0.0, std::cos(phi)),
        around(std::cos(phi), 0.0, -std::sin(phi));
    glm::dvec3 alongX, alongY, away;
    if (m.cylinder) {
        // q = radius (sin phi, 0, cos phi) + (0, 1 - 2 Y / H, 0).
        alongX = m.s * hx * outward + radius * (2.0 * kPi / m.width) * around;
        alongY = m.s * hy * outward + glm::dvec3(0.0, -2.0 / m.height, 0.0);
        away = outward;
    } else {
        // q = radius w, w = (sin theta sin phi, cos theta, sin theta cos phi).
        const double theta = kPi * y / m.height;
        const glm::dvec3 w(std::sin(theta) * std::sin(phi), std::cos(theta),
                           std::sin(theta) * std::cos(phi));
        const glm::dvec3 wTheta(std::cos(theta) * std::sin(phi), -std::sin(theta),
                                std::cos(theta) * std::cos(phi));
        alongX = m.s * hx * w + radius * std::sin(theta) * (2.0 * kPi / m.width) * around;
        alongY = m.s * hy * w + radius * (kPi / m.height) * wTheta;
        away = w;
    }
    glm::dvec3 n = glm::cross(alongX, alongY);
    if (glm::dot(n, n) == 0.0) n = away;  // a pole: no tangent along X there
    if (glm::dot(n, away) < 0.0) n = -n;
    return glm::normalize(n / scale);
}

}  // namespace

CurvedBoundaries curvedBoundaries(const ReliefGeometry& relief) {
    const HeightMap& map = *relief.map;
    // Bilinear cells end at sample centres, biquadratic squares at texel edges (the
    // poles and the caps, Y = 0 and H, are not crossed).
    const double offset = relief.interpolation == Interpolation::Biquadratic ? 0.0 : 0.5;
    CurvedBoundaries b;
    for (int i = 0; i < map.width; ++i) {
        const double phi = 2.0 * kPi * ((i + offset) / map.width - 0.5);
        b.u.push_back({std::sin(phi), std::cos(phi)});
    }
    for (int j = offset == 0.0 ? 1 : 0; j < map.height; ++j) {
        const double y = j + offset;  // the boundary between cells j - 1 and j
        b.v.push_back(relief.base.kind == BaseKind::Cylinder ? 1.0 - 2.0 * y / map.height
                                                             : std::cos(kPi * y / map.height));
    }
    return b;
}

ReferenceHit traceCurvedReference(const ReliefGeometry& relief, const CurvedBoundaries& boundaries,
                                  const Ray& ray, double top) {
    assert(relief.map != nullptr && !relief.map->empty() && relief.base.curved());
    const HeightMap& map = *relief.map;
    const bool cylinder = relief.base.kind == BaseKind::Cylinder;
    const Surface m{map,        relief.heightScale,
                    cylinder,   map.width,
                    map.height, relief.interpolation == Interpolation::Biquadratic};
    const glm::dvec3 scale = relief.base.frameScale();
    const glm::dvec3 o = ray.origin / scale, d = ray.direction / scale;

    // The shell: within 1 + top of the axis (between the caps) or the centre.
    glm::dvec2 span = withinRadius(o, d, 1.0 + top, cylinder);
    bool throughCap = false;
    if (cylinder) {
        if (d.y == 0.0) {
            if (std::abs(o.y) > 1.0) return {};
        } else {
            const double ta = (-1.0 - o.y) / d.y, tb = (1.0 - o.y) / d.y;
            const double enter = std::min(ta, tb), leave = std::max(ta, tb);
            throughCap = enter >= span.x;
            span = {std::max(span.x, enter), std::min(span.y, leave)};
        }
    }
    if (span.x > span.y || span.y < 0.0) return {};
    ReferenceHit hit;
    hit.entryFace = throughCap && span.x >= 0.0 ? HitFace::Cap : HitFace::None;
    const auto at = [&](double t) { return o + t * d; };
    const auto finish = [&](HitFace face, double t) {
        const glm::dvec3 q = at(t);
        hit.face = face;
        hit.t = t;
        hit.position = ray.origin + t * ray.direction;
        hit.uv = {m.mapX(q) / map.width, m.mapY(q) / map.height};
        return hit;
    };

    // Through a cap: a hit right there when the cap's point lies within the surface's
    // radius over the edge row (v = 0 at the top, 1 at the bottom).
    if (hit.entryFace == HitFace::Cap) {
        const glm::dvec3 q = at(span.x);
        // The edge row's patch: the bilinear cell or biquadratic texel square holding the
        // edge (the last square for v = 1, whose far side the edge is).
        const double x = m.mapX(q), y = q.y > 0.0 ? 0.0 : map.height;
        const int i = static_cast<int>(std::floor(x - m.offset()));
        const int j = std::min(static_cast<int>(std::floor(y - m.offset())), map.height - 1);
        double fx = x - (i + m.offset());
        fx -= map.width * std::round(fx / map.width);
        const double h = patchOf(m, i, j).height(std::clamp(fx, 0.0, 1.0),
                                                 std::clamp(y - (j + m.offset()), 0.0, 1.0));
        if (m.radial(q) <= 1.0 + m.s * h) {
            finish(HitFace::Cap, span.x);
            hit.normal = glm::normalize(glm::dvec3(0.0, q.y > 0.0 ? 1.0 : -1.0, 0.0) / scale);
            return hit;
        }
    }

    const double t0 = std::max(span.x, 0.0), t1 = span.y;
    std::vector<double> stops = boundaryCrossings(m, boundaries, o, d, t0, t1);
    stops.insert(stops.begin(), t0);
    stops.push_back(t1);
    const double tolerance = 1e-12 * std::max(t1 - t0, 1e-300);
    for (std::size_t k = 0; k + 1 < stops.size(); ++k) {
        const double a = stops[k], b = stops[k + 1];
        if (b <= a && !(a == b && stops.size() == 2)) continue;
        const glm::dvec3 mid = at(0.5 * (a + b));
        const double x = m.mapX(mid), y = m.mapY(mid);
        const int i = static_cast<int>(std::floor(x - m.offset()));
        const int j = std::clamp(static_cast<int>(std::floor(y - m.offset())), m.quadratic ? 0 : -1,
                                 map.height - 1);
        const CellSearch cell{m, o, d, i, j, patchOf(m, i, j), tolerance};
        if (const auto t = cell.first(a, b)) {
            finish(HitFace::Top, *t);
            const glm::dvec3 q = at(*t);
            hit.normal = topNormal(m, cell.patch, cell.local(*t), m.mapX(q), m.mapY(q), scale);
            return hit;
        }
    }
    return hit;
}

}  // namespace microrelief::detail
