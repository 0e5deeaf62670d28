#include "FrameStats.h"

#include <algorithm>
#include <vector>

namespace microrelief {

GpuTimer::GpuTimer(const GL& gl) : gl_(gl) {
    for (gl::Query& query : queries_) query = gl::Query::create(gl_);
}

void GpuTimer::collect(bool wait) {
    // Oldest first, so `last_` ends on the newest finished result.
    for (int k = 0; k < kRing; ++k) {
        const int slot = (next_ + k) % kRing;
        if (!pending_[slot]) continue;
        GLint available = GL_FALSE;
        gl_.GetQueryObjectiv(queries_[slot].id(), GL_QUERY_RESULT_AVAILABLE, &available);
        if (!available && !(wait && slot == next_)) continue;
        GLuint64 nanoseconds = 0;
        gl_.GetQueryObjectui64v(queries_[slot].id(), GL_QUERY_RESULT, &nanoseconds);
        last_ = static_cast<double>(nanoseconds) * 1e-6;
        pending_[slot] = false;
    }
}

void GpuTimer::begin() {
    // The slot about to be reused was issued kRing frames ago; if it is still not done,
    // wait for it rather than lose it.
    collect(true);
    gl_.BeginQuery(GL_TIME_ELAPSED, queries_[next_].id());
}

void GpuTimer::end() {
    gl_.EndQuery(GL_TIME_ELAPSED);
    pending_[next_] = true;
    next_ = (next_ + 1) % kRing;
}

IterationStats readIterationStats(const GL& gl, const OffscreenTarget& target) {
    const int width = target.width(), height = target.height();
    std::vector<float> iterations(static_cast<std::size_t>(width) * height);
    target.bind();
    gl.ReadBuffer(GL_COLOR_ATTACHMENT2);  // relief.frag's outStats: iterations in red
    gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl.ReadPixels(0, 0, width, height, GL_RED, GL_FLOAT, iterations.data());
    IterationStats stats;
    double sum = 0.0;
    for (float n : iterations) {
        // Pixels whose ray missed are discarded by the shader and keep the cleared 0.
        if (n <= 0.0f) continue;
        sum += n;
        ++stats.hitPixels;
        stats.maxIterations = std::max(stats.maxIterations, static_cast<int>(n));
    }
    if (stats.hitPixels > 0) stats.meanPerHitPixel = sum / static_cast<double>(stats.hitPixels);
    return stats;
}

}  // namespace microrelief
