// A rendered picture read back to the host: the shaded colour, the world position AOV
// and the traversal statistics of relief.frag, top row first (OffscreenTarget reads it;
// the accuracy figures, core/trace/Accuracy.h, compare it with the exact reference).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace microrelief {

struct RenderedFrame {
    int width = 0, height = 0;
    std::vector<std::uint8_t> color;  // RGBA8, row 0 at the top
    std::vector<float> position;      // RGBA32F: world x, y, z, hit (1) or miss (0)
    std::vector<float> stats;         // RGBA32F: iterations, fetches, stop level (the instrumented
                                      // variant: fetches of the bounds), exhausted
    std::vector<float> shadow;        // one float: how much of the light reaches the hit (1 lit)

    const float* positionAt(int column, int row) const {
        return &position[(static_cast<std::size_t>(row) * width + column) * 4];
    }
    const float* statsAt(int column, int row) const {
        return &stats[(static_cast<std::size_t>(row) * width + column) * 4];
    }
    float shadowAt(int column, int row) const {
        return shadow[static_cast<std::size_t>(row) * width + column];
    }
};

}  // namespace microrelief
