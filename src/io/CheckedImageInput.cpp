#include "io/CheckedImageInput.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string_view>

#include "io/CutOffCheck.h"
#include "io/ExrCheck.h"
#include "io/PngCheck.h"
#include "microrelief/core/Error.h"
#include "microrelief/core/heightmap/HeightMap.h"

namespace microrelief {

void checkRegularFile(const std::filesystem::path& file, const std::string& name,
                      const std::string& what) {
    std::error_code ec;
    const std::filesystem::file_status status = std::filesystem::status(file, ec);
    if (status.type() == std::filesystem::file_type::not_found)
        throwBadInput(name + ": no such file");
    if (ec) throwBadInput(name + ": cannot read (" + ec.message() + ")");
    if (status.type() == std::filesystem::file_type::directory)
        throwBadInput(name + ": is a directory, not " + what);
    if (status.type() != std::filesystem::file_type::regular)
        throwBadInput(name + ": is not a regular file (a device, FIFO or socket); give " + what +
                      " file");
}

void checkSize(const std::string& name, long long width, long long height, int maxSide,
               const std::string& what, std::size_t maxSamples) {
    if (width <= 0 || height <= 0) throwBadInput(name + ": the image is empty (0 pixels)");
    if (width > maxSide || height > maxSide) {
        throwBadInput(name + ": " + std::to_string(width) + " x " + std::to_string(height) +
                      " is larger than the " + std::to_string(maxSide) + " x " +
                      std::to_string(maxSide) + " " + what + " may have");
    }
    const double samples = static_cast<double>(width) * static_cast<double>(height);
    if (maxSamples > 0 && samples > static_cast<double>(maxSamples)) {
        // What drawing them needs, rounded up to a GiB, and the memory available (the
        // bound's samples, kPagedBytesPerSample each), rounded down to a tenth of one.
        const auto gib = [](double count) {
            return count * static_cast<double>(kPagedBytesPerSample) / (1 << 30);
        };
        char available[32];
        std::snprintf(available, sizeof available, "%.1f",
                      std::floor(gib(static_cast<double>(maxSamples)) * 10.0) / 10.0);
        throw MapOverMemory(name + ": " + std::to_string(width) + " x " + std::to_string(height) +
                            " samples need about " +
                            std::to_string(static_cast<long long>(std::ceil(gib(samples)))) +
                            " GiB of memory to draw, more than the " + available +
                            " GiB available now");
    }
}

std::string oneLine(std::string text) {
    std::replace_if(
        text.begin(), text.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text;
}

std::unique_ptr<OIIO::ImageInput> openCheckedImage(const std::filesystem::path& file, int maxSide,
                                                   const std::string& what,
                                                   std::size_t maxSamples) {
    const std::string name = file.string();
    checkRegularFile(file, name);
    std::error_code error;
    if (std::filesystem::file_size(file, error) == 0 && !error)
        throwBadInput(name + ": the file is empty (0 bytes)");
    if (hasPngSignature(file)) {
        // The size first, from IHDR alone, then the structure (which inflates the data).
        std::string defect;
        const std::optional<PngHeader> header = readPngHeader(file, defect);
        if (!header) throwBadInput(name + ": not a valid PNG (" + defect + ")");
        checkSize(name, header->width, header->height, maxSide, what, maxSamples);
        if (const auto bad = pngStructureDefect(file))
            throwBadInput(name + ": not a valid PNG (" + *bad + ")");
    } else if (hasExrMagic(file)) {
        std::string defect;
        const auto parts = readExrHeader(file, defect);
        if (!parts) throwBadInput(name + ": not a valid OpenEXR file (" + defect + ")");
        for (const ExrPartSize& part : *parts)
            checkSize(name, part.width, part.height, maxSide, what, maxSamples);
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
        // Elevation models in GDAL's other formats: what is read instead, and how to get it
        // (a build without GDAL reads none).
        constexpr std::array<std::string_view, 9> kElevationExtensions = {
            ".asc", ".img", ".nc", ".dem", ".bil", ".vrt", ".grd", ".adf", ".xyz"};
        const bool elevation = MICRORELIEF_WITH_GDAL &&
                               std::find(kElevationExtensions.begin(), kElevationExtensions.end(),
                                         extension) != kElevationExtensions.end();
        throwBadInput(name + ": no image format OpenImageIO reads for the extension '" +
                      file.extension().string() + "'" +
                      (elevation ? "; elevation models are read as GeoTIFF (.tif) or SRTM .hgt: "
                                   "gdal_translate -of GTiff converts this one"
                                 : ""));
    }
    OIIO::ImageSpec opened;
    if (!input->open(name, opened)) {
        std::string reason = oneLine(input->geterror());
        if (reason.empty()) reason = "not a " + std::string(input->format_name()) + " file";
        throwBadInput(name + ": cannot read the image (" + reason + ")");
    }
    checkSize(name, input->spec().width, input->spec().height, maxSide, what, maxSamples);
    // A file cut off where its decoder would not say so (a TIFF's strips past its end are
    // read as they are, a JPEG's missing rows as grey): refused, not drawn.
    if (const std::optional<std::string> defect = cutOffDefect(file, input->format_name()))
        throwBadInput(name + ": cut off (" + *defect + ")");
    return input;
}

}  // namespace microrelief
