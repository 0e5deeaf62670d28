// The multilevel elevation map: its shape for any size, and the property the tracer
// relies on: over any footprint, the max it reports bounds every height of the
// bilinear surface inside that footprint.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <utility>

#include "microrelief/core/heightmap/MaxPyramid.h"
#include "microrelief/core/synth/SyntheticMaps.h"

using namespace microrelief;

namespace {

// The max of surface(x, y) over [x0, x1] x [y0, y1], by dense sampling (a lower bound of
// the true max, which is what a bound must exceed).
template <class Surface>
double denseMax(const Surface& surface, double x0, double y0, double x1, double y1, int steps) {
    double best = 0.0;
    for (int b = 0; b <= steps; ++b) {
        for (int a = 0; a <= steps; ++a)
            best = std::max(best, surface(x0 + (x1 - x0) * a / steps, y0 + (y1 - y0) * b / steps));
    }
    return best;
}

double sampledMax(const HeightMap& map, double x0, double y0, double x1, double y1, int steps) {
    return denseMax([&](double x, double y) { return map.surface(x, y); }, x0, y0, x1, y1, steps);
}

// A random footprint [lo, hi] over a w x h map, from a point to up to the map's longer
// side on (short ones more often): past X = w only on a wrapped map, and never more than
// once round.
std::pair<glm::dvec2, glm::dvec2> randomFootprint(std::mt19937& random, int w, int h, bool wrapU) {
    std::uniform_real_distribution<double> x(0.0, w), y(0.0, h), unit(0.0, 1.0);
    const glm::dvec2 lo(x(random), y(random));
    const double reach = std::max(w, h) * unit(random) * unit(random);
    glm::dvec2 hi = lo + reach * glm::dvec2{unit(random), unit(random)};
    hi.y = std::min(hi.y, static_cast<double>(h));
    hi.x = std::min(hi.x, wrapU ? lo.x + w - 1e-9 : static_cast<double>(w));
    return {lo, hi};
}

// Every block the max of the finest texels it covers (to the map's edge for the last of a
// row or column), every window the max of the 2 x 2 blocks from it on: by brute force.
void expectBlocksAndWindowsFromTheFinest(const MaxPyramid& p, const HeightMap& map) {
    for (int level = 0; level < p.windowLevelCount(); ++level) {
        const int w = p.windowLevelWidth(level), h = p.windowLevelHeight(level);
        for (int q = 0; q < h; ++q) {
            for (int pp = 0; pp < w; ++pp) {
                // The block: finest texels from (pp, q) << level, to the map's edge for
                // the last of a row or column.
                const int x1 = pp == w - 1 ? map.width : (pp + 1) << level;
                const int y1 = q == h - 1 ? map.height : (q + 1) << level;
                float block = 0.0f;
                for (int j = q << level; j < y1; ++j)
                    for (int i = pp << level; i < x1; ++i)
                        block = std::max(block, p.block(0, i, j));
                ASSERT_EQ(p.block(level, pp, q), block) << level << ": " << pp << "," << q;
                float window = 0.0f;
                for (int dq = 0; dq < 2; ++dq)
                    for (int dp = 0; dp < 2; ++dp)
                        if (pp + dp < w && q + dq < h)
                            window = std::max(window, p.block(level, pp + dp, q + dq));
                ASSERT_EQ(p.window(level, pp, q), window) << level << ": " << pp << "," << q;
            }
        }
    }
}

}  // namespace

TEST(MaxPyramid, LevelSizesForOddNonSquareMaps) {
    const MaxPyramid p(HeightMap(300, 77));
    // The windows: GL's mip sizes of 300 x 77, no padding.
    ASSERT_EQ(p.windowLevelCount(), 9);
    EXPECT_EQ(p.windowLevelWidth(0), 300);
    EXPECT_EQ(p.windowLevelHeight(0), 77);
    EXPECT_EQ(p.windowLevelWidth(3), 37);
    EXPECT_EQ(p.windowLevelHeight(3), 9);
    EXPECT_EQ(p.windowLevelWidth(8), 1);
    EXPECT_EQ(p.windowLevelHeight(8), 1);
}

