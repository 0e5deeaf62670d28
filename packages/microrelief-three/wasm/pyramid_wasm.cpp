// pyramid_wasm.cpp: the C++ max pyramid (microrelief::core's MaxPyramid, unchanged) behind a
// C interface for JavaScript, compiled to WebAssembly by scripts/build.mjs. The package's
// CPU path (src/pyramid.js) uses it where WebGL 2 cannot render into R16F: the same
// windows texel for texel as the GPU builder, as halves of bound / 2^S (docs/engine.md,
// "Textures"), ready for a GL_R16F upload.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "microrelief/core/heightmap/MaxPyramid.h"

using namespace microrelief;

namespace {

std::string lastError;
std::vector<std::unique_ptr<MaxPyramid>> pyramids;  // handle k + 1 is pyramids[k]

MaxPyramid* find(int handle) {
    if (handle < 1 || handle > static_cast<int>(pyramids.size())) return nullptr;
    return pyramids[handle - 1].get();
}

// A stored bound divided by 2^S: a normal half or 0, exactly (storedBound), as its bits.
std::uint16_t halfBits(float bound, int scaleExponent) {
    if (bound == 0.0f) return 0;
    const float scaled = std::ldexp(bound, -scaleExponent);
    const std::uint32_t bits = std::bit_cast<std::uint32_t>(scaled);
    const int exponent = static_cast<int>(bits >> 23) - 127 + 15;
    return static_cast<std::uint16_t>((exponent << 10) | ((bits >> 13) & 0x3ffu));
}

}  // namespace

extern "C" {

// The windows pyramid of `samples` (width x height floats, row 0 first), u wrapped when
// `wrapU` (a curved base): a handle, or 0 with mr_last_error() saying why (a bad size, a
// negative or non-finite sample: heightMapFromSamples's messages).
int mr_build_windows(const float* samples, int width, int height, int wrapU) {
    try {
        const HeightMap map = heightMapFromSamples(samples, width, height,
                                                   static_cast<std::size_t>(width) * sizeof(float),
                                                   {}, "the height map");
        pyramids.push_back(std::make_unique<MaxPyramid>(map, wrapU != 0, BoundPrecision::Half));
        return static_cast<int>(pyramids.size());
    } catch (const std::exception& e) {
        lastError = e.what();
        return 0;
    }
}

int mr_level_count(int handle) {
    const MaxPyramid* p = find(handle);
    return p ? p->windowLevelCount() : 0;
}

// Level `level`'s width << 16 | height.
int mr_level_size(int handle, int level) {
    const MaxPyramid* p = find(handle);
    return p ? (p->windowLevelWidth(level) << 16) | p->windowLevelHeight(level) : 0;
}

// Level `level`'s texels, row 0 first, as half bits of bound / 2^S.
void mr_copy_level(int handle, int level, std::uint16_t* out) {
    const MaxPyramid* p = find(handle);
    if (!p) return;
    const std::vector<float>& data = p->windowLevelData(level);
    for (std::size_t k = 0; k < data.size(); ++k) out[k] = halfBits(data[k], p->scaleExponent());
}

float mr_max_height(int handle) {
    const MaxPyramid* p = find(handle);
    return p ? p->maxHeight() : 0.0f;
}

int mr_scale_exponent(int handle) {
    const MaxPyramid* p = find(handle);
    return p ? p->scaleExponent() : 0;
}

void mr_release(int handle) {
    if (find(handle)) pyramids[handle - 1].reset();
}

const char* mr_last_error() { return lastError.c_str(); }
}
