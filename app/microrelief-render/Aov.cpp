#include "Aov.h"

#include <vector>

namespace microrelief {

void writeAov(ImageWriteBatch& batch, const std::filesystem::path& file, const RenderedFrame& frame,
              bool withShadow) {
    if (!withShadow) {
        batch.write(file, {frame.width,
                           frame.height,
                           4,
                           PixelType::Float,
                           frame.position.data(),
                           {"R", "G", "B", "A"}});
        return;
    }
    const std::size_t pixels = static_cast<std::size_t>(frame.width) * frame.height;
    std::vector<float> channels(pixels * 5);
    for (std::size_t p = 0; p < pixels; ++p) {
        for (int c = 0; c < 4; ++c) channels[5 * p + c] = frame.position[4 * p + c];
        channels[5 * p + 4] = frame.position[4 * p + 3] > 0.5f ? frame.shadow[p] : 0.0f;
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