TEST(MaxPyramid, OneByOneAndTwoByTwo) {
    HeightMap one(1, 1, 0.4f);
    const MaxPyramid p1(one);
    ASSERT_EQ(p1.windowLevelCount(), 1);
    EXPECT_FLOAT_EQ(p1.block(0, 0, 0), 0.4f);
    EXPECT_FLOAT_EQ(p1.maxHeight(), 0.4f);

    HeightMap two(2, 2);
    two.samples = {0.0f, 1.0f, 0.25f, 0.5f};
    const MaxPyramid p2(two);
    ASSERT_EQ(p2.windowLevelCount(), 2);
    // Texel (0, 0) covers [0, 1]^2: the surface there peaks at its corner (1, 1), the
    // average of all four samples, or at the sample (0,0) itself, or an edge midpoint
    // (1, 0.5): the average of samples 0 and 1 = 0.5.
    EXPECT_FLOAT_EQ(p2.block(0, 0, 0), 0.5f);
    EXPECT_FLOAT_EQ(p2.block(0, 1, 0), 1.0f);
    EXPECT_FLOAT_EQ(p2.block(1, 0, 0), 1.0f);
}

TEST(MaxPyramid, FinestLevelIsTheExactSurfaceMaxOverEachTexel) {
    const HeightMap map = synth::whiteNoise(9, 7, 11);
    const MaxPyramid p(map);
    for (int j = 0; j < map.height; ++j) {
        for (int i = 0; i < map.width; ++i) {
            const double dense = sampledMax(map, i, j, i + 1, j + 1, 40);
            // Exact: as high as any sampled point, and attained (the dense grid hits the
            // nine candidate points, so the two agree to rounding).
            EXPECT_GE(p.block(0, i, j) + 1e-6, dense);
            EXPECT_NEAR(p.block(0, i, j), dense, 1e-6) << i << "," << j;
        }
    }
}

// The bound the traversal reads for a segment from a to b (segmentBound, the C++
// mirror of max_pyramid.glsl), at the level the traversal picks for it.
double traversalBound(const MaxPyramid& p, glm::dvec2 a, glm::dvec2 b, int* fetches = nullptr,
                      int* level = nullptr) {
    const BoundRead read = p.segmentBound(a, b);
    if (fetches) *fetches = read.fetches;
    if (level) *level = read.level;
    return read.bound;
}

// The surface's max along the segment's path, densely sampled: what a bound must exceed.
double sampledMaxAlong(const HeightMap& map, glm::dvec2 a, glm::dvec2 b, int steps) {
    double best = 0.0;
    for (int k = 0; k <= steps; ++k) {
        const glm::dvec2 p = a + (b - a) * (static_cast<double>(k) / steps);
        best = std::max(best, map.surface(p.x, p.y));
    }
    return best;
}

// The property test: random maps of odd, non-power-of-two, non-square sizes, random
// segments of every length and direction; the bound, one fetch at a level no coarser
// than one step above the footprint's (its texels at least half the footprint wide),
// must never fall below the surface anywhere along the segment.
TEST(MaxPyramid, SegmentBoundCoversTheSurfaceAlongAnySegment) {
    std::mt19937 random(1234);
    const std::vector<std::pair<int, int>> sizes = {{1, 1},   {2, 2},   {3, 5},  {17, 4},
                                                    {31, 33}, {64, 64}, {100, 7}};
    for (auto [w, h] : sizes) {
        const HeightMap map = synth::whiteNoise(w, h, static_cast<std::uint32_t>(w * 131 + h));
        const MaxPyramid p(map);
        std::uniform_real_distribution<double> x(0.0, w), y(0.0, h), unit(0.0, 1.0),
            turn(0.0, 6.2831853);
        for (int trial = 0; trial < 2000; ++trial) {
            // Lengths spread over scales, from a sliver to the whole map.
            const double length = std::pow(std::max(w, h) * 1.5, unit(random)) * unit(random);
            const double angle = turn(random);
            const glm::dvec2 a(x(random), y(random));
            const glm::dvec2 b =
                glm::clamp(a + length * glm::dvec2(std::cos(angle), std::sin(angle)),
                           glm::dvec2(0.0), glm::dvec2(w, h));
            int fetches = 0, level = -1;
            const double bound = traversalBound(p, a, b, &fetches, &level);
            ASSERT_GE(bound, sampledMaxAlong(map, a, b, 400) - 1e-12)
                << w << "x" << h << " segment (" << a.x << "," << a.y << ") -> (" << b.x << ","
                << b.y << ")";
            ASSERT_EQ(fetches, 1);
            const double extent = std::max(std::abs(b.x - a.x), std::abs(b.y - a.y));
            ASSERT_TRUE(level == 0 || std::ldexp(1.0, level) <= 2.0 * (extent + 1.0))
                << "level " << level << " for a footprint " << extent << " wide";
        }
    }
}

