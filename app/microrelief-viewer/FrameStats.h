// The live figures of the panel: the GPU time of the relief pass from GL timer queries,
// and the mean number of segments the traversal visits per pixel, read back from the
// statistics output of relief.frag.
#pragma once

#include <array>
#include <optional>

#include "microrelief/gl/Objects.h"
#include "microrelief/gl/OffscreenTarget.h"

namespace microrelief {

// GL_TIME_ELAPSED around a pass, in a ring of queries read only once their result is
// available, so measuring never stalls the pipeline; the figure lags a frame or two.
class GpuTimer {
public:
    explicit GpuTimer(const GL& gl);
    void begin();
    void end();
    // Reads whatever measurements have finished; call once a frame.
    void poll() { collect(false); }
    // The most recent finished measurement, milliseconds.
    std::optional<double> lastMilliseconds() const { return last_; }

private:
    void collect(bool wait);

    static constexpr int kRing = 4;
    const GL& gl_;
    std::array<gl::Query, kRing> queries_;
    std::array<bool, kRing> pending_{};
    int next_ = 0;
    std::optional<double> last_;
};

struct IterationStats {
    double meanPerHitPixel = 0.0;  // over pixels whose ray was traced to a hit
    int maxIterations = 0;
    std::size_t hitPixels = 0;
};

// Reads the iterations channel of the target's statistics output (one float a pixel:
// a quarter of the full RGBA32F readback, cheap enough a few times a second on a
// software rasteriser). Leaves the target's framebuffer bound.
IterationStats readIterationStats(const GL& gl, const OffscreenTarget& target);

}  // namespace microrelief
