// The pictures the viewer writes, as 8-bit RGB rows top first: the view's picture (the
// relief pass at the view's size, no panel: what --screenshot, P and F12 write, the same
// pixels microrelief-render writes for the copied command) and the window as shown, panel
// included (--window-screenshot).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "microrelief/gl/OffscreenTarget.h"
#include "microrelief/io/ImageFile.h"

namespace microrelief {

struct RgbPicture {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgb;
    // The picture as an image file takes it (it points into `rgb`).
    ImageData image() const { return {width, height, 3, PixelType::UInt8, rgb.data(), {}}; }
};

// `target`'s colour, whose positions are relative to `eye` (the eye it was drawn from).
RgbPicture viewPicture(const OffscreenTarget& target, const glm::dvec3& eye);

// The window's back buffer, `framebufferSize` pixels, as drawn before the swap.
RgbPicture windowPicture(const GL& gl, const glm::ivec2& framebufferSize);

}  // namespace microrelief
