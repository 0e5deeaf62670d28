// The benchmark's clocks: a draw timed by a GL timer query and by the wall clock to
// glFinish (llvmpipe answers timer queries without timing its rasteriser, so only the
// second means anything there), and the median of a series.
#pragma once

#include <algorithm>
#include <chrono>
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
        gl_.Finish();
        const auto start = std::chrono::steady_clock::now();
        gl_.BeginQuery(GL_TIME_ELAPSED, query_.id());
        draw();
        gl_.EndQuery(GL_TIME_ELAPSED);
        gl_.Finish();
        const double wall =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        GLuint64 ns = 0;
        gl_.GetQueryObjectui64v(query_.id(), GL_QUERY_RESULT, &ns);
        return {ns * 1e-6, wall};
    }

private:
    const GL& gl_;
    gl::Query query_;
};

}  // namespace microrelief::bench
