// The max pyramid of a map read a band of rows at a time (MaxPyramid.h, BoundPrecision::Half,
// untiled), given out a row at a time, level by level, as soon as each row is known: how a
// pyramid file is built for a map larger than memory (io/PyramidFile.h). The rows are
// MaxPyramid's texels, bit for bit (the same texelSquareBound, storedBound and maxima).
//
// Two passes over the rows: the first finds the largest sample, which sets S (the finest
// bounds' least value depends on it); the second makes the levels. Memory: the band of
// samples and its finest bounds (about 2 (band + 2) rows), and at most three rows of blocks
// a level, never the map.
#pragma once

#include <functional>
#include <string>

namespace microrelief {

// A map's rows, top to bottom: read(y0, y1, out) fills rows y0 .. y1 - 1, width samples a
// row, each finite and >= 0. Called in order, twice over.
struct MapRows {
    int width = 0, height = 0;
    std::function<void(int y0, int y1, float* out)> read;
};

// A row of a page level (PyramidPages.h): level 0 the samples, 1 + k window level k;
// `texels` holds the level's width.
using PyramidRowSink = std::function<void(int level, int row, const float* texels)>;

struct StreamedPyramid {
    float largestSample = 0.0f;
    float maxHeight = 0.0f;  // MaxPyramid::maxHeight: pyramidTop(largestSample)
    int scaleExponent = 0;
};

// Streams the levels of `rows`' pyramid (u wrapped when `wrapU`) into `sink`: every row of
// every page level exactly once, each level's rows in order (levels interleaved). Reads
// `band` rows at a time. `progress` (may be empty) is told the rows read so far out of
// 2 x height. Throws Error(BadInput) naming `source` for a sample that is not finite and
// >= 0.
StreamedPyramid streamPyramid(
    const MapRows& rows, bool wrapU, int band, const PyramidRowSink& sink,
    const std::string& source,
    const std::function<void(long long done, long long total)>& progress = {});

}  // namespace microrelief
