#include "microrelief/core/heightmap/PyramidStream.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <sstream>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "microrelief/core/Error.h"
#include "microrelief/core/ParallelRows.h"
#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/core/heightmap/MaxPyramid.h"

namespace microrelief {

namespace {

// The window levels made from their blocks as the block rows arrive (MaxPyramid's
// reduceBlocks and computeWindows, a row at a time). A level keeps the block rows a window
// or a parent block still needs: rows from min(next window, 2 x next parent) on, at most three.
class BlockCascade {
public:
    BlockCascade(const std::vector<glm::ivec2>& sizes, const PyramidRowSink& sink) : sink_(sink) {
        for (const glm::ivec2 size : sizes) levels_.push_back({size, {}, 0, 0, 0});
    }

    void push(int k, std::vector<float> row) {
        Level& level = levels_[k];
        const glm::ivec2 size = level.size;
        level.rows.push_back(std::move(row));
        const int have = level.first + static_cast<int>(level.rows.size());
        // Window q: the max of blocks q, q + 1 by q, q + 1, those that exist (0 for the others,
        // as computeWindows has it: every bound is >= 0).
        std::vector<float> out(static_cast<std::size_t>(size.x));
        while (level.windowsOut < size.y && (level.windowsOut + 1 < have || have == size.y)) {
            const int q = level.windowsOut;
            const std::vector<float>& a = rowAt(level, q);
            const std::vector<float>* b = q + 1 < size.y ? &rowAt(level, q + 1) : nullptr;
            for (int p = 0; p < size.x; ++p) {
                const bool right = p + 1 < size.x;
                out[p] = std::max({a[p], right ? a[p + 1] : 0.0f, b ? (*b)[p] : 0.0f,
                                   b && right ? (*b)[p + 1] : 0.0f});
            }
            sink_(1 + k, q, out.data());
            ++level.windowsOut;
        }
        // Parent block Q: the max of children 2Q .. 2Q + 1 per axis, the last of a row or
        // column every child from 2Q on (an odd count's last too).
        const bool hasParent = k + 1 < static_cast<int>(levels_.size());
        if (hasParent) {
            const glm::ivec2 parent = levels_[k + 1].size;
            while (level.parentsOut < parent.y) {
                const int q = level.parentsOut;
                const int qEnd = q == parent.y - 1 ? size.y - 1 : std::min(2 * q + 1, size.y - 1);
                if (qEnd >= have) break;
                std::vector<float> reduced(static_cast<std::size_t>(parent.x));
                for (int p = 0; p < parent.x; ++p) {
                    const int pEnd =
                        p == parent.x - 1 ? size.x - 1 : std::min(2 * p + 1, size.x - 1);
                    float best = 0.0f;
                    for (int cq = 2 * q; cq <= qEnd; ++cq) {
                        const std::vector<float>& child = rowAt(level, cq);
                        for (int cp = 2 * p; cp <= pEnd; ++cp) best = std::max(best, child[cp]);
                    }
                    reduced[p] = best;
                }
                ++level.parentsOut;
                push(k + 1, std::move(reduced));  // levels_ is never resized: `level` stays
            }
        }
        const int keepFrom =
            hasParent ? std::min(level.windowsOut, 2 * level.parentsOut) : level.windowsOut;
        while (level.first < keepFrom && !level.rows.empty()) {
            level.rows.pop_front();
            ++level.first;
        }
    }

private:
    struct Level {
        glm::ivec2 size;
        std::deque<std::vector<float>> rows;  // block rows first, first + 1, ...
        int first, windowsOut, parentsOut;
    };
    static const std::vector<float>& rowAt(const Level& level, int row) {
        return level.rows[static_cast<std::size_t>(row - level.first)];
    }