// A one-texel spike: the case a sample-only pyramid or a centre fetch gets wrong
// (the spike's peak lies between the footprint's sample centres).
TEST(MaxPyramid, ASpikeIsSeenByEverySegmentOverItsSlopes) {
    const HeightMap map = synth::spike(16, 16, 7, 9);
    const MaxPyramid p(map);
    // A short segment across the spike's slope only (X in [8.2, 8.3]): the surface there
    // reaches 1 - 0.7 = 0.3 at the sample row.
    EXPECT_GE(traversalBound(p, {8.2, 9.5}, {8.3, 9.5}), 0.3 - 1e-6);
    EXPECT_DOUBLE_EQ(traversalBound(p, {0.0, 0.0}, {16.0, 16.0}), 1.0);
    EXPECT_DOUBLE_EQ(traversalBound(p, {0.5, 0.5}, {4.5, 4.0}), 0.0);
}

TEST(MaxPyramid, FinestLevelNeverRoundsBelowTheSurface) {
    // Averages of samples that do not sum exactly in float: the bound is rounded up.
    HeightMap map(2, 2);
    map.samples = {0.1f, 0.7f, 0.3f, 0.9f};
    const MaxPyramid p(map);
    for (int j = 0; j < 2; ++j) {
        for (int i = 0; i < 2; ++i) {
            for (int k = 0; k <= 100; ++k) {
                for (int l = 0; l <= 100; ++l) {
                    ASSERT_GE(static_cast<double>(p.block(0, i, j)),
                              map.surface(i + k / 100.0, j + l / 100.0));
                }
            }
        }
    }
}

TEST(MaxPyramid, WindowLevelIsTheFinestWhoseWindowHoldsTheFootprint) {
    const MaxPyramid p(HeightMap(64, 64));
    EXPECT_EQ(p.windowLevel({5, 5}, {5, 5}), 0);    // one texel
    EXPECT_EQ(p.windowLevel({5, 5}, {6, 6}), 0);    // 2 x 2 texels from 5: window 0
    EXPECT_EQ(p.windowLevel({5, 5}, {7, 5}), 1);    // 5..7: level-1 texels 2..3
    EXPECT_EQ(p.windowLevel({3, 0}, {5, 0}), 1);    // 3..5: level-1 texels 1..2
    EXPECT_EQ(p.windowLevel({8, 8}, {15, 15}), 2);  // 8 wide, aligned: level-2 texels 2..3
    EXPECT_EQ(p.windowLevel({7, 0}, {15, 0}), 3);   // 9 wide: level-3 texels 0..1
    EXPECT_EQ(p.windowLevel({31, 0}, {32, 0}), 0);  // across the middle, still window 0
    EXPECT_EQ(p.windowLevel({0, 0}, {63, 63}), 5);  // the whole map: 2 x 2 level-5 texels
}

// The windows (issue 16: no padding): GL's mip sizes of W x H; each block the max of the
// finest texels it covers, the last of a row or column reaching to the map's edge; each
// window the max of the 2 x 2 blocks from it on.
TEST(MaxPyramid, WindowsAreTheMaxOfTwoByTwoBlocksWithoutPadding) {
    const HeightMap map = synth::whiteNoise(13, 6, 77);
    for (const BoundPrecision precision : {BoundPrecision::Float, BoundPrecision::Half}) {
        const MaxPyramid p(map, false, precision);
        ASSERT_EQ(p.windowLevelCount(), 4);  // 13 x 6, 6 x 3, 3 x 1, 1 x 1
        EXPECT_EQ(p.windowLevelWidth(1), 6);
        EXPECT_EQ(p.windowLevelHeight(1), 3);
        EXPECT_EQ(p.windowLevelWidth(2), 3);
        EXPECT_EQ(p.windowLevelHeight(2), 1);
        expectBlocksAndWindowsFromTheFinest(p, map);
        // The top: the largest finest bound.
        const std::vector<float>& finest = p.blockLevelData(0);
        EXPECT_EQ(p.window(p.windowLevelCount() - 1, 0, 0),
                  *std::max_element(finest.begin(), finest.end()));
    }
}

