#include "microrelief/core/heightmap/HeightMap.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

#include "microrelief/core/Error.h"

namespace microrelief {

HeightMap rowsReversed(const HeightMap& map) {
    HeightMap reversed(map.width, map.height);
    for (int j = 0; j < map.height; ++j)
        for (int i = 0; i < map.width; ++i) reversed.at(i, j) = map.at(i, map.height - 1 - j);
    return reversed;
}

float HeightMap::clamped(int i, int j) const {
    return at(std::clamp(i, 0, width - 1), std::clamp(j, 0, height - 1));
}

float HeightMap::wrapped(int i, int j) const {
    const int column = i % width;
    return at(column < 0 ? column + width : column, std::clamp(j, 0, height - 1));
}

float HeightMap::sample(int i, int j, const MapAddressing& a) const {
    const int w = width * a.tilesX, h = height * a.tilesY;
    if (a.wrapU) {
        i %= w;
        if (i < 0) i += w;
    } else {
        i = std::clamp(i, 0, w - 1);
    }
    j = std::clamp(j, 0, h - 1);
    return at(i % width, j % height);
}

double HeightMap::surface(double x, double y, bool wrapU) const {
    return surface(x, y, MapAddressing{wrapU}, Interpolation::Bilinear);
}

double HeightMap::surface(double x, double y, bool wrapU, Interpolation interpolation) const {
    return surface(x, y, MapAddressing{wrapU}, interpolation);
}

namespace {

// A texel coordinate moved into [-2, n + 2) without changing the surface there: clamped
// beyond the edge (every sample a stencil reaches past it is the edge's sample), or, where
// the map repeats, moved by whole periods (std::fmod is exact). Coordinates already in
// range are left as they are, bit for bit. Without it a ray's far end (x ~ 1e15 for a grazing
// ray) overflows the int cast of its texel, which is undefined behaviour.
double intoRange(double x, int n, bool repeats) {
    if (x >= -2.0 && x < n + 2.0) return x;
    if (!repeats) return std::clamp(x, -2.0, n + 2.0);
    const double r = std::fmod(x, static_cast<double>(n));
    return r < 0.0 ? r + n : r;
}

}  // namespace

double HeightMap::surface(double x, double y, const MapAddressing& a,
                          Interpolation interpolation) const {
    // A NaN coordinate (a caller's degenerate case) has no surface: NaN, not a texel.
    if (std::isnan(x) || std::isnan(y)) return std::numeric_limits<double>::quiet_NaN();
    x = intoRange(x, width * a.tilesX, a.wrapU);
    y = intoRange(y, height * a.tilesY, false);
    if (interpolation == Interpolation::Bilinear) {
        // Sample centres sit at half-integers: shift so that sample i is at integer i.
        const double sx = x - 0.5, sy = y - 0.5;
        const double fx0 = std::floor(sx), fy0 = std::floor(sy);
        const int i = static_cast<int>(fx0), j = static_cast<int>(fy0);
        const double fx = sx - fx0, fy = sy - fy0;
        const double h00 = sample(i, j, a), h10 = sample(i + 1, j, a);
        const double h01 = sample(i, j + 1, a), h11 = sample(i + 1, j + 1, a);
        return (h00 * (1 - fx) + h10 * fx) * (1 - fy) + (h01 * (1 - fx) + h11 * fx) * fy;
    }
    // The texel square holding (x, y), and the position in it from its sample.
    const double fx0 = std::floor(x), fy0 = std::floor(y);
    const int i = static_cast<int>(fx0), j = static_cast<int>(fy0);
    double wx[3], wy[3];
    quadraticWeights(x - fx0 - 0.5, wx);
    quadraticWeights(y - fy0 - 0.5, wy);
    double h = 0.0;
    for (int b = 0; b < 3; ++b) {
        for (int c = 0; c < 3; ++c) h += wx[c] * wy[b] * sample(i - 1 + c, j - 1 + b, a);
    }
    return h;
}

Interpolation parseInterpolation(const std::string& name) {
    if (name == "bilinear") return Interpolation::Bilinear;
    if (name == "biquadratic") return Interpolation::Biquadratic;
    throwBadInput("unknown {interpolation} '" + name + "' (expected bilinear or biquadratic)");
}

const char* interpolationName(Interpolation interpolation) {
    return interpolation == Interpolation::Biquadratic ? "biquadratic" : "bilinear";
}

float HeightMap::maxValue() const {
    return samples.empty() ? 0.0f : *std::max_element(samples.begin(), samples.end());
}

float HeightMap::minValue() const {
    return samples.empty() ? 0.0f : *std::min_element(samples.begin(), samples.end());
}

void prepareHeights(HeightMap& map, const HeightMapLoadOptions& options,
                    const std::string& source) {
    if (map.width <= 0 || map.height <= 0 || map.empty()) {
        throwBadInput(source + ": the height map has no samples");
    }
    if (options.normalize) {
        float lo = INFINITY, hi = -INFINITY;
        for (float h : map.samples) {
            if (!std::isfinite(h)) {
                throwBadInput(source +
                              ": the height map holds a non-finite value (NaN or Inf); "
                              "{map.load.normalize} cannot map it");
            }
            lo = std::min(lo, h);
            hi = std::max(hi, h);
        }
        const float range = hi - lo;
        for (float& h : map.samples) h = range > 0.0f ? (h - lo) / range : 0.0f;
        return;
    }
    for (std::size_t k = 0; k < map.samples.size(); ++k) {
        const float h = map.samples[k];
        if (std::isfinite(h) && h >= 0.0f) continue;
        const int i = static_cast<int>(k % map.width), j = static_cast<int>(k / map.width);
        std::ostringstream message;
        // The spec asks every refusal to suggest --normalize; for a non-finite value it
        // can only help once the value is repaired, and the message says so.
        message << source << ": sample (" << i << ", " << j << ") is " << h
                << "; heights must be finite and >= 0 ("
                << (std::isfinite(h)
                        ? "try {map.load.normalize} to map [min, max] to [0, 1]"
                        : "{map.load.normalize} rescales finite maps only: repair the map first")
                << ")";
        throwBadInput(message.str());
    }
}

HeightMap repeatMap(const HeightMap& tile, int tilesX, int tilesY, std::size_t maxSamples) {
    const std::size_t samples =
        tile.samples.size() * static_cast<std::size_t>(tilesX) * static_cast<std::size_t>(tilesY);
    if (samples > maxSamples) {
        throwBadInput("the map tiled " + std::to_string(tilesX) + " x " + std::to_string(tilesY) +
                      " would be " + std::to_string(samples) + " samples, more than the " +
                      std::to_string(maxSamples) + " it may be repeated to");
    }
    HeightMap whole(tile.width * tilesX, tile.height * tilesY);
    for (int j = 0; j < whole.height; ++j)
        for (int i = 0; i < whole.width; ++i)
            whole.at(i, j) = tile.at(i % tile.width, j % tile.height);
    return whole;
}

namespace {

// heightMapFromSamples for either sample type: `scale` maps a stored value to [0, 1].
template <class Sample>
HeightMap copySamples(const Sample* samples, int width, int height, std::size_t rowStrideBytes,
                      float scale, const HeightMapLoadOptions& options, const std::string& source) {
    if (samples == nullptr) throwBadInput(source + ": no samples (a null pointer)");
    if (width <= 0 || height <= 0)
        throwBadInput(source + ": the height map has no samples (" + std::to_string(width) + " x " +
                      std::to_string(height) + ")");
    if (width > options.maxSide || height > options.maxSide) {
        throwBadInput(source + ": " + std::to_string(width) + " x " + std::to_string(height) +
                      " is larger than the " + std::to_string(options.maxSide) + " x " +
                      std::to_string(options.maxSide) + " a height map may have");
    }
    const std::size_t rowBytes = static_cast<std::size_t>(width) * sizeof(Sample);
    if (rowStrideBytes < rowBytes) {
        throwBadInput(source + ": a row stride of " + std::to_string(rowStrideBytes) +
                      " bytes is shorter than a row (" + std::to_string(rowBytes) + " bytes)");
    }
    HeightMap map(width, height);
    const auto* bytes = reinterpret_cast<const unsigned char*>(samples);
    for (int j = 0; j < height; ++j) {
        // Rows need not be aligned for Sample: copy each value's bytes.
        const unsigned char* row = bytes + rowStrideBytes * static_cast<std::size_t>(j);
        for (int i = 0; i < width; ++i) {
            Sample value;
            std::memcpy(&value, row + static_cast<std::size_t>(i) * sizeof(Sample), sizeof(Sample));
            map.at(i, j) = static_cast<float>(value) * scale;
        }
    }
    prepareHeights(map, options, source);
    return map;
}

}  // namespace

HeightMap heightMapFromSamples(const float* samples, int width, int height,
                               std::size_t rowStrideBytes, const HeightMapLoadOptions& options,
                               const std::string& source) {
    return copySamples(samples, width, height, rowStrideBytes, 1.0f, options, source);
}

HeightMap heightMapFromSamples(const std::uint16_t* samples, int width, int height,
                               std::size_t rowStrideBytes, const HeightMapLoadOptions& options,
                               const std::string& source) {
    return copySamples(samples, width, height, rowStrideBytes, 1.0f / 65535.0f, options, source);
}

}  // namespace microrelief
