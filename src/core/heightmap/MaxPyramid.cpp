#include "microrelief/core/heightmap/MaxPyramid.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "microrelief/core/Error.h"
#include "microrelief/core/ParallelRows.h"

namespace microrelief {

namespace {

// The bits of a float >= 0 with the sign cleared: -0 becomes 0, and for the rest an
// unsigned comparison of the bits is a comparison of the values.
std::uint32_t magnitudeBits(float value) {
    return std::bit_cast<std::uint32_t>(value) & 0x7fffffffu;
}

// roundUpMean on the bits. A float f * 2^(Q - 150) with f its 24-bit significand (the
// implicit one included; for a denormal, f is the mantissa and Q = 1, as for the smallest
// normals). With a >= b, the sum is aligned to a's unit with three guard bits: a's
// significand shifted left by 3, b's by 3 - d (d = Qa - Qb), or right by d - 3 where b's
// lowest bits fall below the guard bits (`lost`). The sum then holds 27 or 28 bits, and
// the mean is kept to 24 of them (to fewer where it lands among the denormals): the exact
// mean is (kept + a fraction) units of the result's last place, and the fraction is
// nonzero exactly when any dropped bit is. Rounding up adds one unit then. Why `lost`
// needs no more bits: it is below a's unit / 8, and the result's unit is at least that,
// so whether it is zero decides the rounding alone. A carry out of the significand (a
// mantissa of 2^24, or 2^23 from the denormals) lands in the exponent field as the next
// binade's first value, which is the right answer: the encoding below adds, not ors.
std::uint32_t roundUpMeanBits(std::uint32_t a, std::uint32_t b) {
    const std::uint32_t hi = std::max(a, b), lo = std::min(a, b);
    const std::uint32_t eh = hi >> 23, el = lo >> 23;
    const std::uint32_t fh = eh == 0 ? hi : (hi & 0x7fffffu) | 0x800000u;
    const std::uint32_t fl = el == 0 ? lo : (lo & 0x7fffffu) | 0x800000u;
    const std::uint32_t qh = std::max(eh, 1u), ql = std::max(el, 1u);
    const std::uint32_t d = qh - ql;
    std::uint32_t sum = fh << 3, lost = 0;
    if (d <= 3) {
        sum += fl << (3 - d);
    } else {
        const std::uint32_t k = std::min(d - 3, 31u);  // 31: all of fl (24 bits) is lost
        sum += fl >> k;
        lost = fl & ((1u << k) - 1u);
    }
    // sum * 2^(qh - 153) is the sum, half of it 2^(qh - 154): keep its top 24 bits, whose
    // last place is 2^(q - 150).
    std::uint32_t shift = sum >= (1u << 27) ? 4u : 3u;
    std::uint32_t q = qh - 4 + shift;
    if (q == 0) {  // a denormal mean: the last place is 2^-149 whatever the length
        shift += 1;
        q = 1;
    }
    lost |= sum & ((1u << shift) - 1u);
    return ((q - 1) << 23) + (sum >> shift) + (lost != 0 ? 1u : 0u);
}

}  // namespace

float roundUpMean(float a, float b) {
    return std::bit_cast<float>(roundUpMeanBits(magnitudeBits(a), magnitudeBits(b)));
}

float texelSquareBound(const HeightMap& map, int i, int j, bool wrapU) {
    return texelSquareBound(map, i, j, MapAddressing{wrapU});
}

float texelSquareBound(const HeightMap& map, int i, int j, const MapAddressing& addressing) {
    // The Bezier net along rows first, then along its columns (see MaxPyramid.h); the max
    // taken on the bits (all >= 0), so it is the same on every machine.
    // Inside the map (its first tile) the 3 x 3 samples need no clamping or wrapping:
    // sample() would return these same samples (its index arithmetic, divisions for the
    // tiles, was 28 % of a 20000 x 20000 map's paged render in a profile).
    const bool inside = i >= 1 && j >= 1 && i + 1 < map.width && j + 1 < map.height;
    std::uint32_t rows[3][3];
    for (int b = 0; b < 3; ++b) {
        std::uint32_t c[3];
        for (int a = 0; a < 3; ++a)
            c[a] = magnitudeBits(inside ? map.at(i - 1 + a, j - 1 + b)
                                        : map.sample(i - 1 + a, j - 1 + b, addressing));
        rows[b][0] = roundUpMeanBits(c[0], c[1]);
        rows[b][1] = c[1];
        rows[b][2] = roundUpMeanBits(c[1], c[2]);
    }
    std::uint32_t best = 0;
    for (int a = 0; a < 3; ++a) {
        best = std::max({best, roundUpMeanBits(rows[0][a], rows[1][a]), rows[1][a],
                         roundUpMeanBits(rows[1][a], rows[2][a])});
    }
    return std::bit_cast<float>(best);
}

int pyramidScaleExponent(float top) {
    const int e = static_cast<int>(std::bit_cast<std::uint32_t>(top) >> 23) - 127;
    return std::clamp(e - 14, -112, 113);
}

namespace {

// The smallest float with 11 significant bits (a half's) not below the float of `bits`
// (>= 0): the low 13 mantissa bits rounded up; a carry runs into the exponent field, which
// is the next binade's first value.
std::uint32_t roundUpToHalfBits(std::uint32_t bits) {
    return (bits + 0x1fffu) & ~0x1fffu;
}

}  // namespace

float storedBound(float bound, BoundPrecision precision, int scaleExponent) {
    const std::uint32_t bits = magnitudeBits(bound);
    if (precision == BoundPrecision::Float || bits == 0) return std::bit_cast<float>(bits);
    const std::uint32_t smallest = static_cast<std::uint32_t>(scaleExponent - 14 + 127) << 23;
    return std::bit_cast<float>(std::max(roundUpToHalfBits(bits), smallest));
}

float pyramidTop(float largestSample) {
    return std::bit_cast<float>(roundUpToHalfBits(magnitudeBits(largestSample)));
}

std::vector<glm::ivec2> windowLevelSizes(int mapWidth, int mapHeight) {
    std::vector<glm::ivec2> sizes;
    for (glm::ivec2 size(mapWidth, mapHeight);; size = glm::max(size >> 1, glm::ivec2(1))) {
        sizes.push_back(size);
        if (size == glm::ivec2(1)) return sizes;
    }
}

MaxPyramid::MaxPyramid(const HeightMap& map, bool wrapU, BoundPrecision precision)
    : MaxPyramid(map, MapAddressing{wrapU}, precision) {}

MaxPyramid::MaxPyramid(const HeightMap& map, const MapAddressing& addressing,
                       BoundPrecision precision)
    : mapWidth_(map.width),
      mapHeight_(map.height),
      wrapU_(addressing.wrapU),
      addressing_(addressing),
      precision_(precision) {
    windowSizes_ = windowLevelSizes(map.width, map.height);
    for (const glm::ivec2 size : windowSizes_) {
        blocks_.emplace_back(std::size_t(size.x) * size.y, 0.0f);
        windows_.emplace_back(std::size_t(size.x) * size.y, 0.0f);
    }
    build(map);
}

void MaxPyramid::build(const HeightMap& map) {
    scaleExponent_ =
        precision_ == BoundPrecision::Half ? pyramidScaleExponent(pyramidTop(map.maxValue())) : 0;
    computeFinest(map, {0, 0, mapWidth_, mapHeight_});
    for (int level = 0; level < windowLevelCount(); ++level) {
        if (level > 0) reduceBlocks(level, {0, 0, windowSizes_[level].x, windowSizes_[level].y});
        computeWindows(level, {0, 0, windowSizes_[level].x, windowSizes_[level].y});
    }
}

float MaxPyramid::finestBound(const HeightMap& map, int i, int j) const {
    // A tiled map's texel occurs once in every tile: with neighbours from the tiles beside
    // it inside the whole, clamped to itself at the whole's edges. The first and the last
    // tile's occurrences have both kinds (the first's left and the last's right edge
    // clamp, the first's right and the last's left edge meet the next tile), the others
    // repeat them, so the max over those two per axis bounds the surface over every
    // occurrence of the texel square. Untiled, that is the one occurrence.
    const int lastTileX = (addressing_.tilesX - 1) * map.width,
              lastTileY = (addressing_.tilesY - 1) * map.height;
    // Along an untiled axis the "two" occurrences are one, taken once.
    float best = 0.0f;
    for (int y = 0; y <= (lastTileY > 0 ? 1 : 0); ++y) {
        for (int x = 0; x <= (lastTileX > 0 ? 1 : 0); ++x)
            best = std::max(
                best, texelSquareBound(map, i + x * lastTileX, j + y * lastTileY, addressing_));
    }
    return best;
}

namespace {

// Row r of the Bezier net over texels [x0, x1) (texelSquareBound's rows, as bits): entry
// 2k + 1 is sample x0 + k, entry 2k the rounded-up mean of samples x0 + k - 1 and x0 + k;
// the row clamped, the columns past the map's edges clamped or wrapped (`addressing`,
// untiled), as sample() has them. Neighbouring texels share the mean between them.
void netRow(const HeightMap& map, int r, int x0, int x1, const MapAddressing& addressing,
            std::uint32_t* net) {
    const int row = std::clamp(r, 0, map.height - 1);
    const auto at = [&](int i) {
        return magnitudeBits(i >= 0 && i < map.width ? map.at(i, row)
                                                     : map.sample(i, r, addressing));
    };
    std::uint32_t left = at(x0 - 1);
    const int n = x1 - x0;
    for (int k = 0; k < n; ++k) {
        const std::uint32_t centre = at(x0 + k);
        net[2 * k] = roundUpMeanBits(left, centre);
        net[2 * k + 1] = centre;
        left = centre;
    }
    net[2 * n] = roundUpMeanBits(left, at(x1));
}

}  // namespace

void finestBounds(const HeightMap& map, const MapAddressing& addressing, const TexelRect& rect,
                  BoundPrecision precision, int scaleExponent, float* out, std::size_t stride) {
    if (addressing.tiled())
        throwRuntime("finestBounds: a tiled map's texels (MaxPyramid::finestBound)");
    if (rect.empty()) return;
    // texelSquareBound of each texel, by the same means of the same bits, each computed
    // once: a texel's 3 x 3 net shares its columns' horizontal means with the texels beside
    // it and its rows' vertical means with the texels above and below, so a band of rows
    // carries the net's rows down (3 means a texel where texelSquareBound takes 12; 0.3 to
    // 0.5 us a texel on one core that way, the bulk of a build).
    parallelRows(rect.y0, rect.y1, rect.width(), [&](int y0, int y1) {
        const std::size_t n = 2 * static_cast<std::size_t>(rect.width()) + 1;
        std::vector<std::uint32_t> above(n), row(n), below(n), meanAbove(n), meanBelow(n),
            columnMax(n);
        netRow(map, y0 - 1, rect.x0, rect.x1, addressing, above.data());
        netRow(map, y0, rect.x0, rect.x1, addressing, row.data());
        for (std::size_t x = 0; x < n; ++x) meanAbove[x] = roundUpMeanBits(above[x], row[x]);
        for (int j = y0; j < y1; ++j) {
            netRow(map, j + 1, rect.x0, rect.x1, addressing, below.data());
            for (std::size_t x = 0; x < n; ++x) {
                meanBelow[x] = roundUpMeanBits(row[x], below[x]);
                columnMax[x] = std::max({meanAbove[x], row[x], meanBelow[x]});
            }
            float* const texels = out + static_cast<std::size_t>(j - rect.y0) * stride;
            for (int k = 0; k < rect.width(); ++k) {
                const std::uint32_t best =
                    std::max({columnMax[2 * k], columnMax[2 * k + 1], columnMax[2 * k + 2]});
                texels[k] = storedBound(std::bit_cast<float>(best), precision, scaleExponent);
            }
            std::swap(row, below);
            std::swap(meanAbove, meanBelow);
        }
    });
}

void MaxPyramid::computeFinest(const HeightMap& map, const TexelRect& rect) {
    if (rect.empty()) return;
    if (addressing_.tiled()) {
        // Each texel from its samples alone, over its occurrences (finestBound).
        parallelRows(rect.y0, rect.y1, rect.width(), [&](int y0, int y1) {
            for (int j = y0; j < y1; ++j) {
                for (int i = rect.x0; i < rect.x1; ++i) {
                    blocks_[0][static_cast<std::size_t>(j) * mapWidth_ + i] =
                        storedBound(finestBound(map, i, j), precision_, scaleExponent_);
                }
            }
        });
        return;
    }
    finestBounds(map, addressing_, rect, precision_, scaleExponent_,
                 &blocks_[0][static_cast<std::size_t>(rect.y0) * mapWidth_ + rect.x0],
                 static_cast<std::size_t>(mapWidth_));
}

void MaxPyramid::reduceBlocks(int level, const TexelRect& rect) {
    // Block p's children are 2p and 2p + 1, and for the last block of a row (or column)
    // every child from 2p on: an odd count's last child too.
    const glm::ivec2 c = windowSizes_[level - 1], size = windowSizes_[level];
    const std::vector<float>& child = blocks_[level - 1];
    parallelRows(rect.y0, rect.y1, rect.width(), [&](int y0, int y1) {
        for (int q = y0; q < y1; ++q) {
            const int qEnd = q == size.y - 1 ? c.y - 1 : std::min(2 * q + 1, c.y - 1);
            for (int p = rect.x0; p < rect.x1; ++p) {
                const int pEnd = p == size.x - 1 ? c.x - 1 : std::min(2 * p + 1, c.x - 1);
                float best = 0.0f;
                for (int cq = 2 * q; cq <= qEnd; ++cq) {
                    for (int cp = 2 * p; cp <= pEnd; ++cp)
                        best = std::max(best, child[static_cast<std::size_t>(cq) * c.x + cp]);
                }
                blocks_[level][static_cast<std::size_t>(q) * size.x + p] = best;
            }
        }
    });
}

void MaxPyramid::computeWindows(int level, const TexelRect& rect) {
    // Each window the max of the 2 x 2 blocks from it on (those that exist).
    const glm::ivec2 size = windowSizes_[level];
    const std::vector<float>& blocks = blocks_[level];
    auto at = [&](int p, int q) {
        return p < size.x && q < size.y ? blocks[static_cast<std::size_t>(q) * size.x + p] : 0.0f;
    };
    parallelRows(rect.y0, rect.y1, rect.width(), [&](int y0, int y1) {
        for (int q = y0; q < y1; ++q) {
            for (int p = rect.x0; p < rect.x1; ++p) {
                windows_[level][static_cast<std::size_t>(q) * size.x + p] =
                    std::max({at(p, q), at(p + 1, q), at(p, q + 1), at(p + 1, q + 1)});
            }
        }
    });
}

namespace {

// Overlapping or touching rectangles become their bounding box (recomputing a texel that
// did not change is harmless), so a level lists at most two.
void mergeRects(std::vector<TexelRect>& rects) {
    if (rects.size() == 2) {
        const TexelRect& a = rects[0];
        const TexelRect& b = rects[1];
        if (a.x0 <= b.x1 && b.x0 <= a.x1 && a.y0 <= b.y1 && b.y0 <= a.y1) {
            rects = {{std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1),
                      std::max(a.y1, b.y1)}};
        }
    }
}

}  // namespace

