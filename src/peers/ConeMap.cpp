#include "microrelief/peers/ConeMap.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>

#include "microrelief/core/ParallelRows.h"
#include "microrelief/core/heightmap/MaxPyramid.h"
#include "microrelief/peers/MaxMipPyramid.h"

namespace microrelief {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// A cone's walk costs thousands of operations: a few rows of them are worth a thread.
constexpr long long kConeRowCells = 256;

// Every texel's cone ratio, ratioAt(i, j, visited) (visited: the nodes its walk read, added
// to), the rows built on the machine's cores. Each texel's cone is from the map alone, so
// the ratios are the same however many threads ran; the progress is reported one call at a
// time, in order (ConeMapProgress).
template <typename RatioAt>
std::vector<double> ratiosByRow(const HeightMap& map, RatioAt ratioAt, ConeMapStats* stats,
                                const ConeMapProgress& progress) {
    const int w = map.width, h = map.height;
    std::vector<double> ratios(static_cast<std::size_t>(w) * h);
    std::atomic<std::uint64_t> visited{0};
    std::mutex progressMutex;
    int rowsDone = 0;
    parallelEachRow(
        0, h, w,
        [&](int j) {
            std::uint64_t rowVisited = 0;
            for (int i = 0; i < w; ++i)
                ratios[static_cast<std::size_t>(j) * w + i] = ratioAt(i, j, rowVisited);
            visited += rowVisited;
            if (!progress) return;
            const std::lock_guard<std::mutex> lock(progressMutex);
            progress(double(++rowsDone) / h);
        },
        kConeRowCells);
    if (stats) stats->nodesVisited = visited;
    return ratios;
}

// The bilinear surface on the half-texel grid: point (a / 2, b / 2), a in [0, 2W], b in
// [0, 2H]. Odd a is a sample column's centre, even a a texel edge halfway between two
// sample columns (clamped at the map's edges, as HeightMap::surface clamps). Each piece
// [a/2, (a+1)/2] x [b/2, (b+1)/2] lies inside one bilinear cell (cells run between sample
// centres) or in a clamped border, so the surface over it is the bilinear interpolation of
// its four corners here: these are the quarter texels of the pieces below.
class HalfGrid {
public:
    explicit HalfGrid(const HeightMap& map) : w_(2 * map.width + 1), h_(2 * map.height + 1) {
        values_.resize(static_cast<std::size_t>(w_) * h_);
        for (int b = 0; b < h_; ++b) {
            int j0, j1;
            samplesAround(b, map.height, j0, j1);
            for (int a = 0; a < w_; ++a) {
                int i0, i1;
                samplesAround(a, map.width, i0, i1);
                // Sums of floats in doubles: exact unless the samples' exponents lie 29
                // binades apart (then within 2^-53 relative, which the margin below covers).
                values_[static_cast<std::size_t>(b) * w_ + a] =
                    0.25 * ((double(map.at(i0, j0)) + map.at(i1, j0)) +
                            (double(map.at(i0, j1)) + map.at(i1, j1)));
            }
        }
    }
    double at(int a, int b) const { return values_[static_cast<std::size_t>(b) * w_ + a]; }

private:
    static void samplesAround(int a, int n, int& k0, int& k1) {
        k0 = (a % 2 == 1) ? (a - 1) / 2 : a / 2 - 1;
        k1 = (a % 2 == 1) ? k0 : a / 2;
        k0 = std::clamp(k0, 0, n - 1);
        k1 = std::clamp(k1, 0, n - 1);
    }
    int w_, h_;
    std::vector<double> values_;
};

// The gap in texels from coordinate x to the interval [i, i + 1].
double gapTo(double x, int i) {
    return std::max(0.0, std::max(double(i) - x, x - double(i + 1)));
}

// A lower bound of r*_T over piece (a, b) (ConeMap.h), for square T = (i, j) at plateau B:
// the largest r with h(x) <= B + dist(x, T) / r on the piece (infinity where the piece lies
// at or below B). Why each bound holds:
//  * A piece level with T (its x range inside [i, i+1], or its y range inside [j, j+1]):
//    dist(x, T) is the other axis's gap, linear on the piece, so h(x) - dist(x, T) / r is
//    bilinear and peaks at a corner; the largest r that holds at the corners is exact.
//  * A diagonal piece: dist = |(gx, gy)| is convex, at least n . (gx, gy) for the unit n
//    towards the piece's centre (Cauchy-Schwarz), which is linear: the corner argument on
//    it gives rt, a lower bound. Also dist >= dmin (the nearest corner's distance: both
//    gaps grow away from T) and h <= the largest corner, which gives rc. Both are lower
//    bounds; the larger is kept. rc is also what makes the pyramid walk's pruning exact:
//    a node whose dist over (bound - B) is at least r holds no piece below that either.
double pieceRatio(const HalfGrid& grid, int i, int j, double plateau, int a, int b) {
    std::array<double, 4> h, gx, gy;
    double highest = 0.0;
    for (int c = 0; c < 4; ++c) {
        const int ca = a + (c & 1), cb = b + (c >> 1);
        h[c] = grid.at(ca, cb);
        gx[c] = gapTo(0.5 * ca, i);
        gy[c] = gapTo(0.5 * cb, j);
        highest = std::max(highest, h[c]);
    }
    if (!(highest > plateau)) return kInfinity;
    const bool levelInX = a >= 2 * i && a + 1 <= 2 * i + 2;
    const bool levelInY = b >= 2 * j && b + 1 <= 2 * j + 2;
    double r = kInfinity;
    if (levelInX || levelInY) {
        for (int c = 0; c < 4; ++c) {
            if (h[c] > plateau)
                r = std::min(r, (gx[c] + gy[c]) / (h[c] - plateau));  // one gap is 0
        }
        return r;
    }
    const double mx = gapTo(0.5 * a + 0.25, i), my = gapTo(0.5 * b + 0.25, j);
    const double norm = std::hypot(mx, my);
    double dmin = kInfinity;
    for (int c = 0; c < 4; ++c) {
        dmin = std::min(dmin, std::hypot(gx[c], gy[c]));
        if (h[c] > plateau) r = std::min(r, (mx * gx[c] + my * gy[c]) / norm / (h[c] - plateau));
    }
    return std::max(r, dmin / (highest - plateau));
}

// The bound over texel square U = (p, q), its four pieces.
double squareRatio(const HalfGrid& grid, int i, int j, double plateau, int p, int q) {
    if (p == i && q == j) return kInfinity;  // h <= B on T itself
    double r = kInfinity;
    for (int b = 2 * q; b < 2 * q + 2; ++b) {
        for (int a = 2 * p; a < 2 * p + 2; ++a)
            r = std::min(r, pieceRatio(grid, i, j, plateau, a, b));
    }
    return r;
}

// A quadtree node (MaxMipPyramid.h): level, index.
struct Node {
    int level, p, q;
};

// Finest texels [x0, x1) x [y0, y1) under a node, clipped to the map.
struct NodeExtent {
    int x0, y0, x1, y1;
};

NodeExtent extentOf(const Node& n, int width, int height) {
    return {n.p << n.level, n.q << n.level, std::min((n.p + 1) << n.level, width),
            std::min((n.q + 1) << n.level, height)};
}

// The branch-and-bound walk shared by both maps: from the top of the quadtree, each
// node that `lowerBound(node, extent, bound)` says might narrow the cone below `r` is opened
// (its children pushed nearest first, so that near nodes narrow it early), each finest
// texel that might is handed to `leaf` with the cone so far (a leaf may stop early once it
// knows it cannot go below it). `lowerBound` returns a lower bound of every leaf
// ratio under the node; a node whose bound is at least r is skipped, which leaves the
// result what visiting every leaf would give.
template <class LowerBound, class Leaf>
double walkPyramid(const MaxMipPyramid& pyramid, double r, const LowerBound& lowerBound,
                   const Leaf& leaf, std::uint64_t& visited) {
    const int width = pyramid.mapWidth(), height = pyramid.mapHeight();
    std::vector<Node> stack{{pyramid.levelCount() - 1, 0, 0}};
    std::array<std::pair<double, Node>, 4> children;
    while (!stack.empty()) {
        const Node n = stack.back();
        stack.pop_back();
        const NodeExtent e = extentOf(n, width, height);
        if (e.x1 <= e.x0 || e.y1 <= e.y0) continue;  // padding
        const double bound = lowerBound(e, pyramid.texel(n.level, n.p, n.q));
        if (!(bound < r)) continue;
        ++visited;
        if (n.level == 0) {
            r = std::min(r, leaf(n.p, n.q, r));
            continue;
        }
        int count = 0;
        const int cw = pyramid.levelWidth(n.level - 1), ch = pyramid.levelHeight(n.level - 1);
        for (int cy = 0; cy < 2; ++cy) {
            for (int cx = 0; cx < 2; ++cx) {
                const Node c{n.level - 1, 2 * n.p + cx, 2 * n.q + cy};
                if (c.p >= cw || c.q >= ch) continue;
                const NodeExtent ce = extentOf(c, width, height);
                if (ce.x1 <= ce.x0 || ce.y1 <= ce.y0) continue;
                children[count++] = {lowerBound(ce, pyramid.texel(c.level, c.p, c.q)), c};
            }
        }
        // Largest bound first onto the stack: the most promising child comes off first
        // (an insertion sort of at most four).
        for (int k = 1; k < count; ++k) {
            for (int m = k; m > 0 && children[m - 1].first < children[m].first; --m)
                std::swap(children[m - 1], children[m]);
        }
        for (int k = 0; k < count; ++k) stack.push_back(children[k].second);
    }
    return r;
}

// Texel (i, j)'s plateau: the pyramid's finest bound (>= the bilinear surface over the
// square, MaxPyramid.h: texelSquareBound) rounded up to the half grid the GPU holds, and at
// least 2^-14 where not 0: no half denormal, which the GPU build's conversion to RG16F
// might flush to 0 (shaders/pyramid/cone_map.frag does the same).
double plateauOf(const HeightMap& map, int i, int j) {
    const double plateau = halfRoundedUp(texelSquareBound(map, i, j, false));
    return plateau > 0.0 ? std::max(plateau, 0x1p-14) : 0.0;
}

// The relaxed ratio of source sample s against destination sample d, as the published
// tool computes it (GPU Gems 3, ch. 18, listing 18-5) in heights rather than depths: the
// ray from the box top above s through d's surface point, followed past d in `steps`
// steps down to height 0 while it is under the surface; where it first comes out (or ends)
// above s's height, the ratio that puts that point on the cone. Along the march the ratio
// of the ray's point only grows (it moves away from s and down), so once it reaches
// `below` (the cone so far) the pair cannot narrow the cone and the march stops (the
// answer is then some value >= below, which the caller's min ignores).
double relaxedPairRatio(const HeightMap& map, double top, int si, int sj, int di, int dj, int steps,
                        double below) {
    const double sx = si + 0.5, sy = sj + 0.5, hs = map.at(si, sj);
    const double dx = di + 0.5, dy = dj + 0.5, hd = map.at(di, dj);
    if (!(hd > hs)) return kInfinity;  // the ray goes on down from below s: no exit above s
    const double reach = std::hypot(dx - sx, dy - sy);
    if (!(reach < below * (hd - hs))) return kInfinity;  // even d itself is no narrower
    const double vz = hd - top;
    if (!(vz < 0.0)) return reach / (hd - hs);  // d on the top: itself
    const double scale = hd / -vz;              // to height 0 from d
    const double stepX = (dx - sx) * scale / steps, stepY = (dy - sy) * scale / steps,
                 stepZ = vz * scale / steps;
    double x = dx + stepX, y = dy + stepY, z = hd + stepZ;
    for (int k = 1; k < steps; ++k) {
        if (!(map.surface(x, y) >= z)) break;  // out of the solid
        if (!(z > hs) || !(std::hypot(x - sx, y - sy) < below * (z - hs))) return kInfinity;
        x += stepX;
        y += stepY;
        z += stepZ;
    }
    if (!(z > hs)) return kInfinity;
    return std::hypot(x - sx, y - sy) / (z - hs);
}

}  // namespace

