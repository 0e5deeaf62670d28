// parallelRows: every row of the range handed out exactly once, in bands, whatever the
// range and however many threads run (the pyramid builds rely on it to be the same,
// texel for texel, as one loop).
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

#include "microrelief/core/ParallelRows.h"

using namespace microrelief;

TEST(ParallelRows, EveryRowOnceInDisjointBands) {
    for (const auto& [begin, end] :
         std::vector<std::pair<int, int>>{{0, 1}, {0, 2}, {3, 4}, {0, 7}, {5, 1000}, {0, 4097}}) {
        std::vector<std::atomic<int>> seen(end);
        std::mutex m;
        std::vector<std::pair<int, int>> bands;
        std::vector<std::thread::id> threads;
        parallelRows(
            begin, end, 1,
            [&](int y0, int y1) {
                for (int y = y0; y < y1; ++y) ++seen[y];
                const std::lock_guard lock(m);
                bands.emplace_back(y0, y1);
                threads.push_back(std::this_thread::get_id());
            },
            1);
        for (int y = 0; y < end; ++y)
            ASSERT_EQ(seen[y].load(), y >= begin ? 1 : 0)
                << "row " << y << " of " << begin << ".." << end;
        for (const auto& [y0, y1] : bands) EXPECT_LT(y0, y1);  // no empty band
        // As many bands as cores, at most one a row, each on its own thread.
        const int cores = std::max(1u, std::thread::hardware_concurrency());
        EXPECT_EQ(static_cast<int>(bands.size()), std::min(cores, end - begin));
        std::sort(threads.begin(), threads.end());
        EXPECT_EQ(std::unique(threads.begin(), threads.end()), threads.end());
    }
}

TEST(ParallelRows, SmallWorkStaysOnTheCallersThread) {
    int calls = 0;
    std::thread::id where;
    parallelRows(0, 100, 10, [&](int y0, int y1) {
        ++calls;
        where = std::this_thread::get_id();
        EXPECT_EQ(y0, 0);
        EXPECT_EQ(y1, 100);
    });  // 1000 cells, under the default 65536
    EXPECT_EQ(calls, 1);
    EXPECT_EQ(where, std::this_thread::get_id());
    parallelRows(4, 4, 1000, [&](int, int) { ++calls; });  // no rows: no call
    EXPECT_EQ(calls, 1);
}

TEST(ParallelRows, EachRowOnceWhenRowsAreHandedOut) {
    for (const auto& [begin, end] :
         std::vector<std::pair<int, int>>{{0, 1}, {3, 4}, {0, 7}, {5, 1000}, {0, 4097}}) {
        std::vector<std::atomic<int>> seen(end);
        std::mutex m;
        std::vector<std::thread::id> threads;
        parallelEachRow(
            begin, end, 1,
            [&](int y) {
                // Uneven work: a slow row must not hold the rows after it back.
                if (y % 97 == 0) std::this_thread::sleep_for(std::chrono::microseconds(200));
                ++seen[y];
                const std::lock_guard lock(m);
                threads.push_back(std::this_thread::get_id());
            },
            1);
        for (int y = 0; y < end; ++y)
            ASSERT_EQ(seen[y].load(), y >= begin ? 1 : 0)
                << "row " << y << " of " << begin << ".." << end;
        std::sort(threads.begin(), threads.end());
        const int cores = std::max(1u, std::thread::hardware_concurrency());
        EXPECT_LE(std::unique(threads.begin(), threads.end()) - threads.begin(),
                  std::min(cores, end - begin));
    }
    int calls = 0;
    parallelEachRow(4, 4, 1000, [&](int) { ++calls; });  // no rows: no call
    EXPECT_EQ(calls, 0);
}