PyramidRegions pyramidUpdateRegions(const std::vector<glm::ivec2>& levelSizes, int width,
                                    int height, bool wrapU, const TexelRect& changed) {
    PyramidRegions regions;
    const TexelRect c{std::max(changed.x0, 0), std::max(changed.y0, 0), std::min(changed.x1, width),
                      std::min(changed.y1, height)};
    const int levelCount = static_cast<int>(levelSizes.size());
    regions.aligned.resize(levelCount);
    regions.windows.resize(levelCount);
    if (c.empty()) return regions;
    // Finest texel i reads samples i - 1 .. i + 1: rows clamped at the map's edges, columns
    // too on the plane, or wrapped round the seam.
    const int y0 = std::max(c.y0 - 1, 0), y1 = std::min(c.y1 + 1, height);
    std::vector<TexelRect>& finest = regions.aligned[0];
    if (!wrapU || c.x1 - c.x0 + 2 >= width) {
        finest.push_back(
            {wrapU ? 0 : std::max(c.x0 - 1, 0), y0, wrapU ? width : std::min(c.x1 + 1, width), y1});
    } else if (c.x0 == 0) {
        finest = {{0, y0, c.x1 + 1, y1}, {width - 1, y0, width, y1}};
    } else if (c.x1 == width) {
        finest = {{c.x0 - 1, y0, width, y1}, {0, y0, 1, y1}};
    } else {
        finest.push_back({c.x0 - 1, y0, c.x1 + 1, y1});
    }
    for (int level = 0; level < levelCount; ++level) {
        const glm::ivec2 size = levelSizes[level];
        if (level > 0) {
            // Parents of the changed texels of the level below; the last of a row or column
            // also holds what lies past it (the blocks' remainder).
            for (const TexelRect& r : regions.aligned[level - 1]) {
                regions.aligned[level].push_back({std::min(r.x0 >> 1, size.x - 1),
                                                  std::min(r.y0 >> 1, size.y - 1),
                                                  std::min((r.x1 - 1) >> 1, size.x - 1) + 1,
                                                  std::min((r.y1 - 1) >> 1, size.y - 1) + 1});
            }
            mergeRects(regions.aligned[level]);
        }
        // Windows p..p+1 hold texel p: the ones starting one before each changed texel.
        for (const TexelRect& r : regions.aligned[level])
            regions.windows[level].push_back(
                {std::max(r.x0 - 1, 0), std::max(r.y0 - 1, 0), r.x1, r.y1});
        mergeRects(regions.windows[level]);
    }
    return regions;
}

