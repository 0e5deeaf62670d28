#include "microrelief/io/HeightMapFile.h"

#include <OpenImageIO/imageio.h>

#include <cctype>
#include <memory>
#include <optional>

#include "io/CheckedImageInput.h"
#if MICRORELIEF_WITH_GDAL
#include "io/DemFile.h"
#endif
#include "microrelief/core/Error.h"

namespace microrelief {

namespace {

HeightMap loadImage(const std::filesystem::path& file, const HeightMapLoadOptions& options) {
    const std::string name = file.string();
    const std::unique_ptr<OIIO::ImageInput> input =
        openCheckedImage(file, options.maxSide, "a height map", options.maxSamples);
    const OIIO::ImageSpec& spec = input->spec();
    if (spec.depth > 1) throwBadInput(name + ": volume images are not height maps");
    if (spec.nchannels > kMaxHeightMapChannels) {
        throwBadInput(name + ": " + std::to_string(spec.nchannels) + " channels, more than the " +
                      std::to_string(kMaxHeightMapChannels) + " a height map may have");
    }
    if (options.channel < 0 || options.channel >= spec.nchannels) {
        throwBadInput(name + ": {map.load.channel} " + std::to_string(options.channel) +
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

}  // namespace

bool readsGeoreferencedMaps() {
    return MICRORELIEF_WITH_GDAL != 0;
}

std::optional<Georeference> readMapGrid(const std::filesystem::path& file) {
#if MICRORELIEF_WITH_GDAL
    checkRegularFile(file, file.string());
    if (isElevationModelFile(file)) return demGrid(file);
#else
    (void)file;
#endif
    return std::nullopt;
}

HeightMapFile loadHeightMapFile(const std::filesystem::path& file,
                                const HeightMapLoadOptions& options) {
    // The elevation formats by extension: a .tif or .tiff is a DEM where it holds a GeoTIFF
    // grid, an .hgt file always.
    std::string extension = file.extension().string();
    for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    [[maybe_unused]] const bool tiff = extension == ".tif" || extension == ".tiff";  // GDAL only
#if MICRORELIEF_WITH_GDAL
    if (extension == ".hgt" || tiff) {
        checkRegularFile(file, file.string());
        if (!tiff || hasGeoTiffGrid(file)) {
            HeightMapFile dem = loadDem(file, options);
            prepareHeights(dem.map, options, file.string());  // in [0, 1] already
            return dem;
        }
    }
#else
    if (extension == ".hgt")
        throwBadInput(file.string() +
                      ": an elevation model; this build of microrelief reads them only with "
                      "GDAL (build with -DMICRORELIEF_WITH_GDAL=ON and libgdal-dev)");
#endif
    return {loadImage(file, options), std::nullopt, std::nullopt};  // no georeference, no placement
}

void saveElevationModel(const std::filesystem::path& file, const HeightMap& map,
                        const Georeference& geo, const GroundPlacement& placement) {
#if MICRORELIEF_WITH_GDAL
    writeDem(file, map, geo, placement);
#else
    (void)map, (void)geo, (void)placement;
    throwBadInput(file.string() +
                  ": an elevation model; this build of microrelief writes them only with GDAL "
                  "(build with -DMICRORELIEF_WITH_GDAL=ON and libgdal-dev)");
#endif
}

HeightMap loadHeightMap(const std::filesystem::path& file, const HeightMapLoadOptions& options) {
    return loadHeightMapFile(file, options).map;
}

}  // namespace microrelief
