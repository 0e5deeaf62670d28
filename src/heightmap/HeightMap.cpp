#include "heightmap/HeightMap.h"

#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/Error.h"

namespace microrelief {

float HeightMap::clamped(int i, int j) const {
    return at(std::clamp(i, 0, width - 1), std::clamp(j, 0, height - 1));
}

float HeightMap::wrapped(int i, int j) const {
    const int column = i % width;
    return at(column < 0 ? column + width : column, std::clamp(j, 0, height - 1));
}

double HeightMap::surface(double x, double y, bool wrapU) const {
    // Sample centres sit at half-integers: shift so that sample i is at integer i.
    const double sx = x - 0.5, sy = y - 0.5;
    const double fx0 = std::floor(sx), fy0 = std::floor(sy);
    const int i = static_cast<int>(fx0), j = static_cast<int>(fy0);
    const double fx = sx - fx0, fy = sy - fy0;
    const double h00 = sample(i, j, wrapU), h10 = sample(i + 1, j, wrapU);
    const double h01 = sample(i, j + 1, wrapU), h11 = sample(i + 1, j + 1, wrapU);
    return (h00 * (1 - fx) + h10 * fx) * (1 - fy) + (h01 * (1 - fx) + h11 * fx) * fy;
}

double HeightMap::surface(double x, double y, bool wrapU, Interpolation interpolation) const {
    if (interpolation == Interpolation::Bilinear) return surface(x, y, wrapU);
    // The texel square holding (x, y), and the position in it from its sample.
    const double fx0 = std::floor(x), fy0 = std::floor(y);
    const int i = static_cast<int>(fx0), j = static_cast<int>(fy0);
    double wx[3], wy[3];
    quadraticWeights(x - fx0 - 0.5, wx);
    quadraticWeights(y - fy0 - 0.5, wy);
    double h = 0.0;
    for (int b = 0; b < 3; ++b) {
        for (int a = 0; a < 3; ++a) h += wx[a] * wy[b] * sample(i - 1 + a, j - 1 + b, wrapU);
    }
    return h;
}

Interpolation parseInterpolation(const std::string& name) {
    if (name == "bilinear") return Interpolation::Bilinear;
    if (name == "biquadratic") return Interpolation::Biquadratic;
    throwBadInput("unknown --interpolation '" + name + "' (expected bilinear or biquadratic)");
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

namespace {

std::string describe(const std::filesystem::path& file) {
    return file.string();
}

// libpng, under OpenImageIO 2.4's PNG reader, prints "libpng error: ..." to stderr
// itself before OIIO reports the same failure to us; our one-line error says it
// already. Silence file descriptor 2 while OIIO reads (loading is single-threaded).
class QuietStderr {
public:
    QuietStderr() {
        std::fflush(stderr);
        saved_ = ::dup(2);
        const int null = ::open("/dev/null", O_WRONLY);
        if (saved_ >= 0 && null >= 0) ::dup2(null, 2);
        if (null >= 0) ::close(null);
    }
    ~QuietStderr() {
        std::fflush(stderr);
        if (saved_ >= 0) {
            ::dup2(saved_, 2);
            ::close(saved_);
        }
    }
    QuietStderr(const QuietStderr&) = delete;
    QuietStderr& operator=(const QuietStderr&) = delete;

private:
    int saved_ = -1;
};

}  // namespace

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
                              "--normalize cannot map it");
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
                        ? "try --normalize to map [min, max] to [0, 1]"
                        : "--normalize rescales finite maps only: repair the map first")
                << ")";
        throwBadInput(message.str());
    }
}

HeightMap loadHeightMap(const std::filesystem::path& file, const HeightMapLoadOptions& options) {
    const std::string name = describe(file);
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) throwBadInput(name + ": no such file");
    if (std::filesystem::is_directory(file, ec))
        throwBadInput(name + ": is a directory, not an image");

    const QuietStderr quiet;
    auto input = OIIO::ImageInput::open(name);
    if (!input) {
        std::string reason = OIIO::geterror();
        if (reason.empty()) reason = "not an image OpenImageIO can read";
        // OIIO prefixes some messages with the file name already; keep one line.
        std::replace(reason.begin(), reason.end(), '\n', ' ');
        throwBadInput(name + ": cannot read the image (" + reason + ")");
    }
    const OIIO::ImageSpec& spec = input->spec();
    if (spec.width <= 0 || spec.height <= 0)
        throwBadInput(name + ": the image is empty (0 pixels)");
    if (spec.depth > 1) throwBadInput(name + ": volume images are not height maps");
    if (options.channel < 0 || options.channel >= spec.nchannels) {
        throwBadInput(name + ": --channel " + std::to_string(options.channel) +
                      " is out of range; the image has " + std::to_string(spec.nchannels) +
                      " channel(s)");
    }

    HeightMap map(spec.width, spec.height);
    // Reading as FLOAT makes OpenImageIO normalise integer formats by their type range
    // (uint8 / 255, uint16 / 65535) and pass float formats through unchanged.
    const bool ok = input->read_image(0, 0, options.channel, options.channel + 1,
                                      OIIO::TypeDesc::FLOAT, map.samples.data());
    if (!ok) {
        std::string reason = input->geterror();
        std::replace(reason.begin(), reason.end(), '\n', ' ');
        throwBadInput(name + ": cannot read the pixels (" +
                      (reason.empty() ? "truncated or corrupt" : reason) + ")");
    }
    input->close();
    prepareHeights(map, options, name);
    return map;
}

}  // namespace microrelief