// A map large enough to be built in bands (ParallelRows.h: work over 65536 cells is split,
// on a machine of more than one core) is built as one loop would build it: each finest
// texel is texelSquareBound of its samples, stored, and the levels above by brute force
// from them. Level 1 too is split (192k blocks).
// texelSquareBound reads the samples inside the map directly, and through sample()'s
// clamping or wrapping at its edges: the same bits as the Bezier net's max taken here on
// sample() everywhere, on every texel of an odd map, clamped and wrapped, and across
// tiles.
TEST(MaxPyramid, TexelSquareBoundIsTheNetOfTheSamplesSampleGives) {
    const HeightMap map = synth::whiteNoise(13, 7, 3);
    for (const MapAddressing addressing :
         {MapAddressing{false}, MapAddressing{true}, MapAddressing{true, 2, 3}}) {
        const int w = map.width * addressing.tilesX, h = map.height * addressing.tilesY;
        for (int j = -1; j <= h; ++j) {
            for (int i = -1; i <= w; ++i) {
                float rows[3][3];
                for (int b = 0; b < 3; ++b) {
                    const float c0 = map.sample(i - 1, j - 1 + b, addressing),
                                c1 = map.sample(i, j - 1 + b, addressing),
                                c2 = map.sample(i + 1, j - 1 + b, addressing);
                    rows[b][0] = roundUpMean(c0, c1);
                    rows[b][1] = c1;
                    rows[b][2] = roundUpMean(c1, c2);
                }
                float best = 0.0f;
                for (int a = 0; a < 3; ++a) {
                    best = std::max({best, roundUpMean(rows[0][a], rows[1][a]), rows[1][a],
                                     roundUpMean(rows[1][a], rows[2][a])});
                }
                ASSERT_EQ(std::bit_cast<std::uint32_t>(texelSquareBound(map, i, j, addressing)),
                          std::bit_cast<std::uint32_t>(best))
                    << i << "," << j << " wrap " << addressing.wrapU << " tiles "
                    << addressing.tilesX;
            }
        }
    }
}

// The build carries the net's rows down each band (MaxPyramid::computeFinest): on maps one
// sample wide or tall too, where the clamped and wrapped edges meet, and at either precision.
TEST(MaxPyramid, ABuildInBandsEqualsTheTexelByTexelDefinition) {
    for (const auto& [w, h] : std::vector<std::pair<int, int>>{
             {1101, 701}, {1, 1}, {1, 6}, {6, 1}, {2, 2}, {3, 7}, {300, 257}}) {
        const HeightMap map = synth::whiteNoise(w, h, static_cast<std::uint32_t>(5 + w + h));
        for (const bool wrapU : {true, false}) {
            for (const BoundPrecision precision : {BoundPrecision::Half, BoundPrecision::Float}) {
                const MaxPyramid p(map, wrapU, precision);
                for (int j = 0; j < map.height; ++j) {
                    for (int i = 0; i < map.width; ++i) {
                        ASSERT_EQ(
                            std::bit_cast<std::uint32_t>(p.block(0, i, j)),
                            std::bit_cast<std::uint32_t>(storedBound(
                                texelSquareBound(map, i, j, wrapU), precision, p.scaleExponent())))
                            << w << "x" << h << (wrapU ? " wrapped" : "") << ": " << i << "," << j;
                    }
                }
                expectBlocksAndWindowsFromTheFinest(p, map);
            }
        }
    }
}

// Half precision (what the GPU holds): each finest bound rounded up to 11 significant bits
// and at least 2^(S - 14), S from the top: still a bound, at most 2^-10 of it above, and
// divided by 2^S a normal half (the top below 2^15).
TEST(MaxPyramid, HalfPrecisionRoundsEveryBoundUpOntoTheHalfGrid) {
    std::mt19937 random(5);
    for (const float scale : {1.0f, 1e-30f, 3e4f, 1e30f}) {
        HeightMap map = synth::whiteNoise(29, 17, 3);
        for (float& h : map.samples) h *= scale;
        map.at(4, 4) = 0.0f;
        map.at(5, 4) = std::ldexp(scale, -60);  // far below the top: raised to the least bound
        const MaxPyramid exact(map, false, BoundPrecision::Float);
        const MaxPyramid half(map, false, BoundPrecision::Half);
        const int s = half.scaleExponent();
        EXPECT_EQ(s, pyramidScaleExponent(half.maxHeight()));
        EXPECT_LT(std::ldexp(half.maxHeight(), -s), 32768.0f);
        if (s > pyramidScaleExponent(0.0f)) {  // not held up by the clamp (1e-30)
            EXPECT_GE(std::ldexp(half.maxHeight(), -s), 16384.0f) << scale;
        }
        for (int j = 0; j < map.height; ++j) {
            for (int i = 0; i < map.width; ++i) {
                const float a = exact.block(0, i, j), b = half.block(0, i, j);
                ASSERT_GE(b, a) << scale << ": " << i << "," << j;
                if (a == 0.0f) {
                    ASSERT_EQ(b, 0.0f);
                    continue;
                }
                const float stored = std::ldexp(b, -s);  // a normal half, exactly
                ASSERT_GE(stored, std::ldexp(1.0f, -14));
                ASSERT_EQ(stored,
                          std::ldexp(std::round(std::ldexp(stored, 10 - std::ilogb(stored))),
                                     std::ilogb(stored) - 10))
                    << "not on the half grid: " << stored;
                if (a >= std::ldexp(1.0f, s - 14)) {
                    ASSERT_LE(b, a * (1.0f + std::ldexp(1.0f, -10))) << scale;
                }
            }
        }
    }
}

