#include "Aov.h"

#include <vector>

namespace microrelief {

void writeAov(ImageWriteBatch& batch, const std::filesystem::path& file, const RenderedFrame& frame,
              bool withShadow) {
    // World positions: the frame's are relative to its origin (the eye), added back in
    // double and rounded once to the file's float (whose step is the world's at the hit:
    // 0.0625 at 9e5 from the origin; the frame's own positions keep the eye-relative ones).
    const int count = withShadow ? 5 : 4;
    const std::size_t pixels = static_cast<std::size_t>(frame.width) * frame.height;
    std::vector<float> channels(pixels * count);
    for (std::size_t p = 0; p < pixels; ++p) {
        const float* position = &frame.position[4 * p];
        const bool hit = position[3] > 0.5f;
        for (int c = 0; c < 3; ++c) {
            channels[count * p + c] =
                hit ? static_cast<float>(frame.positionOrigin[c] + position[c]) : position[c];
        }
        channels[count * p + 3] = position[3];
        if (withShadow) channels[count * p + 4] = hit ? frame.shadow[p] : 0.0f;
    }
    if (!withShadow) {
        batch.write(file, {frame.width, frame.height, 4, PixelType::Float, channels.data(),
                           {"R", "G", "B", "A"}});
        return;
    }
    // write() stages the file before returning: the buffer need not outlive it.
    batch.write(file, {frame.width,
                       frame.height,
                       5,
                       PixelType::Float,
                       channels.data(),
                       {"R", "G", "B", "A", "shadow"}});
}

}  // namespace microrelief
