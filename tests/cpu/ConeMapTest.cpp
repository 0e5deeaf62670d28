// The cone maps of the cone-stepping peers (peers/ConeMap.h). The property `cone` relies
// on: no conservative cone holds a point of the bilinear surface, checked against an
// independent reference (HeightMap::surface, the spec's bilinear surface, sampled densely:
// every eighth of a texel, which takes in every texel corner, edge midpoint and sample,
// where a bilinear patch's edges and peaks reach their maxima); and the fast build, the
// pyramid walk, never gives a wider cone than the brute force over every texel square.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "ConeCases.h"
#include "microrelief/core/heightmap/MaxPyramid.h"
#include "microrelief/peers/ConeMap.h"

using namespace microrelief;
using microrelief::test::ConeCase;
using microrelief::test::coneCases;

namespace {

double distanceToSquare(double x, double y, int i, int j) {
    const double gx = std::max({0.0, i - x, x - (i + 1)}), gy = std::max({0.0, j - y, y - (j + 1)});
    return std::hypot(gx, gy);
}

// The surface (either last level) on the dense grid: every 1/kDense texel.
constexpr int kDense = 8;
struct DenseSurface {
    int nx, ny;
    std::vector<double> h;
    explicit DenseSurface(const HeightMap& map,
                          Interpolation interpolation = Interpolation::Bilinear)
        : nx(map.width * kDense + 1),
          ny(map.height * kDense + 1),
          h(static_cast<std::size_t>(nx) * ny) {
        for (int b = 0; b < ny; ++b)
            for (int a = 0; a < nx; ++a)
                h[static_cast<std::size_t>(b) * nx + a] =
                    map.surface(double(a) / kDense, double(b) / kDense, false, interpolation);
    }
};

// The dense reference's r* of square (i, j) at plateau B: the smallest dist / (h - B) over
// the grid's points above B (an upper estimate of the exact inf: the grid holds a subset of
// the surface's points).
double sampledRatio(const DenseSurface& s, int i, int j, double plateau) {
    double r = kConeRatioCap;
    for (int b = 0; b < s.ny; ++b) {
        for (int a = 0; a < s.nx; ++a) {
            const double h = s.h[static_cast<std::size_t>(b) * s.nx + a];
            if (h > plateau)
                r = std::min(r, distanceToSquare(double(a) / kDense, double(b) / kDense, i, j) /
                                    (h - plateau));
        }
    }
    return r;
}

class ConeMapCases : public ::testing::TestWithParam<ConeCase> {};

}  // namespace

// The stored cones (what the GPU reads) hold no point of the surface: for every texel T
// and every reference point x, h(x) <= B_T + dist(x, T) / r_T (h <= B_T on T itself,
// whatever r_T: a cone of ratio 0 is T's column above B_T). The slack, 1e-9 of the
// distance, is for the doubles of this check; a cone that is wrong by its build is off by
// far more (a skipped level or a plateau at the sample instead of the bound: texels).
TEST_P(ConeMapCases, ConservativeConesHoldNoSurface) {
    const HeightMap& map = GetParam().map;
    const ConeMap cones = buildConservativeConeMap(map);
    const DenseSurface dense(map);
    double narrowing = 0.0;
    int counted = 0;
    for (int j = 0; j < map.height; ++j) {
        for (int i = 0; i < map.width; ++i) {
            const double plateau = cones.apexAt(i, j), r = cones.ratioAt(i, j);
            EXPECT_GE(plateau, texelSquareBound(map, i, j, false)) << "texel " << i << ", " << j;
            ASSERT_GE(r, 0.0);
            int violations = 0;
            for (int b = 0; b < dense.ny; ++b) {
                for (int a = 0; a < dense.nx; ++a) {
                    const double h = dense.h[static_cast<std::size_t>(b) * dense.nx + a];
                    const double d = distanceToSquare(double(a) / kDense, double(b) / kDense, i, j);
                    // How high the cone lets the surface rise here: not above B on T itself
                    // (d = 0, whatever r), d / r elsewhere (no limit where r is 0: a column).
                    const double allowed = d == 0.0 ? 0.0 : r > 0.0 ? d / r : HUGE_VAL;
                    if (h - plateau > allowed * (1.0 + 1e-9)) {
                        if (++violations <= 2)
                            ADD_FAILURE() << "texel (" << i << ", " << j << ") plateau " << plateau
                                          << " ratio " << r << " holds surface point ("
                                          << double(a) / kDense << ", " << double(b) / kDense
                                          << ") h " << h << " at distance " << d;
                    }
                }
            }
            ASSERT_EQ(violations, 0);
            const double exact = sampledRatio(dense, i, j, plateau);
            if (exact > 0.0 && exact < kConeRatioCap) {
                narrowing += r / exact;
                ++counted;
            }
        }
    }
    if (counted > 0)
        std::cout << GetParam().name << ": stored ratio / dense reference's r* "
                  << narrowing / counted << " on average over " << counted << " texels\n";
}

