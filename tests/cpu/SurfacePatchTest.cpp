// SurfacePatch, the C++ mirror of relief_patch.glsl that the twin's leaf walks: its height
// is the map's surface for either interpolation, its gradient the surface's derivative,
// and maxOver, the bound the leaf skips sub-rectangles by, never below the patch over any
// rectangle (a bilinear patch peaks at a corner; a biquadratic one lies in the convex hull
// of the Bezier net of its restriction to the rectangle).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "microrelief/core/heightmap/SurfacePatch.h"
#include "microrelief/core/synth/SyntheticMaps.h"

using namespace microrelief;

namespace {

struct Cell {
    SurfacePatch patch;
    glm::dvec2 corner;  // map point of local (0, 0)
};

Cell cellAt(const HeightMap& map, int i, int j, bool wrapU, Interpolation interpolation) {
    const double offset = SurfacePatch::offset(interpolation);
    return {SurfacePatch::at(map, i, j, wrapU, interpolation), {i + offset, j + offset}};
}

}  // namespace

TEST(SurfacePatch, IsTheMapsSurfaceAndItsDerivative) {
    const HeightMap map = synth::whiteNoise(7, 5, 3);
    std::mt19937 random(5);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (const Interpolation interpolation :
         {Interpolation::Bilinear, Interpolation::Biquadratic}) {
        for (const bool wrapU : {false, true}) {
            for (int j = -1; j < map.height; ++j) {
                for (int i = -1; i < map.width; ++i) {
                    const Cell c = cellAt(map, i, j, wrapU, interpolation);
                    for (int k = 0; k < 20; ++k) {
                        // Inside the cell (off its edges, where the surface's finite
                        // differences would straddle two patches).
                        const glm::dvec2 f{0.01 + 0.98 * unit(random), 0.01 + 0.98 * unit(random)};
                        const glm::dvec2 x = c.corner + f;
                        const auto h = [&](glm::dvec2 q) {
                            return map.surface(q.x, q.y, wrapU, interpolation);
                        };
                        // The clamped map's bilinear cells beyond the edge rows are clamped
                        // copies; only points on the map compare.
                        if (x.x < 0.0 || x.y < 0.0 || x.x > map.width || x.y > map.height) continue;
                        ASSERT_NEAR(c.patch.height(f), h(x), 1e-12);
                        const double e = 1e-6;
                        const glm::dvec2 numeric(
                            (h(x + glm::dvec2(e, 0)) - h(x - glm::dvec2(e, 0))) / (2 * e),
                            (h(x + glm::dvec2(0, e)) - h(x - glm::dvec2(0, e))) / (2 * e));
                        ASSERT_NEAR(c.patch.gradient(f).x, numeric.x, 1e-6);
                        ASSERT_NEAR(c.patch.gradient(f).y, numeric.y, 1e-6);
                    }
                }
            }
        }
    }
}

// Random cells of noise and of a spike, random sub-rectangles from slivers to the whole
// cell: maxOver is at least the densely sampled max, never more than the cell's own bound
// (maxOver of the whole cell), and for the biquadratic patch close to the max on small
// rectangles (the restricted net converges to the patch as the rectangle shrinks).
TEST(SurfacePatch, MaxOverBoundsThePatchOnAnyRectangle) {
    std::mt19937 random(11);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const std::vector<HeightMap> maps = {synth::whiteNoise(6, 6, 8), synth::spike(6, 6, 3, 2),
                                         synth::cobbles(8, 8, 2)};
    for (const Interpolation interpolation :
         {Interpolation::Bilinear, Interpolation::Biquadratic}) {
        for (const HeightMap& map : maps) {
            for (int trial = 0; trial < 3000; ++trial) {
                const int i = static_cast<int>(unit(random) * map.width);
                const int j = static_cast<int>(unit(random) * map.height);
                const SurfacePatch patch = SurfacePatch::at(map, i, j, true, interpolation);
                const double size = std::pow(unit(random), 3.0);
                glm::dvec2 lo{unit(random), unit(random)};
                lo *= 1.0 - size;
                const glm::dvec2 hi = lo + size * glm::dvec2{unit(random), unit(random)};
                double sampled = 0.0;
                for (int b = 0; b <= 20; ++b)
                    for (int a = 0; a <= 20; ++a)
                        sampled = std::max(sampled,
                                           patch.height(lo + (hi - lo) * glm::dvec2(a, b) / 20.0));
                const double bound = patch.maxOver(lo, hi);
                ASSERT_GE(bound, sampled - 1e-12)
                    << interpolationName(interpolation) << " cell " << i << "," << j << " [" << lo.x
                    << "," << lo.y << "]-[" << hi.x << "," << hi.y << "]";
                ASSERT_LE(bound, patch.maxOver({0, 0}, {1, 1}) + 1e-12);
                // Tight on small rectangles: within the patch's second-order change over them.
                if (size < 0.05) {
                    ASSERT_LE(bound - sampled, 4.0 * size * size + 1e-9) << size;
                }
            }
        }
    }
}