void MaxPyramid::update(const HeightMap& map, const TexelRect& changed) {
    if (addressing_.tiled()) {
        // A tiled texel's bound reads its neighbours in the next tile too (finestBound):
        // pyramidUpdateRegions does not know that, so all again.
        build(map);
        return;
    }
    const PyramidRegions blocks =
        pyramidUpdateRegions(windowSizes_, mapWidth_, mapHeight_, wrapU_, changed);
    for (const TexelRect& r : blocks.aligned[0]) computeFinest(map, r);
    for (int level = 0; level < windowLevelCount(); ++level) {
        if (level > 0) {
            for (const TexelRect& r : blocks.aligned[level]) reduceBlocks(level, r);
        }
        for (const TexelRect& r : blocks.windows[level]) computeWindows(level, r);
    }
    // A top in another binade has another S, and with it another least bound: all again.
    if (precision_ == BoundPrecision::Half && pyramidScaleExponent(maxHeight()) != scaleExponent_)
        build(map);
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
    return std::min(level, windowLevelCount() - 1);
}

BoundRead MaxPyramid::windowOver(glm::ivec2 lo, glm::ivec2 hi) const {
    const int level = windowLevel(lo, hi);
    // The last window of a row or column holds what lies past it (its blocks' remainder).
    const glm::ivec2 p = glm::min(lo >> level, windowSizes_[level] - 1);
    return {window(level, p.x, p.y), level, 1};
}