float halfRoundedDown(double x) {
    if (!(x > 0.0)) return 0.0f;
    if (x >= 65504.0) return 65504.0f;
    int e;
    std::frexp(x, &e);                            // x = m 2^e, m in [1/2, 1)
    const int k = std::max(e - 1, -14);           // the binade (denormals below 2^-14)
    const double unit = std::ldexp(1.0, k - 10);  // 10 mantissa bits
    return static_cast<float>(std::floor(x / unit) * unit);
}

float halfRoundedUp(double x) {
    if (!(x > 0.0)) return 0.0f;
    if (x > 65504.0) return std::numeric_limits<float>::infinity();
    int e;
    std::frexp(x, &e);
    const int k = std::max(e - 1, -14);
    const double unit = std::ldexp(1.0, k - 10);
    return static_cast<float>(std::ceil(x / unit) * unit);  // 2^(k+1) at most: a half too
}

std::uint16_t halfBits(float v) {
    if (v == 0.0f) return 0;
    if (std::isinf(v)) return 0x7c00;
    int e;
    const double m = std::frexp(double(v), &e);  // v = m 2^e
    const int k = e - 1;
    if (k < -14) return static_cast<std::uint16_t>(std::ldexp(double(v), 24));  // denormal
    const double mantissa = (m * 2.0 - 1.0) * 1024.0;
    return static_cast<std::uint16_t>(((k + 15) << 10) | static_cast<int>(mantissa));
}

