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

std::optional<MapGround> mapGround(const ReliefFiles& loaded) {
    if (!loaded.georeference || !loaded.placement) return std::nullopt;
    return MapGround{*loaded.georeference, *loaded.placement};
}

void checkMapExtension(const std::filesystem::path& file) {
    checkReplaceable(file);  // a folder is named as one, not as a name without an extension
    const std::string extension = lowerExtension(file);
    if (extension != ".png" && extension != ".exr" && extension != ".tif" && extension != ".tiff")
        throwBadInput(file.string() +
                      ": a map is saved as .png (16 bits, heights 0 to 1), .exr (float) or, "
                      "from an elevation model, .tif (a GeoTIFF of metres on its grid)");
}

void checkMapSave(const std::filesystem::path& file, const std::optional<MapGround>& ground) {
    checkMapExtension(file);
    const std::string extension = lowerExtension(file);
    if ((extension == ".tif" || extension == ".tiff") && !ground)
        throwBadInput(file.string() +
                      ": a map is saved as a GeoTIFF only where it came from an elevation "
                      "model, whose grid on the ground it keeps; save this one as .png or .exr");
}

std::string saveHeightMap(const HeightMap& map, const std::filesystem::path& file,
                          const std::optional<MapGround>& ground) {
    checkMapSave(file, ground);
    const std::string extension = lowerExtension(file);
    if (extension == ".tif" || extension == ".tiff") {
        saveElevationModel(file, map, ground->georeference, ground->placement);
        return {};
    }
    // What a PNG or an OpenEXR of the samples does not keep of a DEM's map.
    const std::string dropped =
        ground ? file.string() +
                     ": saved without the elevation model's georeference (where it lies, and "
                     "the metres its heights 0 to 1 stand for); save as .tif to keep it"
               : std::string();
    if (extension == ".exr") {
        writeImageAtomically(
            file, {map.width, map.height, 1, PixelType::Float, map.samples.data(), {"Y"}});
        return dropped;
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
    return dropped;
}

}  // namespace microrelief