// The biquadratic surface (issue 12): its finest level is the max of each texel square's
// Bezier net, which must never fall below the patch (a B-spline lies in its net's convex
// hull) and is tighter than the 3 x 3 samples the patch sums; and every window the
// traversal reads over a footprint, on the plane's clamped map and a curved base's wrapped
// one (rectangles across the seam included), must bound the surface inside it.
TEST(MaxPyramid, BiquadraticBoundsCoverThePatchesOnEitherAddressing) {
    std::mt19937 random(77);
    const std::vector<std::pair<int, int>> sizes = {{1, 1}, {2, 2}, {3, 5}, {17, 4}, {31, 33}};
    for (const bool wrapU : {false, true}) {
        for (auto [w, h] : sizes) {
            for (const bool spiky : {false, true}) {
                const auto seed = static_cast<std::uint32_t>(w * 31 + h);
                const HeightMap map =
                    spiky ? synth::spike(w, h, w / 2, h / 2) : synth::whiteNoise(w, h, seed);
                const MaxPyramid p(map, wrapU);
                const auto surface = [&](double x, double y) {
                    return map.surface(x, y, wrapU);
                };
                for (int j = 0; j < h; ++j) {
                    for (int i = 0; i < w; ++i) {
                        double samples = 0.0;
                        for (int b = -1; b <= 1; ++b)
                            for (int a = -1; a <= 1; ++a)
                                samples =
                                    std::max<double>(samples, map.sample(i + a, j + b, wrapU));
                        const double texel = p.block(0, i, j);
                        ASSERT_GE(texel + 1e-12, denseMax(surface, i, j, i + 1, j + 1, 24))
                            << i << "," << j;
                        ASSERT_LE(texel, samples + 1e-6) << i << "," << j;
                    }
                }
                for (int trial = 0; trial < 400; ++trial) {
                    const auto [lo, hi] = randomFootprint(random, w, h, wrapU);
                    const double bound = p.footprintBound(lo, hi).bound;
                    ASSERT_GE(bound, denseMax(surface, lo.x, lo.y, hi.x, hi.y, 30) - 1e-12)
                        << w << "x" << h << (wrapU ? " wrapped" : "") << " [" << lo.x << "," << lo.y
                        << "] - [" << hi.x << "," << hi.y << "]";
                    if (!wrapU) {  // the plane's reads: along the segment lo -> hi
                        double along = 0.0;
                        for (int k = 0; k <= 300; ++k) {
                            const glm::dvec2 q = lo + (hi - lo) * (k / 300.0);
                            along = std::max(along, surface(q.x, q.y));
                        }
                        ASSERT_GE(p.segmentBound(lo, hi).bound, along - 1e-12);
                    }
                }
            }
        }
    }
}

// A tiled map (issue 14) is the larger image made by repeating it: the tile's pyramid must
// bound the whole's surface over every occurrence of every texel square (inside the whole,
// where neighbours come from the next tile, and at its clamped edges), and every footprint
// over the whole, seams between tiles included (wrapped round a curved base, up to once
// round the whole), on both last levels.
TEST(MaxPyramid, TiledBoundsCoverTheWholeSurface) {
    std::mt19937 random(91);
    for (const bool wrapU : {false, true}) {
        for (const Interpolation interpolation :
             {Interpolation::Bilinear, Interpolation::Biquadratic}) {
            for (const auto [w, h, tx, ty] :
                 {std::array{5, 3, 3, 2}, std::array{7, 6, 2, 3}, std::array{1, 4, 4, 1}}) {
                const HeightMap map =
                    synth::whiteNoise(w, h, static_cast<std::uint32_t>(w * 7 + h));
                const MapAddressing addressing{wrapU, tx, ty};
                const MaxPyramid p(map, addressing);
                const int W = w * tx, H = h * ty;
                const auto surface = [&](double x, double y) {
                    return map.surface(x, y, addressing, interpolation);
                };
                const std::string name = std::to_string(w) + "x" + std::to_string(h) + " tiled " +
                                         std::to_string(tx) + "x" + std::to_string(ty) +
                                         (wrapU ? " wrapped " : " ") +
                                         interpolationName(interpolation);
                for (int j = 0; j < H; ++j) {
                    for (int i = 0; i < W; ++i) {
                        ASSERT_GE(p.block(0, i % w, j % h) + 1e-12,
                                  denseMax(surface, i, j, i + 1, j + 1, 16))
                            << name << ": texel square " << i << "," << j;
                    }
                }
                for (int trial = 0; trial < 300; ++trial) {
                    const auto [lo, hi] = randomFootprint(random, W, H, wrapU);
                    ASSERT_GE(p.footprintBound(lo, hi).bound,
                              denseMax(surface, lo.x, lo.y, hi.x, hi.y, 30) - 1e-12)
                        << name << " [" << lo.x << "," << lo.y << "] - [" << hi.x << "," << hi.y
                        << "]";
                }
            }
        }
    }
}