std::vector<double> conservativeConeRatios(const HeightMap& map, bool bruteForce,
                                           ConeMapStats* stats, const ConeMapProgress& progress) {
    const HalfGrid grid(map);
    // Float: the finest bounds as texelSquareBound gives them.
    const MaxMipPyramid pyramid{MaxPyramid(map)};
    const int w = map.width, h = map.height;
    auto ratioAt = [&](int i, int j, std::uint64_t& visited) {
        const double plateau = plateauOf(map, i, j);
        double r = kConeRatioCap;
        auto leaf = [&](int p, int q, double) { return squareRatio(grid, i, j, plateau, p, q); };
        if (bruteForce) {
            for (int q = 0; q < h; ++q) {
                for (int p = 0; p < w; ++p) r = std::min(r, leaf(p, q, r));
            }
            visited += static_cast<std::uint64_t>(w) * h;
            return r;
        }
        // A node's pieces lie at least its gap d from T and at most its bound M high (the
        // quadtree holds maxima of finest bounds, MaxMipPyramid.h), so none has a ratio
        // below d / (M - B) (pieceRatio's rc).
        auto lowerBound = [&](const NodeExtent& e, float bound) {
            if (!(bound > plateau)) return kInfinity;
            const double gx = std::max({0, e.x0 - (i + 1), i - e.x1});
            const double gy = std::max({0, e.y0 - (j + 1), j - e.y1});
            return std::hypot(gx, gy) / (bound - plateau);
        };
        return walkPyramid(pyramid, r, lowerBound, leaf, visited);
    };
    return ratiosByRow(map, ratioAt, stats, progress);
}

