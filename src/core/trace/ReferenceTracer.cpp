#include "microrelief/core/trace/ReferenceTracer.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

namespace microrelief {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Sample space: the world frame shifted and scaled in x and z so that sample (i, j)
// sits at (x, z) = (i, j), that is texel space (X, Y) minus one half; y stays the world
// height. The footprint is [-0.5, W - 0.5] x [-0.5, H - 0.5]. Bilinear cell (ci, cj) is
// the unit square [ci, ci + 1] x [cj, cj + 1] for ci in [-1, W - 1], cj in [-1, H - 1]:
// the border cells are clipped to half a cell and are flat across the edge, which is
// CLAMP_TO_EDGE. The map is affine, so a ray keeps its parameter t.
struct SampleSpace {
    int width = 0, height = 0;
    double scale = 1.0;  // sample units per world unit: max(W, H)

    glm::dvec3 point(const glm::dvec3& world) const {
        return {world.x * scale + 0.5 * (width - 1), world.y, world.z * scale + 0.5 * (height - 1)};
    }
    glm::dvec3 vector(const glm::dvec3& world) const {
        return {world.x * scale, world.y, world.z * scale};
    }
    // Map uv of a sample-space point.
    glm::dvec2 uv(const glm::dvec3& p) const { return {(p.x + 0.5) / width, (p.z + 0.5) / height}; }
};

// One cell's surface in world height units over local coordinates (fx, fz) in [0, 1]^2:
// h = h00 + e fx + g fz + k fx fz, the bilinear interpolation of its four corner samples.
struct BilinearPatch {
    double h00 = 0.0, e = 0.0, g = 0.0, k = 0.0;
    double maxCorner = 0.0;  // the patch's maximum: a bilinear patch peaks at a corner

