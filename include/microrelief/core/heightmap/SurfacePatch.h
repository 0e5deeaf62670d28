// The surface over one cell of a height map, for either interpolation: the C++ mirror of
// shaders/microrelief/relief_patch.glsl (bilinear_patch.glsl, biquadratic_patch.glsl).
// Bilinear cells lie between sample centres (cell (i, j) over X in [i + 1/2, i + 3/2]),
// biquadratic cells are texel squares (X in [i, i + 1]); local coordinates f run over
// [0, 1]^2 across a cell.
#pragma once

#include <array>
#include <optional>

#include <glm/glm.hpp>

#include "microrelief/core/heightmap/HeightMap.h"

namespace microrelief {

struct SurfacePatch {
    Interpolation interpolation = Interpolation::Bilinear;
    int i = 0, j = 0;                           // the cell
    double h00 = 0, h10 = 0, h01 = 0, h11 = 0;  // bilinear: the corner samples
    double net[3][3] = {};                      // biquadratic: the Bezier net, net[a][b]

    // Where cell 0 starts: 1/2 (bilinear), 0 (biquadratic).
    static double offset(Interpolation interpolation) {
        return interpolation == Interpolation::Biquadratic ? 0.0 : 0.5;
    }
    // The patch of cell (i, j), its samples wrapped in i when `wrapU`, clamped otherwise.
    static SurfacePatch at(const HeightMap& map, int i, int j, bool wrapU,
                           Interpolation interpolation);
    // The same over a map addressed as `addressing` has it (tiled: i, j over the whole).
    static SurfacePatch at(const HeightMap& map, int i, int j, const MapAddressing& addressing,
                           Interpolation interpolation);

    double height(glm::dvec2 f) const;
    glm::dvec2 gradient(glm::dvec2 f) const;  // (dh/dX, dh/dY), per texel
    // The patch's max over the local rectangle [lo, hi] (clamped to the cell), never below
    // it: a bilinear patch peaks at a corner of any rectangle; a biquadratic one lies in the
    // convex hull of the rectangle's Bezier net (biquadratic_patch.glsl).
    double maxOver(glm::dvec2 lo, glm::dvec2 hi) const;

    // Biquadratic only: the Bernstein coefficients over s in [0, 1] of the quartic
    // g(s) = height(f(s)) - z(s) along the straight path from local point fa to fb (x, y:
    // local coordinates, z: the ray's height, each linear in s). biquadratic_patch.glsl:
    // biquadraticPathGap.
    using Quartic = std::array<double, 5>;
    Quartic pathGap(const glm::dvec3& fa, const glm::dvec3& fb) const;
};

// The first s in [0, 1] where the parabola through (0, ga), (1/2, gm), (1, gb) reaches 0,
// or nullopt: a sign change at the ends or the middle interpolated; without one, a concave
// parabola that reaches 0 is a touching ray, a hit in the closed solid
// (final_piece.glsl: mr_parabolaFirstRoot). The final pieces of the leaves' subdivisions.
std::optional<double> parabolaFirstRoot(double ga, double gm, double gb);

// A quartic's Bernstein coefficients over [sa, sb] from those over [0, 1] (de Casteljau),
// its value at s, and its first point with g(s) >= 0, or nullopt: the pieces in order, each
// skipped when all its coefficients are below -margin (the convex hull bounds the quartic),
// a rising piece solved by regula falsi, others halved down to `finalWidth` and solved by
// the parabola through their ends and middle (biquadratic_patch.glsl: mr_quarticFirstHit).
SurfacePatch::Quartic quarticPiece(const SurfacePatch::Quartic& q, double sa, double sb);
double quarticValue(const SurfacePatch::Quartic& q, double s);
std::optional<double> quarticFirstHit(const SurfacePatch::Quartic& q, double finalWidth,
                                      double margin);

}  // namespace microrelief
