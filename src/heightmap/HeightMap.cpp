#include "heightmap/HeightMap.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

#include "core/Error.h"
#include "heightmap/ExrCheck.h"
#include "heightmap/PngCheck.h"

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

namespace {

// Before OpenImageIO sees the path: a device (/dev/zero), a FIFO or a socket never ends
// or blocks, and OpenImageIO's format probes would read it forever.
void checkRegularFile(const std::filesystem::path& file, const std::string& name) {
    std::error_code ec;
    const std::filesystem::file_status status = std::filesystem::status(file, ec);
    if (status.type() == std::filesystem::file_type::not_found)
        throwBadInput(name + ": no such file");
    if (ec) throwBadInput(name + ": cannot read (" + ec.message() + ")");
    if (status.type() == std::filesystem::file_type::directory)
        throwBadInput(name + ": is a directory, not an image");
    if (status.type() != std::filesystem::file_type::regular)
        throwBadInput(name +
                      ": is not a regular file (a device, FIFO or socket); give an image file");
}

void checkSize(const std::string& name, long long width, long long height, int maxSide) {
    if (width <= 0 || height <= 0) throwBadInput(name + ": the image is empty (0 pixels)");
    if (width > maxSide || height > maxSide) {
        throwBadInput(name + ": " + std::to_string(width) + " x " + std::to_string(height) +
                      " is larger than the " + std::to_string(maxSide) + " x " +
                      std::to_string(maxSide) + " a height map may have");
    }
}

std::string oneLine(std::string text) {
    std::replace(text.begin(), text.end(), '\n', ' ');
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text;
}

}  // namespace

HeightMap loadHeightMap(const std::filesystem::path& file, const HeightMapLoadOptions& options) {
    const std::string name = describe(file);
    checkRegularFile(file, name);
    if (hasPngSignature(file)) {
        // The size first, from IHDR alone, then the structure (which inflates the data).
        std::string defect;
        const std::optional<PngHeader> header = readPngHeader(file, defect);
        if (!header) throwBadInput(name + ": not a valid PNG (" + defect + ")");
        checkSize(name, header->width, header->height, options.maxSide);
        if (const auto bad = pngStructureDefect(file))
            throwBadInput(name + ": not a valid PNG (" + *bad + ")");
    } else if (hasExrMagic(file)) {
        std::string defect;
        const auto parts = readExrHeader(file, defect);
        if (!parts) throwBadInput(name + ": not a valid OpenEXR file (" + defect + ")");
        for (const ExrPartSize& part : *parts)
            checkSize(name, part.width, part.height, options.maxSide);
    }

    // The reader the extension names, and only that one: OpenImageIO's ImageInput::open
    // tries every reader it has when that one fails, and some of the 28 are no place for
    // a damaged file (the fuzzer had a 26-byte file make the WebP reader allocate 872 MB;
    // the IFF probe reads /dev/zero forever). The format follows the extension, as for
    // the outputs.
    std::string extension = file.extension().string();
    if (extension.size() < 2) throwBadInput(name + ": no extension to tell the image format by");
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    auto input = OIIO::ImageInput::create(extension.substr(1), /*do_open=*/false);
    if (!input) {
        OIIO::geterror();  // clear the pending message
        throwBadInput(name + ": no image format OpenImageIO reads for the extension '" +
                      file.extension().string() + "'");
    }
    OIIO::ImageSpec opened;
    if (!input->open(name, opened)) {
        std::string reason = oneLine(input->geterror());
        if (reason.empty()) reason = "not a " + std::string(input->format_name()) + " file";
        throwBadInput(name + ": cannot read the image (" + reason + ")");
    }
    const OIIO::ImageSpec& spec = input->spec();
    checkSize(name, spec.width, spec.height, options.maxSide);
    if (spec.depth > 1) throwBadInput(name + ": volume images are not height maps");
    if (spec.nchannels > kMaxHeightMapChannels) {
        throwBadInput(name + ": " + std::to_string(spec.nchannels) + " channels, more than the " +
                      std::to_string(kMaxHeightMapChannels) + " a height map may have");
    }
    if (options.channel < 0 || options.channel >= spec.nchannels) {
        throwBadInput(name + ": --channel " + std::to_string(options.channel) +
                      " is out of range; the image has " + std::to_string(spec.nchannels) +
                      " channel(s)");
    }

    try {
        HeightMap map(spec.width, spec.height);
        // Reading as FLOAT makes OpenImageIO normalise integer formats by their type range
        // (uint8 / 255, uint16 / 65535) and pass float formats through unchanged.
        const bool ok = input->read_image(0, 0, options.channel, options.channel + 1,
                                          OIIO::TypeDesc::FLOAT, map.samples.data());
        if (!ok) {
            const std::string reason = oneLine(input->geterror());
            throwBadInput(name + ": cannot read the pixels (" +
                          (reason.empty() ? "truncated or corrupt" : reason) + ")");
        }
        input->close();
        prepareHeights(map, options, name);
        return map;
    } catch (const std::bad_alloc&) {
        throwRuntime(name + ": not enough memory for its " + std::to_string(spec.width) + " x " +
                     std::to_string(spec.height) + " samples");
    }
}

}  // namespace microrelief