BoundRead MaxPyramid::segmentBound(glm::dvec2 a, glm::dvec2 b) const {
    const glm::ivec2 ta = finestTexelAt(a), tb = finestTexelAt(b);
    return windowOver(glm::min(ta, tb), glm::max(ta, tb));
}

BoundRead MaxPyramid::tiledWindows(glm::ivec2 lo, glm::ivec2 hi) const {
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
    return split ? windowOver({0, 0}, tile - 1) : windowOver(a, b);
}

BoundRead MaxPyramid::footprintBound(glm::dvec2 lo, glm::dvec2 hi) const {
    if (addressing_.tiled()) {
        const glm::ivec2 tlo = finestTexelAt(lo);
        glm::ivec2 thi = finestTexelAt(hi);
        if (wrapU_ && hi.x >= mapWidth_ * addressing_.tilesX)
            thi.x = static_cast<int>(std::floor(hi.x));  // past the seam
        return tiledWindows(tlo, thi);
    }
    if (!wrapU_ || hi.x < mapWidth_) return windowOver(finestTexelAt(lo), finestTexelAt(hi));
    // Across the seam: [lo.x, W) and [0, hi.x - W], each held by a window of its own; the
    // level is the second's, as the shader reports it.
    const glm::ivec2 tlo = finestTexelAt(lo), thi = finestTexelAt(hi - glm::dvec2(mapWidth_, 0.0));
    const BoundRead right = windowOver(tlo, {mapWidth_ - 1, thi.y});
    const BoundRead left = windowOver({0, tlo.y}, thi);
    return {std::max(right.bound, left.bound), left.level, right.fetches + left.fetches};
}

}  // namespace microrelief