namespace {

ConeMap conservativeConeMap(const HeightMap& map, bool bruteForce, ConeMapStats* stats,
                            const ConeMapProgress& progress) {
    const std::vector<double> ratios = conservativeConeRatios(map, bruteForce, stats, progress);
    ConeMap cones{map.width, map.height, {}, {}};
    cones.apex.resize(ratios.size());
    cones.ratio.resize(ratios.size());
    for (int j = 0; j < map.height; ++j) {
        for (int i = 0; i < map.width; ++i) {
            const std::size_t k = static_cast<std::size_t>(j) * map.width + i;
            cones.apex[k] = static_cast<float>(plateauOf(map, i, j));
            // Rounded down, after a margin of 2^-40 relative for the doubles' rounding in
            // pieceRatio (a few operations, each within 2^-53).
            cones.ratio[k] = halfRoundedDown(ratios[k] * (1.0 - 0x1p-40));
        }
    }
    return cones;
}

}  // namespace

ConeMap buildConservativeConeMap(const HeightMap& map, ConeMapStats* stats,
                                 const ConeMapProgress& progress) {
    return conservativeConeMap(map, false, stats, progress);
}

ConeMap buildConservativeConeMapBruteForce(const HeightMap& map) {
    return conservativeConeMap(map, true, nullptr, {});
}