    double height(double fx, double fz) const { return h00 + e * fx + g * fz + k * fx * fz; }
    // (dh/dfx, dh/dfz)
    glm::dvec2 gradient(double fx, double fz) const { return {e + k * fz, g + k * fx}; }
};

// `Samples` (here and below): what the walks read of a map, its `width`, `height` and
// `at(i, j)` and `clamped(i, j)` samples as HeightMap has them: a HeightMap, or the samples
// of pages read as the walk needs them (PagedSamples).
template <class Samples>
BilinearPatch cellPatch(const Samples& map, double heightScale, int ci, int cj) {
    const auto sample = [&](int i, int j) {
        return heightScale * static_cast<double>(map.at(std::clamp(i, 0, map.width - 1),
                                                        std::clamp(j, 0, map.height - 1)));
    };
    const double h00 = sample(ci, cj), h10 = sample(ci + 1, cj);
    const double h01 = sample(ci, cj + 1), h11 = sample(ci + 1, cj + 1);
    return {h00, h10 - h00, h01 - h00, h00 - h10 - h01 + h11, std::max({h00, h10, h01, h11})};
}

// The smallest tau in [0, length] with a tau^2 + b tau + c <= 0, if any. The roots use
// the cancellation-free form q = -(b + sign(b) sqrt(b^2 - 4ac)) / 2, roots q/a and c/q.
std::optional<double> firstNonPositive(double a, double b, double c, double length) {
    if (c <= 0.0) return 0.0;
    if (a == 0.0) {
        if (!(b < 0.0)) return std::nullopt;
        const double tau = -c / b;
        return tau <= length ? std::optional(tau) : std::nullopt;
    }
    const double discriminant = b * b - 4.0 * a * c;
    if (discriminant < 0.0) return std::nullopt;  // no real root: f keeps the sign of c > 0
    const double q = -0.5 * (b + std::copysign(std::sqrt(discriminant), b));
    // q != 0 here: q = 0 needs b = 0 and b^2 = 4ac, impossible with c > 0 and a != 0.
    const double r1 = q / a, r2 = c / q;
    const double lo = std::min(r1, r2), hi = std::max(r1, r2);
    if (a > 0.0) {
        // f <= 0 exactly on [lo, hi]; since f(0) = c > 0 both roots lie on one side of 0.
        if (hi < 0.0 || lo > length) return std::nullopt;
        return std::max(lo, 0.0);
    }
    // a < 0: f <= 0 outside (lo, hi), and f(0) > 0 puts 0 between the roots.
    if (hi > length) return std::nullopt;
    return std::max(hi, 0.0);
}

// The first tau in [0, length] at which the ray start + tau dir (sample space, start in
// the patch's local coordinates) lies on or below the patch: z(tau) - h(tau) <= 0 is a
// quadratic in tau because the patch is bilinear and the ray is linear in x and z.
std::optional<double> firstContact(const BilinearPatch& patch, const glm::dvec3& start,
                                   const glm::dvec3& dir, double length) {
    // Exact cull: above the highest corner over the whole span, the ray cannot touch.
    if (std::min(start.y, start.y + dir.y * length) > patch.maxCorner) return std::nullopt;
    const double a = -patch.k * dir.x * dir.z;
    const double b =
        dir.y - (patch.e * dir.x + patch.g * dir.z + patch.k * (start.x * dir.z + start.z * dir.x));
    const double c = start.y - patch.height(start.x, start.z);
    return firstNonPositive(a, b, c, length);
}

// The ray's interval inside the bounding box {x in footprint, 0 <= y <= top} (sample
// space) and the face of the solid it enters through at tEnter: a wall, the bottom, or
// None where it enters through the box's top or starts inside the box (tEnter < 0).
// exitsThroughBottom: it leaves the box through the base plane, downwards.
struct BoxSpan {
    double tEnter = -kInfinity, tExit = kInfinity;
    HitFace entryFace = HitFace::None;
    bool exitsThroughBottom = false;
};

std::optional<BoxSpan> clipToBoundingBox(const glm::dvec3& o, const glm::dvec3& d, int width,
                                         int height, double top) {
    BoxSpan span;
    // Closed slabs: a ray grazing a face or an edge still meets the closed solid there.
    using enum HitFace;
    const auto slab = [&span](double origin, double dir, double lo, double hi, HitFace lowFace,
                              HitFace highFace) {
        if (dir == 0.0) return origin >= lo && origin <= hi;
        const double tLo = (lo - origin) / dir, tHi = (hi - origin) / dir;
        const double tNear = dir > 0.0 ? tLo : tHi, tFar = dir > 0.0 ? tHi : tLo;
        if (tNear > span.tEnter) {
            span.tEnter = tNear;
            span.entryFace = dir > 0.0 ? lowFace : highFace;
        }
        if (tFar <= span.tExit) {
            span.tExit = tFar;
            span.exitsThroughBottom = dir < 0.0 && lowFace == Bottom;
        }
        return true;
    };
    const bool parallelInside = slab(o.x, d.x, -0.5, width - 0.5, WallX, WallX) &&
                                slab(o.z, d.z, -0.5, height - 0.5, WallZ, WallZ) &&
                                slab(o.y, d.y, 0.0, top, Bottom, None);
    if (!parallelInside || span.tEnter > span.tExit || span.tExit < 0.0) return std::nullopt;
    if (span.tEnter < 0.0) span.entryFace = None;
    return span;
}

// The cell holding coordinate `p` for a ray moving with `dir` along that axis: on a cell
// boundary, the cell the ray moves into.
int startCell(double p, double dir, int count) {
    const double cell = std::floor(p);
    int index = static_cast<int>(std::clamp(cell, -2.0, static_cast<double>(count)));
    if (dir < 0.0 && p == cell) --index;
    return std::clamp(index, -1, count - 1);
}

// The t at which the ray leaves cell `cell` along one axis.
double cellExit(double origin, double dir, int cell) {
    if (dir > 0.0) return (cell + 1 - origin) / dir;
    if (dir < 0.0) return (cell - origin) / dir;
    return kInfinity;
}

struct CellContact {
    double t = 0.0;
    glm::dvec2 gradient{0.0};  // (dh/dx, dh/dz) of the surface at the contact, sample space
};

// The 2D DDA (Amanatides and Woo) over the bilinear cells the ray crosses between
// tStart and span.tExit, in order, solving each cell's patch exactly: the first contact.
template <class Samples>
std::optional<CellContact> walkCells(const Samples& map, double heightScale, const glm::dvec3& o,
                                     const glm::dvec3& d, double tStart, const BoxSpan& span) {
    const double tExit = span.tExit;
    const glm::dvec3 start = o + tStart * d;
    int ci = startCell(start.x, d.x, map.width), cj = startCell(start.z, d.z, map.height);
    const int stepI = d.x > 0.0 ? 1 : -1, stepJ = d.z > 0.0 ? 1 : -1;
    double t = tStart;
    for (;;) {
        const double tx = cellExit(o.x, d.x, ci), tz = cellExit(o.z, d.z, cj);
        // Rounding can put the start a hair outside its cell: clamp to an empty span.
        const double tEnd = std::max(t, std::min({tx, tz, tExit}));
        const BilinearPatch patch = cellPatch(map, heightScale, ci, cj);
        const glm::dvec3 local = o + t * d - glm::dvec3(ci, 0.0, cj);
        if (const auto tau = firstContact(patch, local, d, tEnd - t)) {
            const double fx = std::clamp(local.x + *tau * d.x, 0.0, 1.0);
            const double fz = std::clamp(local.z + *tau * d.z, 0.0, 1.0);
            return CellContact{std::min(t + *tau, tEnd), patch.gradient(fx, fz)};
        }
        if (tEnd >= tExit) {
            // Down through the base plane inside the footprint the ray is in the solid
            // (h >= 0): a root on a zero patch can round to just past the exit.
            if (!span.exitsThroughBottom) return std::nullopt;
            const glm::dvec3 end = local + (tEnd - t) * d;
            return CellContact{
                tEnd, patch.gradient(std::clamp(end.x, 0.0, 1.0), std::clamp(end.z, 0.0, 1.0))};
        }
        // Through a corner both indices step; the diagonal cells only touch the ray there.
        if (tx <= tz) ci += stepI;
        if (tz <= tx) cj += stepJ;
        if (ci < -1 || ci >= map.width || cj < -1 || cj >= map.height) return std::nullopt;
        t = tEnd;
    }
}

// ---- The biquadratic surface (scene-and-cli.md, "Interpolation") ----
//
// Over texel square (i, j), sample space x in [i - 1/2, i + 1/2], the surface is the sum of
// the 3 x 3 samples around it weighted by the quadratic B-spline's (1/2 - f)^2 / 2,
// 3/4 - f^2, (1/2 + f)^2 / 2 with f = x - i. Along the ray f is linear in t, so the gap
// between the ray and the surface is a polynomial of degree 4 in t, written out here in
// the power basis; its first zero is isolated through its derivatives, whose roots split
// the stretch into pieces where it is monotone.

using Polynomial = std::vector<double>;  // coefficients, lowest degree first

Polynomial multiply(const Polynomial& a, const Polynomial& b) {
    Polynomial c(a.size() + b.size() - 1, 0.0);
    for (std::size_t i = 0; i < a.size(); ++i)
        for (std::size_t j = 0; j < b.size(); ++j) c[i + j] += a[i] * b[j];
    return c;
}

double evaluate(const Polynomial& p, double t) {
    double v = 0.0;
    for (std::size_t k = p.size(); k-- > 0;) v = v * t + p[k];
    return v;
}

Polynomial derivative(const Polynomial& p) {
    Polynomial d;
    for (std::size_t k = 1; k < p.size(); ++k) d.push_back(static_cast<double>(k) * p[k]);
    return d.empty() ? Polynomial{0.0} : d;
}

// A root of p in [a, b], where p is monotone there with p(a) > 0 >= p(b): bisection to the
// last bit.
double bisectMonotone(const Polynomial& p, double a, double b) {
    for (int k = 0; k < 200 && b - a > 1e-16 * std::max(1.0, std::abs(b)); ++k) {
        const double m = 0.5 * (a + b);
        (evaluate(p, m) > 0.0 ? a : b) = m;
    }
    return b;
}

// The roots of p in (a, b), sorted: the roots of p' split [a, b] into monotone pieces, each
// with at most one root.
std::vector<double> rootsIn(const Polynomial& p, double a, double b) {
    std::vector<double> stops{a};
    if (p.size() > 2) {
        for (double c : rootsIn(derivative(p), a, b)) stops.push_back(c);
    }
    stops.push_back(b);
    std::vector<double> roots;
    for (std::size_t k = 0; k + 1 < stops.size(); ++k) {
        const double l = stops[k], r = stops[k + 1];
        const double pl = evaluate(p, l), pr = evaluate(p, r);
        if (pr == 0.0 && r < b) {
            roots.push_back(r);
        } else if ((pl > 0.0 && pr < 0.0) || (pl < 0.0 && pr > 0.0)) {
            const Polynomial q = pl > 0.0 ? p : [&] {
                Polynomial n = p;
                for (double& c : n) c = -c;
                return n;
            }();
            roots.push_back(bisectMonotone(q, l, r));
        }
    }
    return roots;
}

// The first tau in [0, length] with p(tau) <= 0: the start, or the first end of a
// monotone piece at which p is <= 0 (a touching ray reaches 0 at a critical point).
std::optional<double> firstNonPositive(const Polynomial& p, double length) {
    if (evaluate(p, 0.0) <= 0.0) return 0.0;
    std::vector<double> stops = rootsIn(derivative(p), 0.0, length);
    stops.push_back(length);
    double previous = 0.0;
    for (double stop : stops) {
        if (evaluate(p, stop) <= 0.0) return bisectMonotone(p, previous, stop);
        previous = stop;
    }
    return std::nullopt;
}

struct QuadraticSquare {
    double c[3][3];  // world heights of samples (i - 1 + a, j - 1 + b) as c[b][a]
    double maxSample;
};

template <class Samples>
QuadraticSquare squareAt(const Samples& map, double heightScale, int i, int j) {
    QuadraticSquare q{};
    q.maxSample = 0.0;
    for (int b = 0; b < 3; ++b) {
        for (int a = 0; a < 3; ++a) {
            q.c[b][a] = heightScale * map.clamped(i - 1 + a, j - 1 + b);
            q.maxSample = std::max(q.maxSample, q.c[b][a]);
        }
    }
    return q;
}

// The B-spline weights as polynomials in tau, where f = f0 + tau df.
std::array<Polynomial, 3> weightPolynomials(double f0, double df) {
    const Polynomial minus{0.5 - f0, -df}, plus{0.5 + f0, df};  // 1/2 -+ f
    Polynomial w0 = multiply(minus, minus), w2 = multiply(plus, plus);
    for (double& c : w0) c *= 0.5;
    for (double& c : w2) c *= 0.5;
    const Polynomial w1{0.75 - f0 * f0, -2.0 * f0 * df, -df * df};
    return {w0, w1, w2};
}

// The first tau in [0, length] at which the ray (its start at f = local (x - i, z - j))
// lies on or below the square's surface.
std::optional<double> firstContact(const QuadraticSquare& q, const glm::dvec3& local,
                                   const glm::dvec3& d, double length) {
    // Exact cull: the surface never rises above its control points.
    if (std::min(local.y, local.y + d.y * length) > q.maxSample) return std::nullopt;
    const auto wx = weightPolynomials(local.x, d.x), wz = weightPolynomials(local.z, d.z);
    Polynomial gap{local.y, d.y, 0.0, 0.0, 0.0};  // ray height - surface height
    for (int b = 0; b < 3; ++b) {
        for (int a = 0; a < 3; ++a) {
            const Polynomial term = multiply(wx[a], wz[b]);
            for (std::size_t k = 0; k < term.size(); ++k) gap[k] -= q.c[b][a] * term[k];
        }
    }
    return firstNonPositive(gap, length);
}

glm::dvec2 gradientAt(const QuadraticSquare& q, double fx, double fz) {
    double wx[3], wz[3];
    quadraticWeights(fx, wx);
    quadraticWeights(fz, wz);
    const double dx[3] = {-(0.5 - fx), -2.0 * fx, 0.5 + fx},
                 dz[3] = {-(0.5 - fz), -2.0 * fz, 0.5 + fz};
    glm::dvec2 g(0.0);
    for (int b = 0; b < 3; ++b) {
        for (int a = 0; a < 3; ++a) g += q.c[b][a] * glm::dvec2(dx[a] * wz[b], wx[a] * dz[b]);
    }
    return g;
}

// The DDA over the texel squares the ray crosses (sample space: square i holds
// x in [i - 1/2, i + 1/2], i in [0, W - 1]), solving each square's quartic: the first
// contact. As walkCells, for the biquadratic surface.
template <class Samples>
std::optional<CellContact> walkSquares(const Samples& map, double heightScale, const glm::dvec3& o,
                                       const glm::dvec3& d, double tStart, const BoxSpan& span) {
    // In square space (sample space + 1/2) the squares are unit cells 0..W-1 x 0..H-1.
    const glm::dvec3 os = o + glm::dvec3(0.5, 0.0, 0.5);
    const glm::dvec3 start = os + tStart * d;
    const auto first = [](double p, double dir, int count) {
        double cell = std::floor(p);
        if (dir < 0.0 && p == cell) cell -= 1.0;
        return static_cast<int>(std::clamp(cell, 0.0, count - 1.0));
    };
    int i = first(start.x, d.x, map.width), j = first(start.z, d.z, map.height);
    const int stepI = d.x > 0.0 ? 1 : -1, stepJ = d.z > 0.0 ? 1 : -1;
    double t = tStart;
    for (;;) {
        const double tx = cellExit(os.x, d.x, i), tz = cellExit(os.z, d.z, j);
        const double tEnd = std::max(t, std::min({tx, tz, span.tExit}));
        const QuadraticSquare square = squareAt(map, heightScale, i, j);
        // Local: f = x - i - 1/2 in [-1/2, 1/2] over the square.
        const glm::dvec3 local = os + t * d - glm::dvec3(i + 0.5, 0.0, j + 0.5);
        const auto at = [&](double tau) {
            return glm::dvec2(std::clamp(local.x + tau * d.x, -0.5, 0.5),
                              std::clamp(local.z + tau * d.z, -0.5, 0.5));
        };
        if (const auto tau = firstContact(square, local, d, tEnd - t)) {
            const glm::dvec2 f = at(*tau);
            return CellContact{std::min(t + *tau, tEnd), gradientAt(square, f.x, f.y)};
        }
        if (tEnd >= span.tExit) {
            if (!span.exitsThroughBottom) return std::nullopt;
            const glm::dvec2 f = at(tEnd - t);
            return CellContact{tEnd, gradientAt(square, f.x, f.y)};
        }
        if (tx <= tz) i += stepI;
        if (tz <= tx) j += stepJ;
        if (i < 0 || i >= map.width || j < 0 || j >= map.height) return std::nullopt;
        t = tEnd;
    }
}

// A hit on a planar face (wall or bottom), snapped exactly onto that plane.
ReferenceHit faceHit(HitFace face, double t, const Ray& ray, const SampleSpace& space) {
    const glm::dvec3 d = space.vector(ray.direction);
    const glm::dvec3 p = space.point(ray.origin) + t * d;
    ReferenceHit hit;
    hit.face = face;
    hit.t = t;
    hit.position = ray.origin + t * ray.direction;
    hit.uv = space.uv(p);
    const double halfA = 0.5 * space.width / space.scale, halfB = 0.5 * space.height / space.scale;
    switch (face) {
        case HitFace::WallX: {
            const double side = d.x > 0.0 ? -1.0 : 1.0;  // entering through x = -a/2 moving +x
            hit.position.x = side * halfA;
            hit.uv.x = side < 0.0 ? 0.0 : 1.0;
            hit.normal = {side, 0.0, 0.0};
            break;
        }
        case HitFace::WallZ: {
            const double side = d.z > 0.0 ? -1.0 : 1.0;
            hit.position.z = side * halfB;
            hit.uv.y = side < 0.0 ? 0.0 : 1.0;
            hit.normal = {0.0, 0.0, side};
            break;
        }
        default:
            assert(face == HitFace::Bottom);
            hit.position.y = 0.0;
            hit.normal = {0.0, -1.0, 0.0};
            break;
    }
    return hit;
}

ReferenceHit topHit(const CellContact& contact, const Ray& ray, const SampleSpace& space) {
    ReferenceHit hit;
    hit.face = HitFace::Top;
    hit.t = contact.t;
    hit.position = ray.origin + contact.t * ray.direction;
    hit.uv = space.uv(space.point(ray.origin) + contact.t * space.vector(ray.direction));
    // y = h(fx, fz) with fx = x scale + const: dy/dx = scale dh/dfx, likewise for z.
    const glm::dvec2 slope = contact.gradient * space.scale;
    hit.normal = glm::normalize(glm::dvec3(-slope.x, 1.0, -slope.y));
    return hit;
}

// `top` bounds the solid from above: s times the largest sample, or infinity where
// finding that would cost more than the walk. The plane's solid over `map`'s samples.
template <class Samples>
ReferenceHit traceBelow(const Samples& map, double heightScale, Interpolation interpolation,
                        const Ray& ray, double top) {
    assert(map.width > 0 && map.height > 0);
    assert(heightScale >= 0.0 && std::isfinite(heightScale));
    assert(ray.direction != glm::dvec3(0.0));
    const SampleSpace space{map.width, map.height,
                            static_cast<double>(std::max(map.width, map.height))};
    const glm::dvec3 o = space.point(ray.origin), d = space.vector(ray.direction);

    const auto span = clipToBoundingBox(o, d, map.width, map.height, top);
    if (!span) return {};
    const auto entered = [&span](ReferenceHit hit) {
        hit.entryFace = span->entryFace;
        return hit;
    };
    // Heights are >= 0, so the whole bottom face belongs to the solid.
    if (span->entryFace == HitFace::Bottom)
        return entered(faceHit(HitFace::Bottom, span->tEnter, ray, space));

    const double tStart = std::max(span->tEnter, 0.0);
    const auto contact = interpolation == Interpolation::Biquadratic
                             ? walkSquares(map, heightScale, o, d, tStart, *span)
                             : walkCells(map, heightScale, o, d, tStart, *span);
    if (!contact) return entered({});
    // Touching the solid right where the ray enters through a wall: a wall hit.
    if (span->entryFace != HitFace::None && contact->t == tStart) {
        return entered(faceHit(span->entryFace, tStart, ray, space));
    }
    return entered(topHit(*contact, ray, space));
}

}  // namespace

