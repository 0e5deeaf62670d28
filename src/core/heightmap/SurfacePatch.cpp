#include "microrelief/core/heightmap/SurfacePatch.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace microrelief {

namespace {

glm::dvec3 bernstein(double u) {
    const double w = 1.0 - u;
    return {w * w, 2.0 * u * w, u * u};
}

// Column k: the weights of a quadratic's Bezier points over [0, 1] in its k-th Bezier point
// over [a, b] (its values and polar form at (a, a), (a, b), (b, b)).
glm::dmat3 restriction(double a, double b) {
    const glm::dvec3 polar((1.0 - a) * (1.0 - b), a * (1.0 - b) + b * (1.0 - a), a * b);
    return glm::dmat3(bernstein(a), polar, bernstein(b));
}

}  // namespace

SurfacePatch SurfacePatch::at(const HeightMap& map, int i, int j, bool wrapU,
                              Interpolation interpolation) {
    return at(map, i, j, MapAddressing{wrapU}, interpolation);
}

SurfacePatch SurfacePatch::at(const HeightMap& map, int i, int j, const MapAddressing& wrapU,
                              Interpolation interpolation) {
    SurfacePatch p;
    p.interpolation = interpolation;
    p.i = i;
    p.j = j;
    if (interpolation == Interpolation::Bilinear) {
        p.h00 = map.sample(i, j, wrapU);
        p.h10 = map.sample(i + 1, j, wrapU);
        p.h01 = map.sample(i, j + 1, wrapU);
        p.h11 = map.sample(i + 1, j + 1, wrapU);
        return p;
    }
    // The B-spline's control points to the Bezier net, per axis (c0 + c1) / 2, c1,
    // (c1 + c2) / 2 (biquadratic_patch.glsl).
    double c[3][3], rows[3][3];
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) c[a][b] = map.sample(i - 1 + a, j - 1 + b, wrapU);
    for (int b = 0; b < 3; ++b) {
        rows[0][b] = 0.5 * (c[0][b] + c[1][b]);
        rows[1][b] = c[1][b];
        rows[2][b] = 0.5 * (c[1][b] + c[2][b]);
    }
    for (int a = 0; a < 3; ++a) {
        p.net[a][0] = 0.5 * (rows[a][0] + rows[a][1]);
        p.net[a][1] = rows[a][1];
        p.net[a][2] = 0.5 * (rows[a][1] + rows[a][2]);
    }
    return p;
}

double SurfacePatch::height(glm::dvec2 f) const {
    if (interpolation == Interpolation::Bilinear)
        return (h00 * (1 - f.x) + h10 * f.x) * (1 - f.y) + (h01 * (1 - f.x) + h11 * f.x) * f.y;
    const glm::dvec3 bu = bernstein(f.x), bv = bernstein(f.y);
    double h = 0.0;
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) h += bu[a] * bv[b] * net[a][b];
    return h;
}

glm::dvec2 SurfacePatch::gradient(glm::dvec2 f) const {
    if (interpolation == Interpolation::Bilinear)
        return {(h10 - h00) * (1 - f.y) + (h11 - h01) * f.y,
                (h01 - h00) * (1 - f.x) + (h11 - h10) * f.x};
    const glm::dvec3 bu = bernstein(f.x), bv = bernstein(f.y);
    const glm::dvec3 du(-2.0 * (1.0 - f.x), 2.0 - 4.0 * f.x, 2.0 * f.x);
    const glm::dvec3 dv(-2.0 * (1.0 - f.y), 2.0 - 4.0 * f.y, 2.0 * f.y);
    glm::dvec2 g(0.0);
    for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) g += net[a][b] * glm::dvec2(du[a] * bv[b], bu[a] * dv[b]);
    }
    return g;
}

double SurfacePatch::maxOver(glm::dvec2 lo, glm::dvec2 hi) const {
    lo = glm::clamp(lo, 0.0, 1.0);
    hi = glm::clamp(hi, 0.0, 1.0);
    if (interpolation == Interpolation::Bilinear) {
        return std::max({height(lo), height({hi.x, lo.y}), height({lo.x, hi.y}), height(hi)});
    }
    const glm::dmat3 su = restriction(lo.x, hi.x), sv = restriction(lo.y, hi.y);
    double top = -1e300;
    for (int k = 0; k < 3; ++k) {
        // Restricted along u: the k-th point's net column over v, then its Bezier points over
        // [lo.y, hi.y].
        glm::dvec3 column(0.0);
        for (int a = 0; a < 3; ++a)
            column += su[k][a] * glm::dvec3(net[a][0], net[a][1], net[a][2]);
        for (int l = 0; l < 3; ++l) top = std::max(top, glm::dot(sv[l], column));
    }
    return top;
}

