#include "heightmap/MaxPyramid.h"

#include <algorithm>
#include <cmath>

namespace microrelief {

namespace {

int ceilPowerOfTwo(int n) {
    int p = 1;
    while (p < n) p <<= 1;
    return p;
}

// The exact max of the bilinear surface over texel square (i, j): the nine points where
// the patches that meet the square have their corners (see MaxPyramid.h).
float texelSquareMax(const HeightMap& map, int i, int j) {
    float best = 0.0f;
    for (int dj = -1; dj <= 1; ++dj) {
        for (int di = -1; di <= 1; ++di) {
            // Point (i + 0.5 + di/2, j + 0.5 + dj/2) is the average of the samples on
            // either side of it along each axis where it lies between two centres.
            const int i0 = di < 0 ? i - 1 : i, i1 = di > 0 ? i + 1 : i;
            const int j0 = dj < 0 ? j - 1 : j, j1 = dj > 0 ? j + 1 : j;
            const float value = 0.25f * (map.clamped(i0, j0) + map.clamped(i1, j0) +
                                         map.clamped(i0, j1) + map.clamped(i1, j1));
            best = std::max(best, value);
        }
    }
    // Rounding in the averages can land one ulp below a sample; the sample itself is on
    // the surface, so include it explicitly.
    return std::max(best, map.at(i, j));
}

}  // namespace

MaxPyramid::MaxPyramid(const HeightMap& map) : mapWidth_(map.width), mapHeight_(map.height) {
    const int pw = ceilPowerOfTwo(map.width), ph = ceilPowerOfTwo(map.height);
    widths_.push_back(pw);
    heights_.push_back(ph);
    std::vector<float> finest(static_cast<std::size_t>(pw) * ph, 0.0f);
    for (int j = 0; j < map.height; ++j) {
        for (int i = 0; i < map.width; ++i) finest[static_cast<std::size_t>(j) * pw + i] = texelSquareMax(map, i, j);
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
}

int MaxPyramid::footprintLevel(double extent) const {
    int level = 0;
    while (level + 1 < levelCount() && std::ldexp(1.0, level) < extent) ++level;
    return level;
}

float MaxPyramid::boundOver(double x0, double y0, double x1, double y1) const {
    const int level = footprintLevel(std::max(x1 - x0, y1 - y0));
    const double scale = std::ldexp(1.0, -level);
    const int w = widths_[level], h = heights_[level];
    auto index = [scale](double x, int size) { return std::clamp(static_cast<int>(std::floor(x * scale)), 0, size - 1); };
    float best = 0.0f;
    for (int q = index(y0, h); q <= index(y1, h); ++q) {
        for (int p = index(x0, w); p <= index(x1, w); ++p) best = std::max(best, texel(level, p, q));
    }
    return best;
}

}  // namespace microrelief
