#include "microrelief/heightmap/MaxPyramid.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace microrelief {

namespace {

int ceilPowerOfTwo(int n) {
    int p = 1;
    while (p < n) p <<= 1;
    return p;
}

// The exact max of the bilinear surface over texel square (i, j): the nine points where
// the patches that meet the square have their corners (see MaxPyramid.h). Computed in
// double and rounded up to float, so that the bound is never an ulp below the surface.
float texelSquareMax(const HeightMap& map, int i, int j, const MapAddressing& wrapU) {
    double best = 0.0;
    for (int dj = -1; dj <= 1; ++dj) {
        for (int di = -1; di <= 1; ++di) {
            // Point (i + 0.5 + di/2, j + 0.5 + dj/2) is the average of the samples on
            // either side of it along each axis where it lies between two centres.
            const int i0 = di < 0 ? i - 1 : i, i1 = di > 0 ? i + 1 : i;
            const int j0 = dj < 0 ? j - 1 : j, j1 = dj > 0 ? j + 1 : j;
            const double value =
                0.25 * (static_cast<double>(map.sample(i0, j0, wrapU)) + map.sample(i1, j0, wrapU) +
                        map.sample(i0, j1, wrapU) + map.sample(i1, j1, wrapU));
            best = std::max(best, value);
        }
    }
    const float rounded = static_cast<float>(best);
    return rounded < best ? std::nextafter(rounded, INFINITY) : rounded;
}

// A bound of the biquadratic surface over texel square (i, j), never below it. Over the
// square the uniform quadratic B-spline is a tensor-product quadratic whose Bezier control
// net is, per axis, (c0 + c1) / 2, c1, (c1 + c2) / 2 of its three control points (the
// B-spline's weights (1 - u)^2 / 2, 1/2 + u - u^2, u^2 / 2 over u in [0, 1] are exactly
// these Bernstein combinations); the patch lies in the convex hull of its Bezier net, so
// the net's max bounds it. Tighter than the 3 x 3 samples' max (the net's entries are
// averages of them), and attained at the square's corners when a corner entry is the
// largest. Computed in double, rounded up to float.
float texelSquareBezierMax(const HeightMap& map, int i, int j, const MapAddressing& wrapU) {
    double c[3][3];
    for (int b = 0; b < 3; ++b) {
        for (int a = 0; a < 3; ++a) c[b][a] = map.sample(i - 1 + a, j - 1 + b, wrapU);
    }
    const auto net = [](const double p[3], double q[3]) {
        q[0] = 0.5 * (p[0] + p[1]);
        q[1] = p[1];
        q[2] = 0.5 * (p[1] + p[2]);
    };
    double rows[3][3], best = 0.0;
    for (int b = 0; b < 3; ++b) net(c[b], rows[b]);
    for (int a = 0; a < 3; ++a) {
        const double column[3] = {rows[0][a], rows[1][a], rows[2][a]};
        double q[3];
        net(column, q);
        best = std::max({best, q[0], q[1], q[2]});
    }
    const float rounded = static_cast<float>(best);
    return rounded < best ? std::nextafter(rounded, INFINITY) : rounded;
}

}  // namespace

MaxPyramid::MaxPyramid(const HeightMap& map, bool wrapU, Interpolation interpolation)
    : MaxPyramid(map, MapAddressing{wrapU}, interpolation) {}

MaxPyramid::MaxPyramid(const HeightMap& map, const MapAddressing& addressing,
                       Interpolation interpolation)
    : mapWidth_(map.width),
      mapHeight_(map.height),
      wrapU_(addressing.wrapU),
      addressing_(addressing) {
    // A tiled map's texel occurs once in every tile: with neighbours from the tiles beside
    // it inside the whole, clamped to itself at the whole's edges. The first and the last
    // tile's occurrences have both kinds (the first's left and the last's right edge
    // clamp, the first's right and the last's left edge meet the next tile), the others
    // repeat them, so the max over those two per axis bounds the surface over every
    // occurrence of the texel square. Untiled, that is the one occurrence.
    const int lastTileX = (addressing.tilesX - 1) * map.width,
              lastTileY = (addressing.tilesY - 1) * map.height;
    const int offsetsX = lastTileX > 0 ? 2 : 1, offsetsY = lastTileY > 0 ? 2 : 1;
    const auto bound = [&](int i, int j) {
        float best = 0.0f;
        for (int y = 0; y < offsetsY; ++y) {
            for (int x = 0; x < offsetsX; ++x) {
                const int ox = x * lastTileX, oy = y * lastTileY;
                best = std::max(best, interpolation == Interpolation::Biquadratic
                                          ? texelSquareBezierMax(map, i + ox, j + oy, addressing)
                                          : texelSquareMax(map, i + ox, j + oy, addressing));
            }
        }
        return best;
    };
    const int pw = ceilPowerOfTwo(map.width), ph = ceilPowerOfTwo(map.height);
    widths_.push_back(pw);
    heights_.push_back(ph);
    std::vector<float> finest(static_cast<std::size_t>(pw) * ph, 0.0f);
    for (int j = 0; j < map.height; ++j) {
        for (int i = 0; i < map.width; ++i)
            finest[static_cast<std::size_t>(j) * pw + i] = bound(i, j);
    }
    levels_.push_back(std::move(finest));

    while (widths_.back() > 1 || heights_.back() > 1) {
        const int cw = widths_.back(), ch = heights_.back();
        const int w = std::max(1, cw >> 1), h = std::max(1, ch >> 1);
        const std::vector<float>& child = levels_.back();
        std::vector<float> parent(static_cast<std::size_t>(w) * h);
        for (int q = 0; q < h; ++q) {
            for (int p = 0; p < w; ++p) {
                float best = 0.0f;
                for (int cq = 2 * q; cq <= std::min(2 * q + 1, ch - 1); ++cq) {
                    for (int cp = 2 * p; cp <= std::min(2 * p + 1, cw - 1); ++cp) {
                        best = std::max(best, child[static_cast<std::size_t>(cq) * cw + cp]);
                    }
                }
                parent[static_cast<std::size_t>(q) * w + p] = best;
            }
        }
        widths_.push_back(w);
        heights_.push_back(h);
        levels_.push_back(std::move(parent));
    }

    // The overlapping levels: each texel the max of the 2 x 2 aligned texels from it on;
    // past a level's last row or column there is no surface (0, like the padding).
    for (int level = 0; level < levelCount(); ++level) {
        const int w = widths_[level], h = heights_[level];
        const std::vector<float>& aligned = levels_[level];
        auto at = [&](int p, int q) {
            return p < w && q < h ? aligned[static_cast<std::size_t>(q) * w + p] : 0.0f;
        };
        std::vector<float> window(aligned.size());
        for (int q = 0; q < h; ++q) {
            for (int p = 0; p < w; ++p) {
                window[static_cast<std::size_t>(q) * w + p] =
                    std::max({at(p, q), at(p + 1, q), at(p, q + 1), at(p + 1, q + 1)});
            }
        }
        windows_.push_back(std::move(window));
    }
}

