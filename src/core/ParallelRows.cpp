#include "microrelief/core/ParallelRows.h"

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

namespace microrelief {

void parallelRows(int rowBegin, int rowEnd, long long rowCells,
                  const std::function<void(int y0, int y1)>& band, long long minCells) {
    const long long rows = rowEnd - rowBegin;
    if (rows <= 0) return;
    const long long cells = rows * std::max(rowCells, 1LL);
#if defined(__EMSCRIPTEN__) && !defined(__EMSCRIPTEN_PTHREADS__)
    const long long cores = 1;  // WebAssembly built without threads: the caller's alone
#else
    const long long cores = std::max(1u, std::thread::hardware_concurrency());
#endif
    const int threads =
        static_cast<int>(std::min({cores, rows, std::max(1LL, cells / std::max(minCells, 1LL))}));
    if (threads == 1) {
        band(rowBegin, rowEnd);
        return;
    }
    // Equal bands: the builds cost the same per row. Bands whose thread could not be
    // started (the system's limit) run on the caller's thread, beside its own.
    const auto bandStart = [&](int k) { return rowBegin + static_cast<int>(rows * k / threads); };
    std::vector<std::thread> workers;
    workers.reserve(threads - 1);
    int started = 0;
    try {
        for (; started + 1 < threads; ++started) {
            workers.emplace_back(
                [&band, y0 = bandStart(started), y1 = bandStart(started + 1)] { band(y0, y1); });
        }
    } catch (...) {  // std::system_error (no thread to be had), std::bad_alloc
    }
    for (int k = started; k < threads; ++k) band(bandStart(k), bandStart(k + 1));
    for (std::thread& worker : workers) worker.join();
}

void parallelEachRow(int rowBegin, int rowEnd, long long rowCells,
                     const std::function<void(int y)>& row, long long minCells) {
    // parallelRows' bands are the threads here: each takes the next row not yet taken.
    std::atomic<int> next{rowBegin};
    parallelRows(
        rowBegin, rowEnd, rowCells,
        [&](int, int) {
            for (int y = next++; y < rowEnd; y = next++) row(y);
        },
        minCells);
}

}  // namespace microrelief