namespace {

// The hit of `ray` (world) by `traceObject` in the relief's object space: the ray taken
// there by the model transform, which keeps t; the position is the world ray's at that t,
// the normal through the inverse transpose.
template <class TraceObject>
ReferenceHit throughModel(const ModelTransform& model, const Ray& ray, TraceObject traceObject) {
    if (model.isIdentity()) return traceObject(ray);
    ReferenceHit hit = traceObject(model.toObject(ray));
    if (hit) {
        hit.position = ray.origin + hit.t * ray.direction;
        hit.normal = model.normalToWorld(hit.normal);
    }
    return hit;
}

}  // namespace

ReferenceHit traceReference(const ReliefGeometry& relief, const Ray& ray) {
    return throughModel(relief.model, ray, [&](const Ray& objectRay) {
        if (relief.base.curved()) {
            return detail::traceCurvedReference(relief, detail::curvedBoundaries(relief), objectRay,
                                                relief.heightScale * relief.map->maxValue());
        }
        // Without a known top the walk covers every cell under the ray's path over the
        // footprint; the exact per-cell cull keeps the cells above the relief cheap.
        assert(relief.map != nullptr && !relief.map->empty());
        return traceBelow(*relief.map, relief.heightScale, relief.interpolation, objectRay,
                          kInfinity);
    });
}

