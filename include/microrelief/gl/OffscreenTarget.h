// A framebuffer object with the outputs of relief.frag: the shaded picture (SRGB8_ALPHA8:
// the shader's linear colour encoded by the GL while sRGB writes are on, gl::SrgbWrites),
// the world position AOV and the traversal statistics (RGBA32F each), the light's share
// at each hit (R32F: the shadow AOV), and a 32-bit float depth buffer (reversed-Z keeps
// its precision there). Reads
// come back top row first, the orientation of every output image.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "microrelief/gl/Objects.h"
#include "microrelief/gl/RenderedFrame.h"

namespace microrelief {

class OffscreenTarget {
public:
    // Throws Error(BadInput) when the size exceeds the GL's limits, Error(Runtime)
    // when the framebuffer is incomplete.
    OffscreenTarget(const GL& gl, int width, int height);

    void bind() const;
    // Clears the picture to `background` (linear RGB, encoded to sRGB by the GL), the AOV
    // and statistics to 0 and depth to `depth` (1, the far end; 0 under reversed-Z).
    void clear(const glm::vec3& background, float depth = 1.0f) const;
    // The picture; `positionOrigin` is the eye it was drawn from (ReliefRenderer::draw
    // writes hit positions relative to it: RenderedFrame::positionOrigin).
    RenderedFrame read(const glm::dvec3& positionOrigin) const;
    // The depth buffer (32-bit float), window depths, top row first.
    std::vector<float> readDepth() const;
    // The lower-left width x height pixels of this target into `frame` (a picture of its
    // own size, allocated by the caller), as the tile whose lower-left corner is at GL
    // window position (x, y) of that picture.
    void readInto(RenderedFrame& frame, int x, int y, int width, int height) const;

    // The position AOV of one pixel (column, row; row 0 the top): x, y, z of the hit less
    // the eye it was drawn from (ReliefRenderer::draw) and 1, or 0 where the ray missed. A
    // one-pixel read, for picking what the picture shows.
    glm::vec4 positionAt(int column, int row) const;

    int width() const { return width_; }
    int height() const { return height_; }

private:
    const GL& gl_;
    int width_, height_;
    gl::Framebuffer framebuffer_;
    gl::Texture color_, position_, stats_, shadow_;
    gl::Renderbuffer depth_;
};

}  // namespace microrelief