double relaxedRatioCap(const HeightMap& map) {
    return std::min({double(map.width), double(map.height), double(kConeRatioCap)});
}

std::vector<double> relaxedConeRatios(const HeightMap& map, int searchSteps, bool bruteForce,
                                      ConeMapStats* stats, const ConeMapProgress& progress) {
    const MaxMipPyramid pyramid{MaxPyramid(map)};
    const double top = map.maxValue(), cap = relaxedRatioCap(map);
    auto ratioAt = [&](int i, int j, std::uint64_t& visited) {
        const double hs = map.at(i, j);
        auto leaf = [&](int p, int q, double below) {
            if (p == i && q == j) return kInfinity;
            return relaxedPairRatio(map, top, i, j, p, q, searchSteps, below);
        };
        double r = cap;
        if (bruteForce) {
            for (int q = 0; q < map.height; ++q)
                for (int p = 0; p < map.width; ++p) r = std::min(r, leaf(p, q, kInfinity));
            return r;
        }
        // A destination sample d in a node is at most the node's bound M high and at least
        // the distance g from s to the node's sample centres away; its exit point lies
        // farther from s and no higher than d, so its ratio is at least g / (M - hs).
        auto lowerBound = [&](const NodeExtent& e, float bound) {
            if (!(bound > hs)) return kInfinity;
            const double gx = std::max({0.0, e.x0 + 0.5 - (i + 0.5), (i + 0.5) - (e.x1 - 0.5)});
            const double gy = std::max({0.0, e.y0 + 0.5 - (j + 0.5), (j + 0.5) - (e.y1 - 0.5)});
            return std::hypot(gx, gy) / (bound - hs);
        };
        return walkPyramid(pyramid, r, lowerBound, leaf, visited);
    };
    return ratiosByRow(map, ratioAt, stats, progress);
}

ConeMap buildRelaxedConeMap(const HeightMap& map, int searchSteps, ConeMapStats* stats,
                            const ConeMapProgress& progress) {
    const std::vector<double> ratios = relaxedConeRatios(map, searchSteps, false, stats, progress);
    ConeMap cones{map.width, map.height, {}, {}};
    cones.apex.resize(map.samples.size());
    cones.ratio.resize(map.samples.size());
    for (std::size_t k = 0; k < ratios.size(); ++k) {
        const double hs = map.samples[k];
        const float down = halfRoundedDown(hs), up = halfRoundedUp(hs);
        cones.apex[k] = (hs - down <= up - hs) ? down : up;  // the nearest half
        cones.ratio[k] = halfRoundedDown(ratios[k]);
    }
    return cones;
}

std::vector<std::uint16_t> coneMapHalfTexels(const ConeMap& cones) {
    std::vector<std::uint16_t> texels(2 * cones.apex.size());
    for (std::size_t k = 0; k < cones.apex.size(); ++k) {
        texels[2 * k] = halfBits(cones.apex[k]);
        texels[2 * k + 1] = halfBits(cones.ratio[k]);
    }
    return texels;
}

}  // namespace microrelief