namespace {

// A float >= 0 as the exact integer value * 2^149 (up to 2^278): ten 32-bit limbs, least
// significant first. Enough to add two and compare, the reference for roundUpMean.
using Exact = std::array<std::uint64_t, 10>;

Exact exactValue(float x) {
    const std::uint32_t bits = std::bit_cast<std::uint32_t>(x) & 0x7fffffffu;
    const std::uint32_t e = bits >> 23;
    const std::uint64_t f = e == 0 ? bits : (bits & 0x7fffffu) | 0x800000u;
    const int shift = static_cast<int>(std::max(e, 1u)) - 1;  // value * 2^149 = f * 2^shift
    Exact n{};
    n[shift / 32] = (f << (shift % 32)) & 0xffffffffu;
    if (shift / 32 + 1 < 10) n[shift / 32 + 1] = (f << (shift % 32)) >> 32;
    return n;
}

Exact add(const Exact& a, const Exact& b) {
    Exact s{};
    std::uint64_t carry = 0;
    for (int k = 0; k < 10; ++k) {
        const std::uint64_t t = a[k] + b[k] + carry;
        s[k] = t & 0xffffffffu;
        carry = t >> 32;
    }
    return s;
}

int compare(const Exact& a, const Exact& b) {
    for (int k = 9; k >= 0; --k) {
        if (a[k] != b[k]) return a[k] < b[k] ? -1 : 1;
    }
    return 0;
}

// roundUpMean(a, b) is the smallest float r with 2 r >= a + b, exactly.
void expectExactRoundUpMean(float a, float b) {
    const float r = roundUpMean(a, b);
    const Exact sum = add(exactValue(a), exactValue(b));
    ASSERT_GE(compare(add(exactValue(r), exactValue(r)), sum), 0)
        << "below the mean: " << a << ", " << b << " -> " << r;
    if (r > 0.0f) {
        const float below = std::bit_cast<float>(std::bit_cast<std::uint32_t>(r) - 1u);
        ASSERT_LT(compare(add(exactValue(below), exactValue(below)), sum), 0)
            << "not the smallest: " << std::hexfloat << a << ", " << b << " -> " << r;
    }
}

}  // namespace

// The bound's arithmetic (and the GPU builder's, which runs the same integer code): the
// mean of two floats rounded up, exactly, across the whole range of floats >= 0 (zeros,
// denormals, the largest), for pairs far apart and close together.
TEST(MaxPyramid, RoundUpMeanIsTheExactMeanRoundedUp) {
    std::mt19937 random(99);
    std::uniform_int_distribution<std::uint32_t> anyBits(0, 0x7f7fffffu), low(0, 0x00ffffffu),
        offset(0, 1u << 26);
    const auto fromBits = [](std::uint32_t bits) { return std::bit_cast<float>(bits); };
    const std::vector<float> special = {0.0f,
                                        -0.0f,
                                        1.0f,
                                        0.5f,
                                        0.1f,
                                        0.7f,
                                        fromBits(1),
                                        fromBits(0x7fffff),
                                        fromBits(0x800000),
                                        fromBits(0x7f7fffff),
                                        1.0f / 65535.0f,
                                        65535.0f};
    for (float a : special)
        for (float b : special) expectExactRoundUpMean(a, b);
    for (int trial = 0; trial < 200000; ++trial) {
        const std::uint32_t a = anyBits(random);
        expectExactRoundUpMean(fromBits(a), fromBits(anyBits(random)));
        // Neighbours within a few binades: the sums that keep every bit.
        const std::uint32_t near = std::min(a + offset(random), 0x7f7fffffu);
        expectExactRoundUpMean(fromBits(a), fromBits(near));
        expectExactRoundUpMean(fromBits(low(random)), fromBits(low(random)));  // denormals
    }
    EXPECT_EQ(roundUpMean(1.0f, 0.0f), 0.5f);
    EXPECT_EQ(roundUpMean(0.25f, 0.75f), 0.5f);
    EXPECT_EQ(roundUpMean(1.0f, std::ldexp(1.0f, -24)), std::nextafter(0.5f, 1.0f));
}

// The double rounding the bound used to have: the mean of 2^-60 and 1 rounded in double
// to 0.5 exactly, below the surface's 0.5 + 2^-61 at the edge between the two samples.
TEST(MaxPyramid, BoundHoldsAcrossAnyRangeOfHeights) {
    HeightMap map(2, 1);
    map.samples = {std::ldexp(1.0f, -60), 1.0f};
    const MaxPyramid p(map);
    EXPECT_EQ(p.block(0, 0, 0), std::nextafter(0.5f, 1.0f));
    EXPECT_EQ(p.block(0, 1, 0), 1.0f);
}

