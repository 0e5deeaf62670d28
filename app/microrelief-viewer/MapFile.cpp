#include "MapFile.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "microrelief/core/Error.h"
#include "microrelief/io/AtomicFile.h"
#include "microrelief/io/ImageFile.h"

namespace microrelief {

namespace {

std::string lowerExtension(const std::filesystem::path& file) {
    std::string extension = file.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return extension;
}

}  // namespace

void checkMapExtension(const std::filesystem::path& file) {
    checkReplaceable(file);  // a folder is named as one, not as a name without an extension
    const std::string extension = lowerExtension(file);
    if (extension != ".png" && extension != ".exr")
        throwBadInput(file.string() +
                      ": a map is saved as .png (16 bits, heights 0 to 1) or .exr (float)");
}

void saveHeightMap(const HeightMap& map, const std::filesystem::path& file) {
    checkMapExtension(file);
    if (lowerExtension(file) == ".exr") {
        writeImageAtomically(
            file, {map.width, map.height, 1, PixelType::Float, map.samples.data(), {"Y"}});
        return;
    }
    const float highest = map.maxValue();
    if (highest > 1.0f) {
        throwBadInput(file.string() + ": heights reach " + std::to_string(highest) +
                      ", above the 1.0 a 16-bit PNG holds; save as .exr to keep them");
    }
    std::vector<std::uint16_t> levels(map.samples.size());
    std::transform(map.samples.begin(), map.samples.end(), levels.begin(), [](float h) {
        return static_cast<std::uint16_t>(std::lround(std::clamp(h, 0.0f, 1.0f) * 65535.0f));
    });
    writeImageAtomically(file, {map.width, map.height, 1, PixelType::UInt16, levels.data(), {}});
}

}  // namespace microrelief
