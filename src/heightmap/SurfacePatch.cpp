#include "heightmap/SurfacePatch.h"

#include <algorithm>

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

}  // namespace microrelief