// Edits in place: after random rectangles of samples change, update() leaves the pyramid
// that a build from scratch of the new map makes, texel for texel, on every level of the
// blocks and the windows, on the plane and wrapped round the seam (rectangles at either edge
// included).
TEST(MaxPyramid, UpdateAfterAnEditEqualsABuildFromScratch) {
    std::mt19937 random(4321);
    const std::vector<std::pair<int, int>> sizes = {{1, 1},   {2, 3},   {7, 5},
                                                    {33, 17}, {64, 64}, {100, 9}};
    for (const BoundPrecision precision : {BoundPrecision::Float, BoundPrecision::Half}) {
        for (const bool wrapU : {false, true}) {
            for (auto [w, h] : sizes) {
                HeightMap map = synth::whiteNoise(w, h, static_cast<std::uint32_t>(w * 7 + h));
                MaxPyramid pyramid(map, wrapU, precision);
                std::uniform_real_distribution<float> value(0.0f, 1.0f);
                for (int edit = 0; edit < 30; ++edit) {
                    std::uniform_int_distribution<int> x(0, w - 1), y(0, h - 1);
                    int x0 = x(random), x1 = x(random), y0 = y(random), y1 = y(random);
                    if (edit % 5 == 0) x0 = 0;  // at the seam's either side
                    if (edit % 5 == 1) x1 = w - 1;
                    const TexelRect rect{std::min(x0, x1), std::min(y0, y1), std::max(x0, x1) + 1,
                                         std::max(y0, y1) + 1};
                    // Zeros, values in [0, 1), and a raise far above: the top changes binade.
                    const float scale = edit % 7 == 6 ? 100.0f : 1.0f;
                    for (int j = rect.y0; j < rect.y1; ++j)
                        for (int i = rect.x0; i < rect.x1; ++i)
                            map.at(i, j) = edit % 3 == 0 ? 0.0f : scale * value(random);
                    pyramid.update(map, rect);
                    const MaxPyramid rebuilt(map, wrapU, precision);
                    const std::string what = std::to_string(w) + "x" + std::to_string(h) +
                                             (wrapU ? " wrapped" : "") +
                                             (precision == BoundPrecision::Half ? ", half" : "") +
                                             ", edit " + std::to_string(edit);
                    ASSERT_EQ(pyramid.scaleExponent(), rebuilt.scaleExponent()) << what;
                    for (int level = 0; level < rebuilt.windowLevelCount(); ++level) {
                        ASSERT_EQ(pyramid.blockLevelData(level), rebuilt.blockLevelData(level))
                            << what << ", block level " << level;
                        ASSERT_EQ(pyramid.windowLevelData(level), rebuilt.windowLevelData(level))
                            << what << ", window level " << level;
                    }
                }
            }
        }
    }
}

// The bound the traversal reads (one window, at the level the footprint chooses) never
// falls below the surface along a segment with the bounds the GPU holds (half precision),
// on maps whose last blocks absorb odd remainders (issue 16's layout), wrapped or not.
TEST(MaxPyramid, HalfPrecisionWindowsCoverTheSurfaceAlongAnySegment) {
    std::mt19937 random(99);
    const std::vector<std::pair<int, int>> sizes = {{1, 1},   {3, 5},   {17, 4},
                                                    {31, 33}, {100, 7}, {65, 129}};
    for (auto [w, h] : sizes) {
        const HeightMap map = synth::whiteNoise(w, h, static_cast<std::uint32_t>(w * 3 + h));
        for (const bool wrapU : {false, true}) {
            const MaxPyramid p(map, wrapU, BoundPrecision::Half);
            std::uniform_real_distribution<double> x(0.0, w), y(0.0, h), unit(0.0, 1.0);
            for (int trial = 0; trial < 1500; ++trial) {
                const glm::dvec2 lo(x(random), y(random));
                const double reach = std::max(w, h) * unit(random) * unit(random);
                glm::dvec2 hi = lo + reach * glm::dvec2{unit(random), unit(random)};
                hi = glm::min(hi, glm::dvec2(wrapU ? lo.x + w - 1e-9 : w, h));
                const double bound = p.footprintBound(lo, hi).bound;
                double dense = 0.0;
                for (int b = 0; b <= 24; ++b)
                    for (int a = 0; a <= 24; ++a)
                        dense = std::max(dense, map.surface(lo.x + (hi.x - lo.x) * a / 24,
                                                            lo.y + (hi.y - lo.y) * b / 24, wrapU));
                ASSERT_GE(bound, dense - 1e-12)
                    << w << "x" << h << (wrapU ? " wrapped" : "") << " [" << lo.x << "," << lo.y
                    << "] - [" << hi.x << "," << hi.y << "]";
            }
        }
    }
}

