#include "microrelief/core/image/Albedo.h"

#include <algorithm>
#include <cmath>

namespace microrelief {

float srgbToLinear(float encoded) {
    const float c = std::clamp(encoded, 0.0f, 1.0f);
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

float linearToSrgb(float linear) {
    const float c = std::clamp(linear, 0.0f, 1.0f);
    return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

}  // namespace microrelief