ReferenceTracer::ReferenceTracer(const ReliefGeometry& relief)
    : relief_(relief), top_(relief.heightScale * static_cast<double>(relief.map->maxValue())) {
    if (relief.base.curved()) boundaries_ = detail::curvedBoundaries(relief);
}

ReferenceHit ReferenceTracer::trace(const Ray& ray) const {
    return throughModel(relief_.model, ray, [&](const Ray& objectRay) {
        if (relief_.base.curved())
            return detail::traceCurvedReference(relief_, boundaries_, objectRay, top_);
        return traceBelow(*relief_.map, relief_.heightScale, relief_.interpolation, objectRay,
                          top_);
    });
}

// The samples of page level 0 as the walks read them (the Samples of cellPatch): a block of
// kSide^2 at a time, the least recently used of kBlocks replaced.
class PagedReferenceTracer::Samples {
public:
    explicit Samples(std::shared_ptr<const PyramidPages> pages)
        : width(pages->mapWidth()), height(pages->mapHeight()), pages_(std::move(pages)) {
        blocks_.reserve(kBlocks);  // never reallocated: last_ points into it
    }

    const int width, height;

    float at(int i, int j) const {
        const Block& b = block(i >> kShift, j >> kShift);
        return b.texels[static_cast<std::size_t>(j - b.y0) * b.stride + (i - b.x0)];
    }
    float clamped(int i, int j) const {
        return at(std::clamp(i, 0, width - 1), std::clamp(j, 0, height - 1));
    }
    std::size_t blocksRead() const { return blocksRead_; }

private:
    static constexpr int kShift = 8, kBlocks = 32;
    struct Block {
        int bx = -1, by = -1, x0 = 0, y0 = 0, stride = 0;
        std::uint64_t used = 0;
        std::vector<float> texels;
    };

