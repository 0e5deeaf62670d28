// The benchmark's clocks: a draw timed by a GL timer query, by the wall clock to glFinish
// and by the process's CPU time to glFinish (llvmpipe answers timer queries without timing
// its rasteriser, so only the last two mean anything there); the median of a series, its
// quartiles, the order in which interleaved settings are drawn, and the ratio of two
// settings timed in the same rounds.
#pragma once

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "microrelief/gl/Objects.h"

namespace microrelief::bench {

// A CPU rasteriser (llvmpipe, softpipe): its GL timer query does not cover the deferred
// rasterisation, so the tables use the glFinish wall time there; on anything else, a GPU.
inline bool softwareRenderer(const std::string& renderer) {
    return renderer.find("llvmpipe") != std::string::npos ||
           renderer.find("softpipe") != std::string::npos ||
           renderer.find("swrast") != std::string::npos;
}

inline double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n == 0 ? 0.0 : n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// A series' median and quartiles (linear between the order statistics, as R's default
// type 7 and numpy's percentile): the spread the reports give beside a median.
struct Spread {
    double median = 0.0, low = 0.0, high = 0.0;  // the 50th, 25th and 75th percentiles
    // Half the interquartile range over the median, in percent: the "+-" of a median.
    double halfIqrPercent() const { return median > 0.0 ? 50.0 * (high - low) / median : 0.0; }
};

inline double percentile(const std::vector<double>& sorted, double q) {
    if (sorted.empty()) return 0.0;
    const double at = q * static_cast<double>(sorted.size() - 1);
    const std::size_t below = static_cast<std::size_t>(at);
    if (below + 1 >= sorted.size()) return sorted.back();
    return sorted[below] + (at - static_cast<double>(below)) * (sorted[below + 1] - sorted[below]);
}

inline Spread spreadOf(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    return {percentile(values, 0.5), percentile(values, 0.25), percentile(values, 0.75)};
}

// Settings timed frame by frame in turn: `rounds` rounds, each drawing every one of
// `settings` once, round r starting at setting r mod settings and going on in order. A
// slow spell on a shared machine (another process, a frequency step) then falls on every
// setting alike, and none is always drawn first or right after the same neighbour.
// Returns the settings' indices in the order they are drawn.
inline std::vector<std::size_t> interleavedOrder(std::size_t settings, int rounds) {
    std::vector<std::size_t> order;
    for (int round = 0; round < rounds; ++round)
        for (std::size_t k = 0; k < settings; ++k)
            order.push_back((static_cast<std::size_t>(round) + k) % settings);
    return order;
}

// The ratio of two settings timed in the same rounds (series of one frame a round, in
// round order): each round's a over b, then their median and quartiles. Paired so that
// what slows a round slows both of its frames, and cancels.
inline Spread pairedRatio(const std::vector<double>& a, const std::vector<double>& b) {
    std::vector<double> ratios;
    for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k)
        if (b[k] > 0.0) ratios.push_back(a[k] / b[k]);
    return spreadOf(ratios);
}

// The CPU time of every thread of this process (llvmpipe's rasteriser threads included),
// milliseconds: what a frame cost the CPU, whatever else ran on it meanwhile.
inline double processCpuMs() {
    timespec now{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec) * 1e3 + static_cast<double>(now.tv_nsec) * 1e-6;
}

// One frame's times, milliseconds: the GL timer query's, the wall clock's and the process's
// CPU time, each to glFinish.
struct FrameTimes {
    double gpu = 0.0, wall = 0.0, cpu = 0.0;
};

// Wall milliseconds of `work` to glFinish (on llvmpipe the timer query misses the
// rasteriser's work; on a GPU the two agree for passes this long).
template <typename Work>
double wallMs(const GL& gl, Work&& work) {
    gl.Finish();
    const auto start = std::chrono::steady_clock::now();
    work();
    gl.Finish();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

class Timer {
public:
    explicit Timer(const GL& gl) : gl_(gl), query_(gl::Query::create(gl)) {}

    // GPU and wall milliseconds of one draw.
    std::pair<double, double> time(const std::function<void()>& draw) {
        const FrameTimes t = frame(draw);
        return {t.gpu, t.wall};
    }

    // GPU, wall and process CPU milliseconds of one draw.
    FrameTimes frame(const std::function<void()>& draw) {
        gl_.Finish();
        const double cpuStart = processCpuMs();
        const auto start = std::chrono::steady_clock::now();
        gl_.BeginQuery(GL_TIME_ELAPSED, query_.id());
        draw();
        gl_.EndQuery(GL_TIME_ELAPSED);
        gl_.Finish();
        FrameTimes t;
        t.wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                     .count();
        t.cpu = processCpuMs() - cpuStart;
        GLuint64 ns = 0;
        gl_.GetQueryObjectui64v(query_.id(), GL_QUERY_RESULT, &ns);
        t.gpu = ns * 1e-6;
        return t;
    }

private:
    const GL& gl_;
    gl::Query query_;
};

}  // namespace microrelief::bench
