// A colour texture laid over the relief (--albedo): the surface's diffuse colour at each
// (u, v) of the map, sampled at the exact hit. Held as the GPU takes it: 8-bit images as
// stored (sRGB-encoded RGBA, which the GL decodes when it filters), anything else as
// linear float RGBA.
#pragma once

#include <cstdint>
#include <vector>

namespace microrelief {

struct AlbedoImage {
    int width = 0, height = 0;
    bool srgb8 = false;               // bytes hold the pixels, else linear does
    std::vector<std::uint8_t> bytes;  // RGBA8, sRGB-encoded, row 0 at v = 0
    std::vector<float> linear;        // RGBA32F, linear, row 0 at v = 0

    bool empty() const { return width == 0; }
};

// The sRGB transfer function and its inverse, per channel in [0, 1].
float srgbToLinear(float encoded);
float linearToSrgb(float linear);

}  // namespace microrelief