namespace {

// A random straight path across a biquadratic texel square of white noise: local (u, v)
// ends anywhere in the square, the ray's height at each end anywhere in [0, 1].
struct Path {
    SurfacePatch patch;
    glm::dvec3 fa, fb;
    double gap(double s) const {
        const glm::dvec3 f = glm::mix(fa, fb, s);
        return patch.height(glm::dvec2(f)) - f.z;
    }
};

Path randomPath(const HeightMap& map, std::mt19937& random) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::uniform_int_distribution<int> cell(-1, map.width - 1);
    const SurfacePatch patch =
        SurfacePatch::at(map, cell(random), cell(random), false, Interpolation::Biquadratic);
    return {patch,
            {unit(random), unit(random), unit(random)},
            {unit(random), unit(random), unit(random)}};
}

}  // namespace

// pathGap's quartic is the patch minus the ray along the path, quarticPiece's coefficients
// are the same quartic over a sub-piece, and their convex hull bounds it there: the bound
// the plane's biquadratic leaf skips pieces by (biquadratic_patch.glsl: mr_quarticFirstHit).
TEST(SurfacePatch, PathGapIsTheGapAndItsPiecesHullsBoundIt) {
    const HeightMap map = synth::whiteNoise(9, 9, 11);
    std::mt19937 random(3);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int k = 0; k < 2000; ++k) {
        const Path path = randomPath(map, random);
        const SurfacePatch::Quartic q = path.patch.pathGap(path.fa, path.fb);
        for (int n = 0; n <= 16; ++n)
            ASSERT_NEAR(quarticValue(q, n / 16.0), path.gap(n / 16.0), 1e-12) << k << " " << n;
        double sa = unit(random), sb = unit(random);
        if (sa > sb) std::swap(sa, sb);
        const SurfacePatch::Quartic piece = quarticPiece(q, sa, sb);
        const double hull = *std::max_element(piece.begin(), piece.end());
        for (int n = 0; n <= 32; ++n) {
            const double s = sa + (sb - sa) * n / 32.0;
            ASSERT_NEAR(quarticValue(piece, n / 32.0), quarticValue(q, s), 1e-12) << k;
            ASSERT_LE(quarticValue(q, s), hull + 1e-12) << k << " [" << sa << ", " << sb << "]";
        }
    }
}

// quarticFirstHit finds the first zero of the gap, against a dense scan refined by
// bisection: the same hit or miss unless the path only grazes the patch, and the same
// point to within the final piece's parabola.
TEST(SurfacePatch, QuarticFirstHitIsTheFirstPointInTheSolid) {
    const HeightMap map = synth::whiteNoise(9, 9, 12);
    std::mt19937 random(4);
    int hits = 0, grazes = 0;
    for (int k = 0; k < 3000; ++k) {
        const Path path = randomPath(map, random);
        const auto found = quarticFirstHit(path.patch.pathGap(path.fa, path.fb), 1.0 / 64.0, 0.0);
        std::optional<double> expected;
        double top = path.gap(0.0);
        constexpr int kScan = 4096;
        for (int n = 0; n <= kScan && !expected; ++n) {
            const double s = static_cast<double>(n) / kScan;
            top = std::max(top, path.gap(s));
            if (path.gap(s) < 0.0) continue;
            double lo = std::max(0.0, s - 1.0 / kScan), hi = s;
            if (n == 0) lo = hi = 0.0;
            for (int b = 0; b < 50; ++b)
                (path.gap(0.5 * (lo + hi)) < 0.0 ? lo : hi) = 0.5 * (lo + hi);
            expected = hi;
        }
        if (expected.has_value() != found.has_value() ||
            (expected && std::abs(*expected - *found) > 1e-3)) {
            // Only where the path grazes the patch: the gap's top within the scan's reach of 0.
            ASSERT_LT(std::abs(top), 1e-4) << k << ": expected " << (expected ? *expected : -1.0)
                                           << ", found " << (found ? *found : -1.0);
            ++grazes;
            continue;
        }
        if (expected) {
            ++hits;
            ASSERT_GE(path.gap(*found), -1e-4) << k << " at " << *found;
        }
    }
    EXPECT_GT(hits, 500);
    EXPECT_LT(grazes, 10);
}