glm::ivec2 MaxPyramid::finestTexelAt(glm::dvec2 p) const {
    return {std::clamp(static_cast<int>(std::floor(p.x)), 0, mapWidth_ * addressing_.tilesX - 1),
            std::clamp(static_cast<int>(std::floor(p.y)), 0, mapHeight_ * addressing_.tilesY - 1)};
}

int MaxPyramid::windowLevel(glm::ivec2 lo, glm::ivec2 hi) const {
    // A span of d texels crosses at most one level-k boundary once d < 2^k, so with
    // m = floor(log2 d) the level is m or m + 1.
    const unsigned span = static_cast<unsigned>(std::max(hi.x - lo.x, hi.y - lo.y));
    int level = span > 0 ? std::bit_width(span) - 1 : 0;  // floor(log2 span), like findMSB
    const glm::ivec2 crossed = (hi >> level) - (lo >> level);
    if (crossed.x > 1 || crossed.y > 1) ++level;
    return std::min(level, levelCount() - 1);
}

double MaxPyramid::windowOver(glm::ivec2 lo, glm::ivec2 hi, int& level, int& fetches) const {
    level = windowLevel(lo, hi);
    ++fetches;
    return window(level, lo.x >> level, lo.y >> level);
}

double MaxPyramid::segmentBound(glm::dvec2 a, glm::dvec2 b, int& level, int& fetches) const {
    const glm::ivec2 ta = finestTexelAt(a), tb = finestTexelAt(b);
    return windowOver(glm::min(ta, tb), glm::max(ta, tb), level, fetches);
}

double MaxPyramid::tiledWindows(glm::ivec2 lo, glm::ivec2 hi, int& level, int& fetches) const {
    // max_pyramid.glsl: mr_tiledWindows. Per axis the tile's texels the footprint covers, or
    // the whole tile; across a seam between tiles the tile's top.
    const glm::ivec2 tile(mapWidth_, mapHeight_), span = hi - lo;
    glm::ivec2 a = lo - tile * (lo / tile), b = a + span;
    for (int axis = 0; axis < 2; ++axis) {
        if (span[axis] >= tile[axis] - 1) {
            a[axis] = 0;
            b[axis] = tile[axis] - 1;
        }
    }
    const bool split = b.x >= tile.x || b.y >= tile.y;
    return split ? windowOver({0, 0}, tile - 1, level, fetches) : windowOver(a, b, level, fetches);
}

double MaxPyramid::footprintBound(glm::dvec2 lo, glm::dvec2 hi, int& level, int& fetches) const {
    if (addressing_.tiled()) {
        const glm::ivec2 tlo = finestTexelAt(lo);
        glm::ivec2 thi = finestTexelAt(hi);
        if (wrapU_ && hi.x >= mapWidth_ * addressing_.tilesX)
            thi.x = static_cast<int>(std::floor(hi.x));  // past the seam
        return tiledWindows(tlo, thi, level, fetches);
    }
    if (!wrapU_ || hi.x < mapWidth_)
        return windowOver(finestTexelAt(lo), finestTexelAt(hi), level, fetches);
    // Across the seam: [lo.x, W) and [0, hi.x - W], each held by a window of its own.
    const glm::ivec2 tlo = finestTexelAt(lo), thi = finestTexelAt(hi - glm::dvec2(mapWidth_, 0.0));
    const double right = windowOver(tlo, {mapWidth_ - 1, thi.y}, level, fetches);
    return std::max(right, windowOver({0, tlo.y}, thi, level, fetches));
}

}  // namespace microrelief
