// A framebuffer object with the outputs of relief.frag: the shaded picture (RGBA8,
// sRGB-encoded by the shader), the world position AOV and the traversal statistics
// (RGBA32F each), and a depth buffer. Reads come back top row first, the orientation
// of every output image.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "gl/Objects.h"

namespace microrelief {

struct RenderedFrame {
    int width = 0, height = 0;
    std::vector<std::uint8_t> color;  // RGBA8, row 0 at the top
    std::vector<float> position;      // RGBA32F: world x, y, z, hit (1) or miss (0)
    std::vector<float> stats;         // RGBA32F: iterations, fetches, stop level, exhausted

    const float* positionAt(int column, int row) const {
        return &position[(static_cast<std::size_t>(row) * width + column) * 4];
    }
    const float* statsAt(int column, int row) const {
        return &stats[(static_cast<std::size_t>(row) * width + column) * 4];
    }
};

class OffscreenTarget {
public:
    // Throws Error(BadInput) when the size exceeds the GL's limits, Error(Runtime)
    // when the framebuffer is incomplete.
    OffscreenTarget(const GL& gl, int width, int height);

    void bind() const;
    // Clears the picture to `background` (linear RGB, encoded to sRGB here), the AOV and
    // statistics to 0 and depth to 1.
    void clear(const glm::vec3& background) const;
    RenderedFrame read() const;
    // The lower-left width x height pixels of this target into `frame` (a picture of its
    // own size, allocated by the caller), as the tile whose lower-left corner is at GL
    // window position (x, y) of that picture.
    void readInto(RenderedFrame& frame, int x, int y, int width, int height) const;

    int width() const { return width_; }
    int height() const { return height_; }

private:
    const GL& gl_;
    int width_, height_;
    gl::Framebuffer framebuffer_;
    gl::Texture color_, position_, stats_;
    gl::Renderbuffer depth_;
};

}  // namespace microrelief