// The pyramid walk gives the brute force's cones: never wider (the walk prunes only nodes
// whose bound cannot narrow the cone), and the same in practice (both take the same piece
// bounds; 1e-12 relative for the doubles' rounding where a prune test and a piece bound
// meet).
// `cone` runs on the biquadratic last level too, from the same cone map with each apex
// raised by 1/2 texel over the ratio (shaders/microrelief/cone_step.glsl,
// mr_coneOfLastLevel, says why that holds: the B-spline is the bilinear surface averaged
// over a unit square). Checked here against the biquadratic surface sampled densely: no
// raised cone holds a point of it. The cones as built, not raised, held none on these maps
// either (counted and printed): the raise is what the argument needs, not what a map was
// seen to need.
TEST_P(ConeMapCases, RaisedConesHoldNoBiquadraticSurface) {
    const HeightMap& map = GetParam().map;
    const ConeMap cones = buildConservativeConeMap(map);
    const DenseSurface dense(map, Interpolation::Biquadratic);
    int violations = 0, unraised = 0;
    for (int j = 0; j < map.height; ++j) {
        for (int i = 0; i < map.width; ++i) {
            const double r = cones.ratioAt(i, j);
            const double plateau = cones.apexAt(i, j),
                         raised = r > 0.0 ? plateau + 0.5 / r : HUGE_VAL;
            for (int b = 0; b < dense.ny; ++b) {
                for (int a = 0; a < dense.nx; ++a) {
                    const double h = dense.h[static_cast<std::size_t>(b) * dense.nx + a];
                    const double d = distanceToSquare(double(a) / kDense, double(b) / kDense, i, j);
                    const double allowed = d == 0.0 ? 0.0 : r > 0.0 ? d / r : HUGE_VAL;
                    if (h - plateau > allowed * (1.0 + 1e-9)) ++unraised;
                    if (h - raised > allowed * (1.0 + 1e-9) && ++violations <= 2)
                        ADD_FAILURE() << "texel (" << i << ", " << j << ") plateau " << plateau
                                      << " raised to " << raised << ", ratio " << r
                                      << ", holds biquadratic point (" << double(a) / kDense << ", "
                                      << double(b) / kDense << ") h " << h << " at distance " << d;
                }
            }
        }
    }
    EXPECT_EQ(violations, 0);
    std::cout << GetParam().name << ": biquadratic points inside the unraised cones: " << unraised
              << "\n";
}

TEST_P(ConeMapCases, FastBuildIsNeverWiderThanBruteForce) {
    const HeightMap& map = GetParam().map;
    ConeMapStats stats;
    const std::vector<double> fast = conservativeConeRatios(map, false, &stats);
    const std::vector<double> brute = conservativeConeRatios(map, true);
    ASSERT_EQ(fast.size(), brute.size());
    int narrower = 0;
    double ratioSum = 0.0;
    for (std::size_t k = 0; k < fast.size(); ++k) {
        EXPECT_LE(fast[k], brute[k] * (1.0 + 1e-12))
            << "texel " << k % map.width << ", " << k / map.width;
        if (fast[k] < brute[k] * (1.0 - 1e-12)) ++narrower;
        ratioSum += brute[k] > 0.0 ? fast[k] / brute[k] : 1.0;
    }
    std::cout << GetParam().name << ": fast / brute force " << ratioSum / fast.size()
              << " on average, " << narrower << " of " << fast.size() << " narrower; "
              << stats.nodesVisited << " nodes visited (" << fast.size() * fast.size()
              << " squares by brute force)\n";
}

INSTANTIATE_TEST_SUITE_P(Maps, ConeMapCases, ::testing::ValuesIn(coneCases()),
                         [](const auto& info) { return info.param.name; });