    const Block& block(int bx, int by) const {
        if (last_ && last_->bx == bx && last_->by == by) return *last_;
        Block* found = nullptr;
        Block* oldest = nullptr;
        for (Block& b : blocks_) {
            if (b.bx == bx && b.by == by) {
                found = &b;
                break;
            }
            if (!oldest || b.used < oldest->used) oldest = &b;
        }
        if (!found) {
            found = blocks_.size() < kBlocks ? &blocks_.emplace_back() : oldest;
            const TexelRect rect{bx << kShift, by << kShift, std::min(width, (bx + 1) << kShift),
                                 std::min(height, (by + 1) << kShift)};
            found->texels.resize(static_cast<std::size_t>(rect.width()) * rect.height());
            found->bx = -1;  // unusable until read
            pages_->read(0, rect, found->texels.data());
            *found = Block{bx, by, rect.x0, rect.y0, rect.width(), 0, std::move(found->texels)};
            ++blocksRead_;
        }
        found->used = ++clock_;
        last_ = found;
        return *found;
    }

    std::shared_ptr<const PyramidPages> pages_;
    mutable std::vector<Block> blocks_;
    mutable Block* last_ = nullptr;
    mutable std::uint64_t clock_ = 0;
    mutable std::size_t blocksRead_ = 0;
};

PagedReferenceTracer::PagedReferenceTracer(std::shared_ptr<const PyramidPages> pages,
                                           double heightScale, Interpolation interpolation,
                                           const ModelTransform& model)
    : heightScale_(heightScale),
      interpolation_(interpolation),
      model_(model),
      top_(heightScale * static_cast<double>(pages->largestSample())) {
    samples_ = std::make_unique<Samples>(std::move(pages));
}

PagedReferenceTracer::~PagedReferenceTracer() = default;

ReferenceHit PagedReferenceTracer::trace(const Ray& ray) const {
    return throughModel(model_, ray, [&](const Ray& objectRay) {
        return traceBelow(*samples_, heightScale_, interpolation_, objectRay, top_);
    });
}

std::size_t PagedReferenceTracer::blocksRead() const {
    return samples_->blocksRead();
}

}  // namespace microrelief
