// A rendered picture read back to the host: the shaded colour, the world position AOV
// and the traversal statistics of relief.frag, top row first (OffscreenTarget reads it;
// the accuracy figures, core/trace/Accuracy.h, compare it with the exact reference).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace microrelief {

struct RenderedFrame {
    int width = 0, height = 0;
    std::vector<std::uint8_t> color;  // RGBA8, row 0 at the top
    // RGBA32F: the hit's world x, y, z less positionOrigin (the eye: the renderer traces
    // relative to it, so a relief far from the world's origin keeps its precision), and
    // hit (1) or miss (0). worldPositionAt adds the origin back, in double.
    std::vector<float> position;
    glm::dvec3 positionOrigin{0.0};
    std::vector<float> stats;         // RGBA32F: iterations, fetches, stop level (the instrumented
                                      // variant: fetches of the bounds), exhausted
    std::vector<float> shadow;        // one float: how much of the light reaches the hit (1 lit)

    const float* positionAt(int column, int row) const {
        return &position[(static_cast<std::size_t>(row) * width + column) * 4];
    }
    // The world position of the pixel's hit (meaningless for a miss: positionAt's w is 0).
    glm::dvec3 worldPositionAt(int column, int row) const {
        const float* p = positionAt(column, row);
        return positionOrigin + glm::dvec3(p[0], p[1], p[2]);
    }
    const float* statsAt(int column, int row) const {
        return &stats[(static_cast<std::size_t>(row) * width + column) * 4];
    }
    float shadowAt(int column, int row) const {
        return shadow[static_cast<std::size_t>(row) * width + column];
    }
};

}  // namespace microrelief
