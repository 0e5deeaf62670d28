// The mesh base's proxy (core/base/MeshProxy.h, which says what it is and why it covers
// every ray): per triangle H_tri and the convex hull of the prism's six corners, padded
// outward so that the float triangles still enclose the exact hull.
#include "microrelief/core/base/MeshProxy.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <utility>

namespace microrelief {

namespace {

constexpr int kCorners = 6;  // P_0..2, then P_0..2 + s H N_0..2
// Points within this of a plane (relative to the hull's size) are taken as on it. The
// padding (far larger) covers what that moves a face by.
constexpr double kCoplanar = 1e-12;
// A uv box over more samples than this is bounded by the map's largest sample.
constexpr double kMaxSamplesBounded = 65536.0;

using Corners = std::array<glm::dvec3, kCorners>;

// A face of the hull: its outward unit normal and the corners on its plane, in order
// counter-clockwise seen from outside (the polygon's vertices only).
struct HullFace {
    glm::dvec3 normal;
    std::vector<int> polygon;
};

// The convex hull of points in a plane with unit normal n: the corners of `indices` as a
// polygon counter-clockwise about n (Andrew's monotone chain on their coordinates in the
// plane; points within `tau` of one another are one point, points on an edge dropped).
std::vector<int> planarHull(const Corners& p, std::vector<int> indices, const glm::dvec3& n,
                            double tau) {
    const glm::dvec3 a = std::abs(n.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 e1 = glm::normalize(glm::cross(n, a)), e2 = glm::cross(n, e1);
    const auto at = [&](int i) { return glm::dvec2(glm::dot(p[i], e1), glm::dot(p[i], e2)); };
    std::sort(indices.begin(), indices.end(), [&](int i, int j) {
        const glm::dvec2 x = at(i), y = at(j);
        return x.x < y.x || (x.x == y.x && x.y < y.y);
    });
    // Turning left (counter-clockwise about n, as (e1, e2, n) is right-handed) by more than
    // the tolerance: the cross product against the chord's length.
    const auto left = [&](int o, int i, int j) {
        const glm::dvec2 u = at(i) - at(o), v = at(j) - at(o);
        return u.x * v.y - u.y * v.x > tau * glm::length(v - u);
    };
    std::vector<int> hull;
    for (int pass = 0; pass < 2; ++pass) {
        const std::size_t floor = hull.size();
        for (int i : indices) {
            if (!hull.empty() && glm::length(at(hull.back()) - at(i)) <= tau) continue;
            while (hull.size() >= floor + 2 && !left(hull[hull.size() - 2], hull.back(), i))
                hull.pop_back();
            hull.push_back(i);
        }
        hull.pop_back();  // the other chain's first point
        std::reverse(indices.begin(), indices.end());
    }
    return hull;
}

// The faces of the convex hull of six points that span 3-space, or nothing where the
// points are (within the tolerance) coplanar. Every plane through three non-collinear
// corners with all six on its inner side is a face plane, and every face plane holds three
// such corners; each plane is kept once (by the set of corners on it).
std::optional<std::vector<HullFace>> hullFaces(const Corners& p) {
    double size = 0.0;
    for (int i = 0; i < kCorners; ++i)
        for (int j = i + 1; j < kCorners; ++j) size = std::max(size, glm::length(p[i] - p[j]));
    const double tau = kCoplanar * size;
    std::vector<HullFace> faces;
    std::vector<unsigned> seen;  // the corner sets of the kept planes
    for (int i = 0; i < kCorners; ++i) {
        for (int j = i + 1; j < kCorners; ++j) {
            for (int k = j + 1; k < kCorners; ++k) {
                const glm::dvec3 m = glm::cross(p[j] - p[i], p[k] - p[i]);
                // Nearly collinear: the plane is ill-defined; a face plane has a better
                // triple (or the hull fails its closure check and the box stands in).
                if (glm::length(m) <= 1e-9 * size * size) continue;
                const glm::dvec3 n = glm::normalize(m);
                bool below = true, above = true;
                unsigned on = 0;
                for (int q = 0; q < kCorners; ++q) {
                    const double d = glm::dot(n, p[q] - p[i]);
                    below = below && d <= tau;
                    above = above && d >= -tau;
                    if (std::abs(d) <= tau) on |= 1u << q;
                }
                if (below && above) return std::nullopt;  // all six in one plane
                if (!below && !above) continue;
                const glm::dvec3 outward = below ? n : -n;
                // The corners on a face plane name it (its outward side is the one all six
                // are not on: one plane, one face, the coplanar case having returned).
                if (std::find(seen.begin(), seen.end(), on) != seen.end()) continue;
                seen.push_back(on);
                std::vector<int> indices;
                for (int q = 0; q < kCorners; ++q)
                    if (on & (1u << q)) indices.push_back(q);
                std::vector<int> polygon = planarHull(p, indices, outward, tau);
                if (polygon.size() >= 3) faces.push_back({outward, std::move(polygon)});
            }
        }
    }
    return faces;
}

// Whether the faces' polygons close up: every directed edge met once and its reverse once
// (corners within the tolerance of one another being one corner).
bool closed(const Corners& p, const std::vector<HullFace>& faces) {
    double size = 0.0;
    for (int i = 0; i < kCorners; ++i)
        for (int j = i + 1; j < kCorners; ++j) size = std::max(size, glm::length(p[i] - p[j]));
    std::array<int, kCorners> canonical{};
    for (int i = 0; i < kCorners; ++i) {
        canonical[i] = i;
        for (int j = 0; j < i; ++j) {
            if (glm::length(p[i] - p[j]) <= kCoplanar * size) {
                canonical[i] = canonical[j];
                break;
            }
        }
    }
    std::map<std::pair<int, int>, int> edges;
    for (const HullFace& f : faces) {
        for (std::size_t k = 0; k < f.polygon.size(); ++k) {
            const int a = canonical[f.polygon[k]];
            const int b = canonical[f.polygon[(k + 1) % f.polygon.size()]];
            if (a == b) return false;
            ++edges[{a, b}];
        }
    }
    for (const auto& [edge, count] : edges) {
        const auto reverse = edges.find({edge.second, edge.first});
        if (count != 1 || reverse == edges.end() || reverse->second != 1) return false;
    }
    return !faces.empty();
}

// The shortest w with n . w >= padding for every unit normal n in `normals`: the point of
// that polyhedron nearest the origin lies in the span of at most three of them, held with
// equality, so every set of one, two or three is tried. Nothing where no w exists (the
// normals not in an open half-space: never at a vertex of a hull that spans 3-space).
std::optional<glm::dvec3> outwardMove(const std::vector<glm::dvec3>& normals, double padding) {
    std::optional<glm::dvec3> best;
    const auto consider = [&](const glm::dvec3& w) {
        for (const glm::dvec3& n : normals)
            if (!(glm::dot(n, w) >= padding * (1.0 - 1e-9))) return;
        if (!best || glm::length(w) < glm::length(*best)) best = w;
    };
    const std::size_t count = normals.size();
    for (std::size_t a = 0; a < count; ++a) {
        consider(padding * normals[a]);
        for (std::size_t b = a + 1; b < count; ++b) {
            const double c = glm::dot(normals[a], normals[b]);
            if (c > -1.0 + 1e-12) consider(padding / (1.0 + c) * (normals[a] + normals[b]));
            for (std::size_t d = b + 1; d < count; ++d) {
                const glm::dmat3 rows =
                    glm::transpose(glm::dmat3(normals[a], normals[b], normals[d]));
                if (std::abs(glm::determinant(rows)) <= 1e-12) continue;
                consider(glm::inverse(rows) * glm::dvec3(padding));
            }
        }
    }
    return best;
}

// The padded hull's triangles, or nothing where the hull cannot be made (coplanar corners,
// a failed closure check, a vertex no outward move of at most `longest` serves).
std::optional<std::vector<glm::dvec3>> paddedHull(const Corners& p, double padding,
                                                  double longest) {
    const auto faces = hullFaces(p);
    if (!faces || !closed(p, *faces)) return std::nullopt;
    std::array<glm::dvec3, kCorners> moved = p;
    for (int q = 0; q < kCorners; ++q) {
        std::vector<glm::dvec3> normals;
        for (const HullFace& f : *faces)
            if (std::find(f.polygon.begin(), f.polygon.end(), q) != f.polygon.end())
                normals.push_back(f.normal);
        if (normals.empty()) continue;  // not a vertex of the hull
        const auto w = outwardMove(normals, padding);
        if (!w || glm::length(*w) > longest) return std::nullopt;
        moved[q] = p[q] + *w;
    }
    std::vector<glm::dvec3> triangles;
    for (const HullFace& f : *faces) {
        for (std::size_t k = 1; k + 1 < f.polygon.size(); ++k) {
            triangles.push_back(moved[f.polygon[0]]);
            triangles.push_back(moved[f.polygon[k]]);
            triangles.push_back(moved[f.polygon[k + 1]]);
        }
    }
    return triangles;
}

// The fallback: the corners' axis-aligned box grown by the padding (12 triangles), which
// holds the hull.
std::vector<glm::dvec3> paddedBox(const Corners& p, double padding) {
    glm::dvec3 lo = p[0], hi = p[0];
    for (const glm::dvec3& c : p) {
        lo = glm::min(lo, c);
        hi = glm::max(hi, c);
    }
    lo -= padding;
    hi += padding;
    const auto corner = [&](int k) {
        return glm::dvec3(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z);
    };
    // Each side as two triangles counter-clockwise seen from outside.
    static constexpr int kQuads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                         {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    std::vector<glm::dvec3> triangles;
    for (const auto& q : kQuads) {
        for (const int k : {q[0], q[1], q[2], q[0], q[2], q[3]}) triangles.push_back(corner(k));
    }
    return triangles;
}

}  // namespace

// Why H_tri bounds h over the triangle, in texel units X = u W, Y = v H (W x H samples,
// sample (i, j) at texel centre (i + 1/2, j + 1/2), indices repeated modulo W and H):
//  * uv(b) = sum b_i T_i is a convex combination of the T_i, so over the triangle X lies
//    in [X0, X1], the box of the T_i times W, and Y likewise.
//  * Bilinear: h(X, Y) mixes the samples of columns i = floor(X - 1/2) and i + 1 (rows
//    likewise) with weights in [0, 1] summing to 1; floor(X) - 1 <= i and
//    i + 1 <= floor(X) + 1.
//  * Biquadratic: over texel square floor(X) the B-spline sums columns floor(X) - 1 ..
//    floor(X) + 1 (rows likewise) with the weights (1/2 - f)^2 / 2, 3/4 - f^2,
//    (1/2 + f)^2 / 2, |f| <= 1/2: each >= 0, summing to 1 (their products too).
//  * Either way h(X, Y) is a convex combination of samples in columns floor(X0) - 1 ..
//    floor(X1) + 1 and rows floor(Y0) - 1 .. floor(Y1) + 1, so at most their largest.
// The samples are floats, so the bound is one exactly.
float topHeight(const HeightMap& map, glm::dvec2 t0, glm::dvec2 t1, glm::dvec2 t2) {
    assert(!map.empty());
    const auto finite = [](glm::dvec2 t) { return std::isfinite(t.x) && std::isfinite(t.y); };
    if (!finite(t0) || !finite(t1) || !finite(t2)) return map.maxValue();
    const glm::dvec2 lo = glm::min(t0, glm::min(t1, t2)), hi = glm::max(t0, glm::max(t1, t2));
    const double i0 = std::floor(lo.x * map.width) - 1.0, i1 = std::floor(hi.x * map.width) + 1.0;
    const double j0 = std::floor(lo.y * map.height) - 1.0, j1 = std::floor(hi.y * map.height) + 1.0;
    const double columns = std::min(i1 - i0 + 1.0, static_cast<double>(map.width));
    const double rows = std::min(j1 - j0 + 1.0, static_cast<double>(map.height));
    if (!(columns * rows <= kMaxSamplesBounded)) return map.maxValue();
    const auto wrap = [](double i, int n) {
        const double r = i - n * std::floor(i / n);
        return std::min(static_cast<int>(r), n - 1);
    };
    float best = 0.0f;
    const int first = wrap(i0, map.width), count = static_cast<int>(columns);
    for (int r = 0; r < static_cast<int>(rows); ++r) {
        const float* row = &map.samples[static_cast<std::size_t>(wrap(j0 + r, map.height)) *
                                        static_cast<std::size_t>(map.width)];
        for (int c = 0, i = first; c < count; ++c) {
            best = std::max(best, row[i]);
            if (++i == map.width) i = 0;
        }
    }
    return best;
}

MeshProxy buildMeshProxy(const TriangleMesh& mesh, const HeightMap& map, double heightScale) {
    assert(heightScale >= 0.0 && std::isfinite(heightScale));
    MeshProxy proxy;
    const std::size_t count = mesh.triangles.size();
    proxy.topHeights.reserve(count);
    std::vector<Corners> corners(count);
    double largest = 0.0;  // the largest coordinate of any corner
    for (std::size_t k = 0; k < count; ++k) {
        const glm::uvec3 tri = mesh.triangles[k];
        const float top =
            topHeight(map, mesh.texCoords[tri[0]], mesh.texCoords[tri[1]], mesh.texCoords[tri[2]]);
        proxy.topHeights.push_back(top);
        for (int i = 0; i < 3; ++i) {
            const glm::dvec3 p = mesh.positions[tri[i]], n = mesh.normals[tri[i]];
            corners[k][i] = p;
            corners[k][i + 3] = p + heightScale * static_cast<double>(top) * n;
        }
        for (const glm::dvec3& c : corners[k])
            largest = std::max({largest, std::abs(c.x), std::abs(c.y), std::abs(c.z)});
    }
    // Why the float triangles enclose the exact hull: a point x of a hull face f is
    // sum beta_v v over its triangle's vertices v (beta >= 0, summing to 1), all on f; each
    // v moves by w_v with n_f . w_v >= padding, then by its rounding r_v to float, so x
    // moves out of f's plane by sum beta_v (n_f . w_v + n_f . r_v) >= padding - max |r_v|.
    // Rounding moves a coordinate by at most half an ulp, 2^-24 of its size, a vertex by
    // at most sqrt(3) 2^-24 of its largest coordinate, which the moves (|w| <= `largest`)
    // keep under 2 `largest`: under 3.5 2^-24 `largest`, well under the padding. So for
    // every s in (0, 1] the surface moved by s of that lies strictly outside the hull's
    // face planes, never meets the hull, and encloses it as the hull's own boundary does:
    // a ray from outside it to a point of the hull crosses it.
    proxy.padding = 32.0 * std::ldexp(largest, -24);

    proxy.firstProxyTriangle.reserve(count + 1);
    for (std::size_t k = 0; k < count; ++k) {
        proxy.firstProxyTriangle.push_back(static_cast<std::uint32_t>(proxy.meshTriangles.size()));
        const Corners& p = corners[k];
        std::vector<glm::dvec3> triangles;
        if (proxy.topHeights[k] == 0.0f || heightScale == 0.0) {
            // The prism is the triangle itself: its own float corners, exact, once in each
            // winding (whichever way a ray crosses it, one of them faces it).
            triangles = {p[0], p[1], p[2], p[0], p[2], p[1]};
        } else if (auto hull = paddedHull(p, proxy.padding, largest)) {
            triangles = std::move(*hull);
        } else {
            triangles = paddedBox(p, proxy.padding);
        }
        for (const glm::dvec3& v : triangles) proxy.positions.push_back(glm::vec3(v));
        proxy.meshTriangles.insert(proxy.meshTriangles.end(), triangles.size() / 3,
                                   static_cast<std::uint32_t>(k));
    }
    proxy.firstProxyTriangle.push_back(static_cast<std::uint32_t>(proxy.meshTriangles.size()));
    return proxy;
}

std::vector<std::uint32_t> hullsThatMayHold(const MeshProxy& proxy, const glm::dvec3& point) {
    std::vector<std::uint32_t> holding;
    for (std::size_t k = 0; k + 1 < proxy.firstProxyTriangle.size(); ++k) {
        glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
        for (std::uint32_t v = 3 * proxy.firstProxyTriangle[k];
             v < 3 * proxy.firstProxyTriangle[k + 1]; ++v) {
            lo = glm::min(lo, glm::dvec3(proxy.positions[v]));
            hi = glm::max(hi, glm::dvec3(proxy.positions[v]));
        }
        if (glm::all(glm::lessThanEqual(lo, point)) && glm::all(glm::lessThanEqual(point, hi)))
            holding.push_back(static_cast<std::uint32_t>(k));
    }
    return holding;
}

}  // namespace microrelief