    const PyramidRowSink& sink_;
    std::vector<Level> levels_;
};

}  // namespace

StreamedPyramid streamPyramid(const MapRows& rows, bool wrapU, int band, const PyramidRowSink& sink,
                              const std::string& source,
                              const std::function<void(long long, long long)>& progress) {
    const int width = rows.width, height = rows.height;
    if (width < 1 || height < 1 || band < 1)
        throwRuntime("streamPyramid: an empty map or band for " + source);
    const long long total = 2LL * height;
    long long done = 0;
    const auto report = [&](int count) {
        done += count;
        if (progress) progress(done, total);
    };

    // Pass 1: the largest sample, and every sample checked.
    std::vector<float> samples;
    float largest = 0.0f;
    for (int y0 = 0; y0 < height; y0 += band) {
        const int y1 = std::min(height, y0 + band);
        samples.assign(static_cast<std::size_t>(y1 - y0) * width, 0.0f);
        rows.read(y0, y1, samples.data());
        for (std::size_t k = 0; k < samples.size(); ++k) {
            const float h = samples[k];
            if (!(std::isfinite(h) && h >= 0.0f)) {
                std::ostringstream message;
                message << source << ": sample (" << k % width << ", "
                        << y0 + static_cast<int>(k / width) << ") is " << h
                        << "; heights must be finite and >= 0"
                        << (std::isfinite(h) ? " (try {map.load.normalize} to map [min, max] "
                                               "to [0, 1])"
                                             : "");
                throwBadInput(message.str());
            }
            largest = std::max(largest, h);
        }
        report(y1 - y0);
    }
    std::vector<float>().swap(samples);
    StreamedPyramid result;
    result.largestSample = largest;
    result.maxHeight = pyramidTop(largest);
    result.scaleExponent = pyramidScaleExponent(result.maxHeight);

    // Pass 2: each band's finest bounds from its samples and the rows either side (clamped at
    // the map's edges, as texelSquareBound clamps), then the window levels row by row. The
    // rows are read once each, in order: the row below a band is read with it and kept as
    // the next band's first, the band's last kept as the next band's row above.
    BlockCascade cascade(windowLevelSizes(width, height), sink);
    const auto rowOf = [&](HeightMap& map, int r) {
        return map.samples.data() + static_cast<std::size_t>(r) * width;
    };
    HeightMap window(width, 1);
    window.samples.reserve(static_cast<std::size_t>(width) * (std::min(band, height) + 2));
    std::vector<float> above(static_cast<std::size_t>(width)), below;
    std::vector<float> finest;
    for (int y0 = 0; y0 < height; y0 += band) {
        const int y1 = std::min(height, y0 + band), count = y1 - y0;
        window.height = count + 2;  // rows y0 - 1 .. y1: the band's at 1 .. count
        window.samples.resize(static_cast<std::size_t>(width) * (count + 2));
        int readFrom = y0;
        if (!below.empty()) {
            std::copy(below.begin(), below.end(), rowOf(window, 1));
            ++readFrom;
        }
        if (readFrom < y1) rows.read(readFrom, y1, rowOf(window, 1 + readFrom - y0));
        if (y1 < height) {
            rows.read(y1, y1 + 1, rowOf(window, count + 1));
            below.assign(rowOf(window, count + 1), rowOf(window, count + 1) + width);
        } else {
            std::copy_n(rowOf(window, count), width, rowOf(window, count + 1));
        }
        if (y0 == 0)
            std::copy_n(rowOf(window, 1), width, rowOf(window, 0));
        else
            std::copy(above.begin(), above.end(), rowOf(window, 0));
        above.assign(rowOf(window, count), rowOf(window, count) + width);
        // The second pass reads the rows again: a map that changed in between (a sample not a
        // height, or above the largest, which set S) would make bounds below its surface.
        for (int r = 1; r <= count; ++r) {
            const float* row = rowOf(window, r);
            for (int i = 0; i < width; ++i) {
                if (!(row[i] >= 0.0f && row[i] <= largest)) {
                    throwBadInput(source +
                                  ": the map changed while its pyramid was built "
                                  "(sample (" +
                                  std::to_string(i) + ", " + std::to_string(y0 + r - 1) +
                                  ") differs from the first pass)");
                }
            }
        }

        // The band's texels at rows 1 .. count of the window, whose rows either side are
        // there: texelSquareBound(window, i, r + 1, wrapU) of each.
        finest.resize(static_cast<std::size_t>(count) * width);
        finestBounds(window, MapAddressing{wrapU}, {0, 1, width, count + 1}, BoundPrecision::Half,
                     result.scaleExponent, finest.data(), static_cast<std::size_t>(width));
        for (int r = 0; r < count; ++r) {
            sink(0, y0 + r, rowOf(window, r + 1));
            const auto from = finest.begin() + static_cast<std::ptrdiff_t>(r) * width;
            cascade.push(0, std::vector<float>(from, from + width));
        }
        report(count);
    }
    return result;
}

}  // namespace microrelief
