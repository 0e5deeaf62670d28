#include "microrelief/io/AlbedoFile.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "io/CheckedImageInput.h"
#include "microrelief/core/Error.h"

namespace microrelief {

namespace {

// A float albedo's colour channels must be finite: the GL filters NaN and infinity into
// black (or spreads them over the neighbours a texel is filtered with), a picture wrong
// without a word. The first bad texel, as an image viewer numbers it (row 0 the first).
template <class T>
void refuseNonFinite(const std::string& name, const std::vector<T>& read, int used, int width) {
    const int colours = std::min(used, 3);  // a 4th channel is read, then replaced by 1
    for (std::size_t k = 0; k < read.size(); ++k) {
        const int channel = static_cast<int>(k % used);
        if (channel >= colours || std::isfinite(static_cast<double>(read[k]))) continue;
        const std::size_t texel = k / used;
        throwBadInput(name + ": texel (column " + std::to_string(texel % width) + ", row " +
                      std::to_string(texel / width) + "), channel " + std::to_string(channel) +
                      " is " + (std::isnan(static_cast<double>(read[k])) ? "NaN" : "infinite") +
                      "; an albedo's colours must be finite numbers");
    }
}

}  // namespace

AlbedoImage loadAlbedo(const std::filesystem::path& file) {
    const std::string name = file.string();
    const std::unique_ptr<OIIO::ImageInput> input =
        openCheckedImage(file, kMaxAlbedoSide, "an albedo");
    const OIIO::ImageSpec& spec = input->spec();
    if (spec.depth > 1) throwBadInput(name + ": volume images are not albedo textures");
    const int channels = spec.nchannels;
    if (channels < 1 || channels > 64)
        throwBadInput(name + ": " + std::to_string(channels) + " channels; an albedo has 1 to 4");
    const bool eightBit = spec.format.basetype == OIIO::TypeDesc::UINT8;
    const bool isFloat = spec.format.is_floating_point();
    const std::size_t pixels = static_cast<std::size_t>(spec.width) * spec.height;
    try {
        AlbedoImage albedo;
        albedo.width = spec.width;
        albedo.height = spec.height;
        albedo.srgb8 = eightBit;
        const int used = std::min(channels, 4);
        // Read the first (up to) four channels, then spread grey to RGB and fill alpha.
        auto expand = [&](auto& out, auto one) {
            std::vector<std::remove_reference_t<decltype(out[0])>> read(pixels * used);
            const bool ok = input->read_image(
                0, 0, 0, used, eightBit ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT,
                read.data());
            if (!ok) {
                const std::string reason = oneLine(input->geterror());
                throwBadInput(name + ": cannot read the pixels (" +
                              (reason.empty() ? "truncated or corrupt" : reason) + ")");
            }
            if (isFloat) refuseNonFinite(name, read, used, spec.width);
            out.resize(pixels * 4);
            for (std::size_t p = 0; p < pixels; ++p) {
                const auto* in = &read[p * used];
                const bool grey = used < 3;
                for (int c = 0; c < 3; ++c) out[4 * p + c] = in[grey ? 0 : c];
                out[4 * p + 3] = one;
            }
        };
        if (eightBit) {
            expand(albedo.bytes, static_cast<std::uint8_t>(255));
        } else {
            expand(albedo.linear, 1.0f);
            // Integer formats above 8 bits are display-referred like 8-bit ones: decode.
            if (!isFloat) {
                for (std::size_t k = 0; k < albedo.linear.size(); ++k)
                    if (k % 4 != 3) albedo.linear[k] = srgbToLinear(albedo.linear[k]);
            }
        }
        input->close();
        return albedo;
    } catch (const std::bad_alloc&) {
        throwRuntime(name + ": not enough memory for its " + std::to_string(spec.width) + " x " +
                     std::to_string(spec.height) + " pixels");
    }
}

}  // namespace microrelief