SurfacePatch::Quartic SurfacePatch::pathGap(const glm::dvec3& fa, const glm::dvec3& fb) const {
    const glm::dmat3 su = restriction(fa.x, fb.x), sv = restriction(fa.y, fb.y);
    // n[k][l]: the net restricted to the path's range along u (k) and v (l), over [0, 1]^2;
    // the path is its diagonal.
    double n[3][3];
    for (int k = 0; k < 3; ++k) {
        glm::dvec3 column(0.0);
        for (int a = 0; a < 3; ++a)
            column += su[k][a] * glm::dvec3(net[a][0], net[a][1], net[a][2]);
        for (int l = 0; l < 3; ++l) n[k][l] = glm::dot(sv[l], column);
    }
    // The diagonal of a tensor-product quadratic: coefficient m sums n[k][l] over k + l = m,
    // weighted C(2, k) C(2, l) / C(4, m); the ray's height is linear.
    const double dz = fb.z - fa.z;
    return {n[0][0] - fa.z, 0.5 * (n[1][0] + n[0][1]) - (fa.z + 0.25 * dz),
            (n[2][0] + 4.0 * n[1][1] + n[0][2]) / 6.0 - (fa.z + 0.5 * dz),
            0.5 * (n[2][1] + n[1][2]) - (fa.z + 0.75 * dz), n[2][2] - fb.z};
}

std::optional<double> parabolaFirstRoot(double ga, double gm, double gb) {
    if (ga >= 0.0) return 0.0;
    if (gm >= 0.0) return 0.5 * ga / (ga - gm);
    if (gb >= 0.0) return 0.5 + 0.5 * gm / (gm - gb);
    // g(s) = ga + B s + A s^2.
    const double A = 2.0 * (ga - 2.0 * gm + gb), B = -3.0 * ga + 4.0 * gm - gb;
    if (A < 0.0) {
        const double vertex = -B / (2.0 * A), disc = B * B - 4.0 * A * ga;
        if (vertex > 0.0 && vertex < 1.0 && disc >= 0.0)
            return std::clamp((-B + std::sqrt(disc)) / (2.0 * A), 0.0, vertex);
    }
    return std::nullopt;
}

SurfacePatch::Quartic quarticPiece(const SurfacePatch::Quartic& q, double sa, double sb) {
    // Right of sa: in place, c[k] ends as level 4 - k's point k.
    SurfacePatch::Quartic c = q;
    for (int r = 1; r <= 4; ++r)
        for (int i = 0; i <= 4 - r; ++i) c[i] += sa * (c[i + 1] - c[i]);
    // Left of tau within [sa, 1]: in place from the top, c[k] ends as level k's point 0.
    const double tau = sa < 1.0 ? (sb - sa) / (1.0 - sa) : 1.0;
    for (int r = 1; r <= 4; ++r)
        for (int i = 4; i >= r; --i) c[i] = c[i - 1] + tau * (c[i] - c[i - 1]);
    return c;
}

double quarticValue(const SurfacePatch::Quartic& q, double s) {
    SurfacePatch::Quartic c = q;
    for (int r = 1; r <= 4; ++r)
        for (int i = 0; i <= 4 - r; ++i) c[i] += s * (c[i + 1] - c[i]);
    return c[0];
}

namespace {

// The one root of a quartic rising from q(0) < 0 to q(1) >= 0 with coefficients that never
// fall: regula falsi with the Illinois rule until the bracket is 2^-18 wide; its upper end,
// in the solid.
double risingRoot(const SurfacePatch::Quartic& q) {
    double lo = 0.0, hi = 1.0, qlo = q[0], qhi = q[4];
    int side = 0;
    for (int k = 0; k < 16 && hi - lo > 1.0 / 262144.0; ++k) {
        const double s = std::clamp((lo * qhi - hi * qlo) / (qhi - qlo), lo, hi);
        const double qs = quarticValue(q, s);
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

constexpr int kQuarticDepth = 12;

}  // namespace

std::optional<double> quarticFirstHit(const SurfacePatch::Quartic& g, double finalWidth,
                                      double margin) {
    int depth = 0;
    std::uint32_t index = 0;
    for (;;) {
        const double scale = std::ldexp(1.0, -depth);
        const double sa = index * scale, sb = (index + 1u) * scale;
        const SurfacePatch::Quartic c = depth == 0 ? g : quarticPiece(g, sa, sb);
        if (*std::max_element(c.begin(), c.end()) >= -margin) {
            if (c[0] >= 0.0) return sa;
            const bool rising =
                c[4] >= 0.0 && c[1] >= c[0] && c[2] >= c[1] && c[3] >= c[2] && c[4] >= c[3];
            if (rising) return sa + (sb - sa) * risingRoot(c);
            if (sb - sa > finalWidth && depth < kQuarticDepth) {
                ++depth;
                index *= 2u;
                continue;
            }
            // The final piece: the parabola through its ends and middle.
            const double middle = (c[0] + 4.0 * c[1] + 6.0 * c[2] + 4.0 * c[3] + c[4]) / 16.0;
            if (const auto s = parabolaFirstRoot(c[0], middle, c[4])) return sa + *s * (sb - sa);
        }
        ++index;
        while (depth > 0 && (index & 1u) == 0u) {
            index >>= 1;
            --depth;
        }
        if (depth == 0) return std::nullopt;
    }
}

}  // namespace microrelief
