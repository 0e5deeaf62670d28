// Work split by rows over the machine's cores: the max pyramid's CPU build
// (core/heightmap/MaxPyramid.h) computes each texel from its inputs alone, so bands of rows
// can be computed at once and the result is the same, texel for texel, however many
// threads ran.
#pragma once

#include <functional>

namespace microrelief {

// Calls band(y0, y1) on disjoint bands of rows [y0, y1) covering [rowBegin, rowEnd), on up
// to std::thread::hardware_concurrency() threads (the caller's among them), and returns
// when all are done. Work of fewer than `minCells` cells (rows x rowCells) runs on the
// caller's thread alone, where starting threads would cost more than it saves. `band`
// must not throw (a throw ends the program, as it would from any thread).
void parallelRows(int rowBegin, int rowEnd, long long rowCells,
                  const std::function<void(int y0, int y1)>& band, long long minCells = 1 << 16);

// The same for work whose cost varies from row to row (rays that miss beside rays that walk
// the relief, cones over flat and rough parts of a map): the rows are handed out one at a
// time, each to the next thread free, and row(y) is called once for each y in
// [rowBegin, rowEnd). `row` must not throw.
void parallelEachRow(int rowBegin, int rowEnd, long long rowCells,
                     const std::function<void(int y)>& row, long long minCells = 1 << 16);

}  // namespace microrelief