// The relaxed cones as published: each a ratio >= 0 on the half grid, its apex the sample
// to the nearest half; a relaxed cone is never narrower than a cone whose apex sits at
// the sample and that holds no sample higher than it (the relaxed exit point lies past the
// sample that made it, no higher), nor wider than the published widest, ratio 1 in texture
// coordinates (one map width per map height unit), which a sample with nothing higher
// keeps. (Seen failing with the cap at the half float's largest: a thin wall at the map's
// top then sends rcsm's rays through it, its cones read bilinearly beside the floor's.)
TEST(ConeMap, RelaxedConesAreAtLeastTheSampleCones) {
    for (const ConeCase& c : coneCases()) {
        const HeightMap& map = c.map;
        const ConeMap cones = buildRelaxedConeMap(map);
        const double cap = relaxedRatioCap(map), top = map.maxValue();
        EXPECT_EQ(cap, std::min(map.width, map.height)) << c.name;
        for (int j = 0; j < map.height; ++j) {
            for (int i = 0; i < map.width; ++i) {
                const double hs = map.at(i, j);
                EXPECT_LE(std::abs(cones.apexAt(i, j) - hs), std::abs(hs) * 0x1p-11 + 0x1p-25)
                    << c.name;
                EXPECT_LE(cones.ratioAt(i, j), cap) << c.name << " texel " << i << ", " << j;
                if (hs == top) {
                    EXPECT_EQ(cones.ratioAt(i, j), halfRoundedDown(cap))
                        << c.name << " texel " << i << ", " << j;
                }
                double sampleCone = cap;
                for (int q = 0; q < map.height; ++q)
                    for (int p = 0; p < map.width; ++p)
                        if (map.at(p, q) > hs)
                            sampleCone = std::min(sampleCone,
                                                  std::hypot(p - i, q - j) / (map.at(p, q) - hs));
                EXPECT_GE(cones.ratioAt(i, j), halfRoundedDown(sampleCone))
                    << c.name << " texel " << i << ", " << j;
            }
        }
    }
}

// The pyramid walk skips only pairs that cannot narrow a relaxed cone: the same ratios as
// every pair by brute force (to the doubles' rounding where a prune test meets a pair).
TEST(ConeMap, RelaxedWalkGivesTheBruteForceCones) {
    for (const ConeCase& c : coneCases()) {
        const std::vector<double> fast = relaxedConeRatios(c.map, 128, false),
                                  brute = relaxedConeRatios(c.map, 128, true);
        for (std::size_t k = 0; k < fast.size(); ++k)
            EXPECT_NEAR(fast[k], brute[k], 1e-12 * brute[k]) << c.name << " texel " << k;
    }
}

// A build reports its rows as it goes: after each row, the fraction done, ending at 1; and
// reporting changes no cone.
TEST(ConeMap, BuildsReportTheirRowsAsTheyGo) {
    const std::vector<ConeCase> cases = coneCases();
    const ConeCase& c = cases.front();
    for (const bool relaxed : {false, true}) {
        std::vector<double> reported;
        const ConeMapProgress progress = [&](double done) { reported.push_back(done); };
        const ConeMap cones = relaxed ? buildRelaxedConeMap(c.map, 128, nullptr, progress)
                                      : buildConservativeConeMap(c.map, nullptr, progress);
        ASSERT_EQ(reported.size(), std::size_t(c.map.height)) << c.name;
        for (std::size_t k = 0; k < reported.size(); ++k)
            EXPECT_EQ(reported[k], double(k + 1) / c.map.height) << c.name << " row " << k;
        const ConeMap quiet =
            relaxed ? buildRelaxedConeMap(c.map) : buildConservativeConeMap(c.map);
        EXPECT_EQ(cones.ratio, quiet.ratio);
        EXPECT_EQ(cones.apex, quiet.apex);
    }
}

TEST(ConeMap, HalfFloatRounding) {
    EXPECT_EQ(halfBits(1.0f), 0x3c00);
    EXPECT_EQ(halfBits(65504.0f), 0x7bff);
    EXPECT_EQ(halfBits(std::ldexp(1.0f, -24)), 0x0001);
    EXPECT_EQ(halfBits(std::ldexp(1.0f, -14)), 0x0400);
    EXPECT_EQ(halfBits(halfRoundedUp(1.0 + 1e-6)), 0x3c01);
    EXPECT_EQ(halfRoundedDown(1.0 + 1e-6), 1.0f);
    EXPECT_EQ(halfRoundedUp(1e6), std::numeric_limits<float>::infinity());
    EXPECT_EQ(halfRoundedDown(1e6), 65504.0f);
    std::mt19937 random(3);
    std::uniform_real_distribution<double> exponent(-26.0, 16.0);
    for (int k = 0; k < 10000; ++k) {
        const double x = std::exp2(exponent(random));
        const float down = halfRoundedDown(x), up = halfRoundedUp(x);
        ASSERT_LE(down, x);
        ASSERT_GE(up, x);
        if (up <= 65504.0f) {
            ASSERT_LE(up - down, std::max(std::abs(x) * 0x1p-10, 0x1p-24)) << x;
            // On the grid: the bits give the value back (GL decodes them so).
            const std::uint16_t bits = halfBits(up);
            const int e = (bits >> 10) & 31, m = bits & 1023;
            const double decoded =
                e == 0 ? std::ldexp(m, -24) : std::ldexp(1.0 + m / 1024.0, e - 15);
            ASSERT_EQ(decoded, double(up)) << x;
        }
    }
}