// The regions are what the GPU builder draws: two rectangles at most per level, the finest
// one the samples' rectangle grown by one texel, wrapping round the seam.
TEST(MaxPyramid, UpdateRegionsGrowByOneTexelAndWrap) {
    const auto sizes = windowLevelSizes(16, 8);
    const auto planeRegions = pyramidUpdateRegions(sizes, 16, 8, false, {0, 3, 2, 4});
    ASSERT_EQ(planeRegions.aligned[0].size(), 1u);
    EXPECT_EQ(planeRegions.aligned[0][0], (TexelRect{0, 2, 3, 5}));
    EXPECT_EQ(planeRegions.windows[0][0], (TexelRect{0, 1, 3, 5}));
    EXPECT_EQ(planeRegions.aligned[1][0], (TexelRect{0, 1, 2, 3}));
    const auto curvedRegions = pyramidUpdateRegions(sizes, 16, 8, true, {0, 3, 2, 4});
    ASSERT_EQ(curvedRegions.aligned[0].size(), 2u);
    EXPECT_EQ(curvedRegions.aligned[0][0], (TexelRect{0, 2, 3, 5}));
    EXPECT_EQ(curvedRegions.aligned[0][1], (TexelRect{15, 2, 16, 5}));
    const auto top = curvedRegions.aligned.back();
    ASSERT_EQ(top.size(), 1u);
    EXPECT_EQ(top[0], (TexelRect{0, 0, 1, 1}));
    EXPECT_TRUE(pyramidUpdateRegions(sizes, 16, 8, false, {5, 5, 5, 9}).aligned[0].empty());
}

// A map read through pages (shaders/paged_map.glsl) stands in for a texel whose
// page is absent with the window above it: window (k, t) must be at most window
// (k + 1, min(t >> 1, last)), and sample p at most window (0, p), on the renderer's Half
// pyramid, for odd sizes, the seam of a curved base, and the last window of a row (which
// reaches to the map's edge). Checked against the samples themselves too: every window is
// at least every sample it covers, [t 2^k, (t + 2) 2^k) per axis, to the edge for the last.
TEST(MaxPyramid, EveryWindowLiesUnderTheWindowAboveItAndEverySampleUnderItsWindow) {
    for (const bool wrapU : {false, true}) {
        for (const glm::ivec2 size : {glm::ivec2(37, 23), glm::ivec2(64, 64), glm::ivec2(5, 130)}) {
            for (const std::uint32_t seed : {1u, 2u}) {
                const HeightMap map = seed == 1 ? synth::whiteNoise(size.x, size.y, 7)
                                                : synth::cobbles(size.x, size.y, 9);
                const MaxPyramid pyramid(map, wrapU, BoundPrecision::Half);
                const std::string what = std::to_string(size.x) + "x" + std::to_string(size.y) +
                                         (wrapU ? " wrapped" : "") + " map " + std::to_string(seed);
                for (int j = 0; j < map.height; ++j)
                    for (int i = 0; i < map.width; ++i)
                        ASSERT_LE(map.at(i, j), pyramid.window(0, i, j))
                            << what << " " << i << "," << j;
                for (int k = 0; k < pyramid.windowLevelCount(); ++k) {
                    const int w = pyramid.windowLevelWidth(k), h = pyramid.windowLevelHeight(k);
                    for (int q = 0; q < h; ++q) {
                        for (int p = 0; p < w; ++p) {
                            const float window = pyramid.window(k, p, q);
                            // The samples it covers (an independent check of what it holds).
                            const int x0 = p << k, y0 = q << k;
                            const int x1 =
                                p + 1 >= w ? map.width : std::min(map.width, (p + 2) << k);
                            const int y1 =
                                q + 1 >= h ? map.height : std::min(map.height, (q + 2) << k);
                            for (int y = y0; y < y1; ++y)
                                for (int x = x0; x < x1; ++x)
                                    ASSERT_LE(map.at(x, y), window) << what << " level " << k;
                            if (k + 1 == pyramid.windowLevelCount()) continue;
                            const int pa = std::min(p >> 1, pyramid.windowLevelWidth(k + 1) - 1);
                            const int qa = std::min(q >> 1, pyramid.windowLevelHeight(k + 1) - 1);
                            ASSERT_LE(window, pyramid.window(k + 1, pa, qa))
                                << what << " level " << k << " window " << p << "," << q;
                        }
                    }
                }
            }
        }
    }
}
